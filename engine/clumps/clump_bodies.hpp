// The rigid clumps of a running simulation: each body's translation (velocity Verlet) and rotation
// (rigid_rotation.hpp), driven by the sum of its member spheres' contact forces. The members stay
// particles for contact detection and the force laws; each step their position, velocity and spin
// are set from their body, and contacts between members of one body are never listed.
#pragma once

#include <vector>

#include "clumps/rigid_rotation.hpp"
#include "core/particles.hpp"
#include "core/scene.hpp"

namespace dem {

struct ClumpBodies {
  std::vector<Vec3> x, v;  // centroid and its velocity
  std::vector<RigidRotation> rotation;
  std::vector<double> mass;
  std::vector<Vec3> moments;        // principal, body frame
  std::vector<Vec3> force, torque;  // of the last force evaluation (space frame)
  // Each body's members in particle order: members[member_start[b]] .. members[member_start[b + 1] - 1]
  // (index_members). Kept between steps, so a step does not sort the members again; a re-sort of the
  // particles rebuilds it.
  std::vector<int> member_start, members;
  // What each body's members take from it in a drift or a kick (written for every body, then read by
  // the members in particle order: drift_bodies, kick_bodies). Scratch of one pass, never saved.
  struct Motion {
    Eigen::Matrix3d to_space;  // the orientation's matrix (drift only)
    Vec3 centre, velocity, spin;
    Vec3 kick, spin_kick;  // of the first half kick (drift only)
  };
  std::vector<Motion> motion;

  bool empty() const { return x.empty(); }
  std::size_t size() const { return x.size(); }
};

ClumpBodies make_bodies(const Scene& scene);

// Member particles (whose indices follow the scene's until the first re-sort): body index, offset
// in the body frame, and the body's mass (the contact laws' damping and the time step see a member
// as the whole body).
void mark_members(const Scene& scene, ClumpBodies& bodies, Particles& p);

// Lists each body's members in particle order (a counting sort over p.body). Call it whenever the
// particles' order changes (mark_members, a re-sort, a state read); inserting free spheres at the end
// leaves it valid.
void index_members(ClumpBodies& bodies, const Particles& p);

// The first half kick and the drift of every body, then its members placed; returns the largest
// squared move of a member since `x_at_build` (for the neighbour-list rebuild). A member's kicks
// (`half_kick`, `spin_kick`: the velocity and spin changes of the half kick, which the dashpots
// add to predict the full-step velocities) are its body's at its place.
double drift_bodies(ClumpBodies& bodies, Particles& p, const std::vector<Vec3>& x_at_build, double dt,
                    std::vector<Vec3>& half_kick, std::vector<Vec3>& spin_kick);

// Sums the members' forces and torques (the force kernel added gravity to each member as if it had
// the body's mass: that is taken out and the body's weight put in once), then the second half
// kick, then the members' velocities and spins. dt = 0 only sums. local_damping (numerics.localDamping,
// Cundall's): each component of the body's force and torque loses local_damping times its size
// against the body's velocity and spin, as a sphere's does in the force kernel.
void kick_bodies(ClumpBodies& bodies, Particles& p, const Vec3& gravity, double dt, double local_damping = 0);

double bodies_kinetic_energy(const ClumpBodies& bodies);
double bodies_rotational_energy(const ClumpBodies& bodies);
double bodies_translational_energy(const ClumpBodies& bodies);

}  // namespace dem
