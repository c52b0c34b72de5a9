// Local damping without branches (core/local_damping.hpp) against the form with them, bit for bit:
// velocities of both signs, +0 and -0, forces of both signs, zero and huge.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "core/local_damping.hpp"

namespace dem::test::test_local_damping {
namespace {

double branchy(double f, double v, double alpha) {
  if (v != 0) f -= alpha * std::abs(f) * (v > 0 ? 1 : -1);
  return f;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(LocalDamping, IsTheBranchingFormBitForBit) {
  const double tiny = std::numeric_limits<double>::denorm_min(), huge = std::numeric_limits<double>::max();
  const double values[] = {0.0, -0.0, tiny, -tiny, 1e-300, -3.5, 2.0, 1e300, -huge, huge, 0.1, -7e-5};
  for (const double alpha : {0.0, 0.3, 0.7, 1.0})
    for (const double f : values)
      for (const double v : values) {
        Vec3 force(f, -f, f), velocity(v, -v, 0.0);
        damp_locally(force, velocity, alpha);
        EXPECT_TRUE(same_bits(force.x(), branchy(f, v, alpha))) << "f " << f << " v " << v << " alpha " << alpha;
        EXPECT_TRUE(same_bits(force.y(), branchy(-f, -v, alpha))) << "f " << -f << " v " << -v << " alpha " << alpha;
        EXPECT_TRUE(same_bits(force.z(), f)) << "no velocity, no damping: f " << f;
      }
}

TEST(LocalDamping, TakesAlphaOfTheForceAgainstTheVelocity) {
  Vec3 force(10, -10, 4), velocity(1, 1, -2);
  damp_locally(force, velocity, 0.3);
  EXPECT_NEAR(force.x(), 7, 1e-14);    // 10 loses 3 against +v
  EXPECT_NEAR(force.y(), -13, 1e-14);  // -10 grows by 3 against +v
  EXPECT_NEAR(force.z(), 5.2, 1e-14);  // 4 grows by 1.2 against -v
}

}  // namespace
}  // namespace dem::test::test_local_damping
