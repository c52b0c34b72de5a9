// A 2D run (Scene::plane): discs in the x-z plane against closed forms. A disc rolls down a slope at
// 2/3 g sin(theta) (a sphere at 5/7), a resting disc weighs rho pi r^2 t g, an elastic gas of discs keeps its
// energy and stays exactly in the plane, and a source fills a box at its mass rate with discs' masses.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include <sstream>

#include "sim/runner.hpp"
#include "sim/state_io.hpp"
#include "support/scenes.hpp"

namespace dem::test::test_plane_2d {
namespace {

constexpr double kG = 9.81;
constexpr double kDensity = 2500;
constexpr double kThickness = 0.01;

Scene planar_scene(double restitution, double friction) {
  Scene s = base_scene(HertzNormal::kName, kDensity, 1e8, 0.25, restitution, friction);
  s.plane = Scene::Plane{kThickness};
  return s;
}

// Its acceleration down a slope of angle theta (gravity tilted, the floor z = 0), rolling from rest,
// measured between 0.1 s and 0.3 s, and its spin over its speed times its radius at 0.3 s.
std::pair<double, double> rolling(bool disc, double theta) {
  Scene s = planar_scene(0.5, 0.5);
  if (!disc) s.plane.reset();
  s.gravity = kG * Vec3(std::sin(theta), 0, -std::cos(theta));
  s.walls.push_back(plane(Vec3::Zero(), Vec3::UnitZ(), "slope"));
  const double r = 0.01;
  s.particles.push_back(sphere(Vec3(0, 0, r), r));
  s.time.steps = 0;
  s.time.duration = 0.3;
  Simulation sim(std::move(s));
  step_until(sim, 1 << 30, [](const Simulation& m) { return m.time() >= 0.1 - 1e-12; });
  const double t1 = sim.time(), v1 = sim.particles().v[0].x();
  step_until(sim, 1 << 30, [](const Simulation& m) { return m.time() >= 0.3 - 1e-12; });
  const double a = (sim.particles().v[0].x() - v1) / (sim.time() - t1);
  return {a, sim.particles().w[0].y() * r / sim.particles().v[0].x()};
}

TEST(Plane2D, ADiscRollsDownASlopeAtTwoThirdsOfGSinTheta) {
  const double theta = 20 * std::numbers::pi / 180;  // tan(theta) / 3 = 0.12 < mu: it rolls without slipping
  const auto [a_disc, spin_disc] = rolling(true, theta);
  EXPECT_NEAR(a_disc / (2.0 / 3.0 * kG * std::sin(theta)), 1, 2e-3);
  EXPECT_NEAR(spin_disc, 1, 2e-3);  // w = v / r about +y: rolling towards +x on a floor below
  const auto [a_sphere, spin_sphere] = rolling(false, theta);  // the same scene in 3D: a sphere
  EXPECT_NEAR(a_sphere / (5.0 / 7.0 * kG * std::sin(theta)), 1, 2e-3);
}

TEST(Plane2D, ARestingDiscWeighsRhoPiRSquaredTimesItsThicknessTimesG) {
  Scene s = planar_scene(0.1, 0.5);
  s.gravity = {0, 0, -kG};
  s.walls.push_back(plane(Vec3::Zero(), Vec3::UnitZ(), "floor"));
  const double r = 0.01;
  s.particles.push_back(sphere(Vec3(0, 0, r), r));
  s.time.steps = 0;
  s.time.duration = 0.2;
  Simulation sim(std::move(s));
  ASSERT_TRUE(run(sim, {}).ok);
  const double weight = kDensity * std::numbers::pi * r * r * kThickness * kG;
  EXPECT_NEAR(-sim.boundary_loads()[0].force.z() / weight, 1, 1e-6);
  EXPECT_EQ(sim.particles().mass[0], kDensity * std::numbers::pi * r * r * kThickness);
}

// A reviewer's find: the energies counted a disc's spin with a sphere's inertia (2/5 m r^2), so a lossless rolling
// disc seemed to lose 7% of its fall, and a spinning disc bouncing without loss was stopped as unstable.
TEST(Plane2D, ASpinningDiscHoldsHalfOfHalfMRSquaredOmegaSquared) {
  Scene s = planar_scene(1.0, 0.0);
  const double r = 0.1, w = 10;
  s.particles.push_back(sphere(Vec3::Zero(), r, Vec3::Zero(), Vec3(0, w, 0)));
  Simulation sim(std::move(s));
  const double m = kDensity * std::numbers::pi * r * r * kThickness;
  EXPECT_NEAR(sim.rotational_energy(), 0.5 * (0.5 * m * r * r) * w * w, 1e-15);
  EXPECT_NEAR(sim.kinetic_energy(), 0.5 * (0.5 * m * r * r) * w * w, 1e-15);
}

// A reviewer's find: a state saved by a 3D run continued under a 2D spec (or the other way, or with another disc
// thickness) ran on with the saved masses, a sphere left off the plane.
TEST(Plane2D, AStateSavedWithAnotherDimensionOrThicknessIsRefused) {
  auto scene = [](std::optional<double> thickness) {
    Scene s = planar_scene(0.5, 0.5);
    s.plane.reset();
    if (thickness) s.plane = Scene::Plane{*thickness};
    s.gravity = {0, 0, -kG};
    s.time.dt = 1e-5;
    s.time.steps = 100;
    s.walls.push_back(plane(Vec3::Zero(), Vec3::UnitZ(), "floor"));
    s.particles.push_back(sphere(Vec3(0, 0, 0.02), 0.01));
    return s;
  };
  auto saved = [&](std::optional<double> thickness) {
    Simulation sim(scene(thickness));
    for (int k = 0; k < 10; ++k) sim.step();
    std::stringstream state;
    StateIO::write(sim, state);
    return state.str();
  };
  auto continued = [&](const std::string& state, std::optional<double> thickness) -> std::string {
    Simulation sim(scene(thickness));
    std::istringstream in(state);
    try {
      StateIO::read(sim, in);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(continued(saved(0.01), 0.01), "");
  EXPECT_EQ(continued(saved(std::nullopt), std::nullopt), "");
  const std::string problem = continued(saved(std::nullopt), 0.01);
  EXPECT_NE(problem.find("the saved state does not belong to this spec: particle 1 weighs 0.010472 kg there, and "
                         "0.00785398 kg as the spec's disc of its radius: the spec's dimension, discThickness or "
                         "density is not the one the state was saved with"),
            std::string::npos)
      << problem;
  EXPECT_NE(continued(saved(0.01), std::nullopt).find("as the spec's sphere of its radius"), std::string::npos);
  EXPECT_NE(continued(saved(0.01), 0.02).find("does not belong to this spec"), std::string::npos);
}

// Discs with random velocities in the plane, bouncing off each other and four walls, without damping or friction.
TEST(Plane2D, AnElasticGasOfDiscsKeepsItsEnergyAndNeverLeavesThePlane) {
  Scene s = planar_scene(1.0, 0.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> speed(-1, 1);
  const double box = 0.2, r = 0.006;
  for (int i = 0; i < 10; ++i)
    for (int k = 0; k < 10; ++k)
      s.particles.push_back(sphere(Vec3((i + 0.5) * box / 10, 0, (k + 0.5) * box / 10), r * (0.6 + 0.04 * k),
                                   Vec3(speed(rng), 0, speed(rng))));
  for (int d : {0, 2}) {
    Vec3 n = Vec3::Zero();
    n[d] = 1;
    s.walls.push_back(plane(Vec3::Zero(), n));
    s.walls.push_back(plane(n * box, -n));
  }
  s.time.steps = 0;
  s.time.duration = 1.0;
  Simulation sim(std::move(s));
  const double start = sim.mechanical_energy();
  ASSERT_TRUE(run(sim, {}).ok);
  EXPECT_NEAR(sim.mechanical_energy() / start, 1, 1e-3);
  const Particles& p = sim.particles();
  for (std::size_t i = 0; i < p.size(); ++i) {
    ASSERT_EQ(p.x[i].y(), 0);
    ASSERT_EQ(p.v[i].y(), 0);
    ASSERT_EQ(p.w[i].x(), 0);
    ASSERT_EQ(p.w[i].z(), 0);
  }
}

TEST(Plane2D, ASourceFillsABoxAtItsMassRateWithDiscs) {
  Scene s = planar_scene(0.3, 0.5);
  s.gravity = {0, 0, -kG};
  s.walls.push_back(plane(Vec3::Zero(), Vec3::UnitZ(), "floor"));
  s.walls.push_back(plane(Vec3(-0.05, 0, 0), Vec3::UnitX(), "left"));
  s.walls.push_back(plane(Vec3(0.05, 0, 0), -Vec3::UnitX(), "right"));
  ParticleSource sand;
  sand.box = Box{{-0.05, -1, 0.25}, {0.05, 1, 0.3}};  // its y range is not used: discs enter at y = 0
  sand.sizes.kind = SizeKind::Uniform;
  sand.sizes.d_min = 0.004;
  sand.sizes.d_max = 0.006;
  sand.mass_rate = 0.05;
  sand.velocity = {0, 0, -1};
  s.sources.push_back(sand);
  s.time.steps = 0;
  s.time.duration = 0.4;
  Simulation sim(std::move(s));
  ASSERT_TRUE(run(sim, {}).ok);
  const Particles& p = sim.particles();
  double mass = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_EQ(p.x[i].y(), 0);
    EXPECT_EQ(p.mass[i], kDensity * std::numbers::pi * p.radius[i] * p.radius[i] * kThickness);
    mass += p.mass[i];
  }
  EXPECT_GT(p.size(), 20u);
  const double largest = kDensity * std::numbers::pi * 0.003 * 0.003 * kThickness;
  EXPECT_NEAR(mass, 0.05 * sim.time(), 0.5 * largest);
}

}  // namespace
}  // namespace dem::test::test_plane_2d
