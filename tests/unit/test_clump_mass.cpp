// Mass properties of clumps (unions of overlapping spheres) by adaptive subdivision, against closed
// forms: the issue's two-sphere clump, a single sphere, disjoint spheres, a sphere inside another.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <numbers>

#include "clumps/mass_properties.hpp"

namespace dem {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(ClumpMass, TwoUnitSpheresOneApartAsInTheIssue) {
  // volume 2 (4 pi / 3) - the lens pi (4r + d)(2r - d)^2 / 12 = 9 pi / 4; the moments are the issue's
  const MassProperties p = union_mass_properties({{Vec3(-0.5, 0, 0), 1}, {Vec3(0.5, 0, 0), 1}});
  EXPECT_NEAR(p.volume, 9 * kPi / 4, 1e-3 * 9 * kPi / 4);
  EXPECT_NEAR(p.volume, 7.0685835, 7e-4);
  EXPECT_NEAR(p.principal_moments[0], 3.0041480, 3e-4);  // about the axis (x), the smallest
  EXPECT_NEAR(p.principal_moments[1], 5.2130803, 5e-4);
  EXPECT_NEAR(p.principal_moments[2], 5.2130803, 5e-4);
  EXPECT_NEAR(std::abs(p.principal_axes(0, 0)), 1.0, 1e-9);  // its axis is the line of centres
  EXPECT_LT(p.centroid.norm(), 1e-9);
  std::printf("two spheres: volume %.7f, moments %.7f %.7f %.7f, last change %.1e\n", p.volume, p.principal_moments[0],
              p.principal_moments[1], p.principal_moments[2], p.relative_accuracy);
}

TEST(ClumpMass, OneSphereIsExact) {
  const MassProperties p = union_mass_properties({{Vec3(1, 2, 3), 0.5}});
  const double volume = 4 * kPi / 3 * 0.125, moment = 0.4 * volume * 0.25;
  EXPECT_NEAR(p.volume, volume, 1e-4 * volume);
  EXPECT_NEAR((p.centroid - Vec3(1, 2, 3)).norm(), 0, 1e-9);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(p.principal_moments[k], moment, 1e-4 * moment);
}

TEST(ClumpMass, DisjointSpheresAddAndASphereInsideAnotherAddsNothing) {
  const double r = 0.3, d = 2.0;  // two spheres far apart: parallel axis theorem across the line
  const MassProperties apart = union_mass_properties({{Vec3(0, 0, -d / 2), r}, {Vec3(0, 0, d / 2), r}});
  const double v1 = 4 * kPi / 3 * r * r * r;
  EXPECT_NEAR(apart.volume, 2 * v1, 1e-4 * 2 * v1);
  EXPECT_NEAR(apart.principal_moments[2], 2 * (0.4 * v1 * r * r + v1 * d * d / 4), 1e-4 * apart.principal_moments[2]);
  const MassProperties nested = union_mass_properties({{Vec3::Zero(), 1.0}, {Vec3(0.2, 0.1, 0), 0.5}});
  EXPECT_NEAR(nested.volume, 4 * kPi / 3, 1e-4 * 4 * kPi / 3);
}

TEST(ClumpMass, TheAxesAreARightHandedRotationOrderedByMoment) {
  const MassProperties p = union_mass_properties({{Vec3(0, 0, 0), 1}, {Vec3(1, 1, 0), 0.7}, {Vec3(0, 1.2, 0.8), 0.6}});
  EXPECT_NEAR(p.principal_axes.determinant(), 1.0, 1e-9);
  EXPECT_LE(p.principal_moments[0], p.principal_moments[1]);
  EXPECT_LE(p.principal_moments[1], p.principal_moments[2]);
  const Eigen::Matrix3d diagonal = p.principal_axes.transpose() * p.inertia * p.principal_axes;
  EXPECT_NEAR(diagonal(0, 1), 0, 1e-9 * p.principal_moments[2]);
  EXPECT_NEAR(diagonal(1, 2), 0, 1e-9 * p.principal_moments[2]);
}

// Long and sparse shapes meet the accuracy asked as compact ones do (the subdivision's depth counts
// from cells about a sphere's size, not from the whole shape's box): a rod of 150 spheres whose
// neighbours overlap (the union's volume in closed form: the spheres less a lens per neighbour pair),
// and two spheres 1,000 radii apart.
TEST(ClumpMass, LongAndSparseShapesMeetTheAccuracyAsked) {
  const double r = 0.01, d = 0.012, accuracy = 1e-4;
  std::vector<MemberSphere> rod;
  for (int k = 0; k < 150; ++k) rod.push_back({Vec3(d * k, 0, 0), r});
  const double sphere = 4 * kPi / 3 * r * r * r, lens = kPi * (4 * r + d) * (2 * r - d) * (2 * r - d) / 12;
  const double rod_volume = 150 * sphere - 149 * lens;
  const MassProperties long_one = union_mass_properties(rod, accuracy);
  std::printf("rod of 150: volume error %.2e\n", long_one.volume / rod_volume - 1);
  EXPECT_NEAR(long_one.volume, rod_volume, accuracy * rod_volume);
  const double apart = 1000 * r;
  const MassProperties sparse = union_mass_properties({{Vec3::Zero(), r}, {Vec3(apart, 0, 0), r}}, accuracy);
  const double across = 2 * (0.4 * sphere * r * r + sphere * apart * apart / 4);
  std::printf("two spheres 1,000 radii apart: volume error %.2e, moment error %.2e\n", sparse.volume / (2 * sphere) - 1,
              sparse.principal_moments[2] / across - 1);
  EXPECT_NEAR(sparse.volume, 2 * sphere, accuracy * 2 * sphere);
  EXPECT_NEAR(sparse.principal_moments[2], across, accuracy * across);
}

// A shape of many spheres is integrated in about the time of its spheres, not of their number
// squared (each cell is tested against the spheres near it only): 2,000 spheres at 1e-4.
TEST(ClumpMass, ManySpheresAreIntegratedInSeconds) {
  std::vector<MemberSphere> cloud;
  for (int k = 0; k < 2000; ++k)  // a lumpy blob, deterministic
    cloud.push_back(
        {Vec3(std::sin(1.3 * k), std::cos(0.7 * k), std::sin(0.31 * k + 1)) * 0.9, 0.08 + 0.04 * std::cos(k)});
  const auto start = std::chrono::steady_clock::now();
  const MassProperties p = union_mass_properties(cloud, 1e-4);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("2,000 spheres at 1e-4: %.2f s, volume %.6f, last change %.1e\n", seconds, p.volume, p.relative_accuracy);
  EXPECT_LT(p.relative_accuracy, 1e-4);
  EXPECT_LT(seconds, 20.0);  // a sanity bound for the sanitized and busy machines, not a benchmark
}

// A shape asked again (a study's runs build the same stones) is not integrated again and gets the
// same bits; a shape one bit apart, or the same at another accuracy, is integrated.
TEST(ClumpMass, AShapeAskedAgainIsNotIntegratedAgain) {
  const std::vector<MemberSphere> stone{{Vec3::Zero(), 1.0}, {Vec3(0.9, 0.3, -0.2), 0.7}, {Vec3(-0.4, 0.8, 0.5), 0.6}};
  const std::uint64_t before = union_mass_property_integrations();
  const MassProperties first = union_mass_properties(stone, 1e-3);
  const MassProperties again = union_mass_properties(stone, 1e-3);
  EXPECT_EQ(union_mass_property_integrations() - before, 1u);
  EXPECT_EQ(first.volume, again.volume);
  EXPECT_EQ(first.centroid, again.centroid);
  EXPECT_EQ(first.inertia, again.inertia);
  EXPECT_EQ(first.principal_moments, again.principal_moments);
  EXPECT_EQ(first.principal_axes, again.principal_axes);
  EXPECT_EQ(first.relative_accuracy, again.relative_accuracy);
  std::vector<MemberSphere> apart = stone;
  apart[2].radius = std::nextafter(apart[2].radius, 1.0);
  const MassProperties other = union_mass_properties(apart, 1e-3);
  union_mass_properties(stone, 1e-4);
  EXPECT_EQ(union_mass_property_integrations() - before, 3u);
  EXPECT_GT(other.volume, 0.0);
}

TEST(ClumpMass, BadSpheresAreRefused) {
  EXPECT_THROW(union_mass_properties({}), std::invalid_argument);
  EXPECT_THROW(union_mass_properties({{Vec3::Zero(), -1}}), std::invalid_argument);
}

}  // namespace
}  // namespace dem
