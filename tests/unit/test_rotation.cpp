// The rotation helpers against closed forms: a bond's turn (the rotation vector) at every angle, and
// a clump's free rotation on both sides of the angle where its small-angle series hands over to libm,
// and four bodies' rotations at once against one at a time.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "clumps/rigid_rotation.hpp"
#include "core/rotation.hpp"

namespace dem::test::test_rotation {
namespace {

// The rotation vector of a unit quaternion in long double (atan2 at any angle): the reference.
Vec3 reference_rotation_vector(const Quat& q) {
  const long double sign = q.w() < 0 ? -1 : 1, x = sign * q.x(), y = sign * q.y(), z = sign * q.z(), c = sign * q.w();
  const long double s = std::sqrt(x * x + y * y + z * z);
  if (s == 0) return Vec3::Zero();
  const long double k = 2 * std::atan2(s, c) / s;
  return Vec3(static_cast<double>(k * x), static_cast<double>(k * y), static_cast<double>(k * z));
}

TEST(RotationVector, IsTheAtan2FormToRoundOffAtEveryAngle) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n(0, 1);
  // tiny to nearly pi, and about 2 atan(1/64), where a small-angle series would hand over
  const double handover = 2 * std::atan(1.0 / 64);
  double worst = 0;
  for (const double angle : {1e-300, 1e-12, 1e-6, 1e-3, 0.99 * handover, 0.999999 * handover, handover,
                             1.000001 * handover, 1.01 * handover, 0.5, 2.0, 3.1}) {
    for (int k = 0; k < 200; ++k) {
      const Vec3 axis = Vec3(n(rng), n(rng), n(rng)).normalized();
      const Quat q = Quat(Eigen::AngleAxisd(angle, axis)).normalized();
      for (const Quat& turn : {q, Quat(-q.w(), -q.x(), -q.y(), -q.z())}) {  // q and -q: one rotation
        const Vec3 want = reference_rotation_vector(turn), got = rotation_vector(turn);
        worst = std::max(worst, (got - want).norm() / want.norm());
      }
    }
  }
  std::printf("rotation_vector's largest relative error: %.2e\n", worst);
  EXPECT_LT(worst, 5e-16);
  EXPECT_EQ(rotation_vector(Quat::Identity()), Vec3::Zero());
}

// A body spinning about one principal axis turns about it at L / I, whatever the other moments:
// after n steps its angle is n dt L / I. At per-step angles on both sides of the free rotation's
// small-angle series (half-angle 1/64) and far below it.
TEST(RigidRotation, ASpinAboutAPrincipalAxisTurnsAtLOverIOnBothSidesOfTheSeries) {
  const Vec3 moments(2.0, 3.0, 5.0);
  for (const double per_step : {1e-7, 2.0 / 64 * 0.999, 2.0 / 64 * 1.001, 0.2}) {
    RigidRotation body;
    const double dt = 1e-3;
    body.angular_momentum = Vec3(0, 0, moments.z() * per_step / dt);
    const int steps = 100;
    for (int k = 0; k < steps; ++k) rotate_free(body, moments, dt);
    const double want = std::remainder(steps * per_step, 2 * std::numbers::pi);
    const Eigen::AngleAxisd turned(body.orientation);
    const double got = turned.angle() * (turned.axis().z() < 0 ? -1 : 1);
    EXPECT_NEAR(got, want, 1e-13 * std::max(1.0, std::abs(want))) << "per step " << per_step;
    EXPECT_NEAR(std::abs(turned.axis().z()), 1, 1e-12) << "per step " << per_step;
  }
}

// The bodies' rotations four at a time (drift_bodies) are the bits of rotate_free on each: seven
// bodies (a group of four and three alone), tumbling at random with a few turning past the small-angle
// series' handover in a step, over 50 steps.
TEST(RigidRotation, FourBodiesAtOnceTurnToTheBitsOfOneAtATime) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> n(0, 1);
  std::uniform_real_distribution<double> u(0.5, 3);
  const int count = 7;
  std::vector<RigidRotation> alone(count);
  std::vector<Vec3> moments(count);
  for (int j = 0; j < count; ++j) {
    moments[j] = Vec3(u(rng), u(rng), u(rng));
    alone[j].orientation = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
    // bodies 1 and 5 turn by more than 2/64 rad a step about some axis: libm's sin and cos
    alone[j].angular_momentum = Vec3(n(rng), n(rng), n(rng)) * ((j == 1 || j == 5) ? 100.0 : 1.0);
  }
  std::vector<RigidRotation> grouped = alone;
  std::vector<RigidRotation*> bodies;
  std::vector<const Vec3*> body_moments;
  for (int j = 0; j < count; ++j) bodies.push_back(&grouped[j]), body_moments.push_back(&moments[j]);
  const double dt = 1e-3;
  for (int step = 0; step < 50; ++step) {
    for (int j = 0; j < count; ++j) rotate_free(alone[j], moments[j], dt);
    rotate_free(bodies.data(), body_moments.data(), count, dt);
  }
  for (int j = 0; j < count; ++j) {
    EXPECT_EQ(alone[j].orientation.coeffs(), grouped[j].orientation.coeffs()) << "body " << j;
    EXPECT_EQ(alone[j].angular_momentum, grouped[j].angular_momentum) << "body " << j;
  }
}

}  // namespace
}  // namespace dem::test::test_rotation
