// Rotation of a rigid body with three different principal moments (a clump), by the symplectic
// splitting of Dullweber, Leimkuhler & McLachlan (J. Chem. Phys. 107, 5840, 1997; "NO_SQUISH" of
// Miller et al., J. Chem. Phys. 116, 8649, 2002): the free-body flow is split into rotations about
// the three principal axes, each solved exactly, in the symmetric sequence 1 2 3 2 1. Every sub-step
// is an exact rotation, so the angular momentum in the space frame is kept to round-off and the
// energy error stays bounded (second order in the step), with no drift over long runs. The sphere
// update (omega += dt T / I) would be wrong for such a body: it ignores omega x (I omega).
#pragma once

#include <Eigen/Geometry>

#include "core/vec.hpp"

namespace dem {

struct RigidRotation {
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // body frame -> space frame
  Vec3 angular_momentum = Vec3::Zero();                             // space frame
};

// Advances the free rotation by dt (no torque). `moments`: principal moments of inertia, in the body
// frame whose axes are the principal axes.
void rotate_free(RigidRotation& body, const Vec3& moments, double dt);

// The same for `count` bodies (bodies[j] with moments[j]), kRotationLanes at a time: the same bits as
// rotate_free on each, in a quarter of the time (a body's turns are a chain the processor waits on).
inline constexpr int kRotationLanes = 4;
void rotate_free(RigidRotation* const bodies[], const Vec3* const moments[], int count, double dt);

// One step with a torque constant over the step (space frame): half a kick of the angular momentum,
// the free rotation, the other half kick (velocity Verlet for rotation).
void rotate_with_torque(RigidRotation& body, const Vec3& moments, const Vec3& torque, double dt);

// The angular velocity in the space frame.
Vec3 angular_velocity(const RigidRotation& body, const Vec3& moments);

// The same from the orientation's rotation matrix (to_space: body frame -> space frame) and the
// inverse principal moments, for a loop that turns several vectors with one orientation (a matrix
// turns a vector in half the work of a quaternion, and a product costs less than a division).
Vec3 angular_velocity(const Eigen::Matrix3d& to_space, const Vec3& angular_momentum, const Vec3& inverse_moments);

// Kinetic energy of the rotation, L . omega / 2.
double rotational_energy(const RigidRotation& body, const Vec3& moments);

}  // namespace dem
