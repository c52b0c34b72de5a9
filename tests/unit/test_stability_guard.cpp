// The stability guard stops a run that went unstable with a message naming the step, the particle
// and the likely cause, and the frames written before the stop stay readable.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>

#include "legacy/legacy_formats.hpp"
#include "output/legacy_output.hpp"
#include "output/run_writers.hpp"
#include "sim/stability_guard.hpp"
#include "spec/spec_loader.hpp"
#include "support/scenes.hpp"

namespace dem::test {
namespace {

// Two spheres pressed together by 1% of the radius, at rest, elastic, no gravity.
Scene pressed_pair() {
  Scene s = base_scene(LinearNormal::kName, 2500, 0, 0.25, 1.0, 0.0, 1e4);
  s.particles.push_back(sphere({-0.0099, 0, 0}, 0.01));
  s.particles.push_back(sphere({0.0099, 0, 0}, 0.01));
  s.time.steps = 2000;
  s.outputs.every_steps = 1;
  s.outputs.animation = true;
  s.numerics.check_interval = 1;
  return s;
}

struct Stopped {
  RunOutcome outcome;
  legacy::ReadResult<legacy::AnimationFrame> frames;
};

Stopped run_with_file(Scene s) {
  Simulation sim(std::move(s));
  const auto path = std::filesystem::temp_directory_path() / ("dem_guard_" + std::to_string(::getpid()) + ".dat");
  Stopped out;
  {
    AnimationWriter writer(path.string(), sim);
    out.outcome = run(sim, {&writer});
  }
  std::ifstream in(path, std::ios::binary);
  out.frames = legacy::read_animation(in);
  std::filesystem::remove(path);
  return out;
}

TEST(StabilityGuard, EnergyGrowingWithoutSourceStopsTheRun) {
  // a sphere resting on a rigid floor under gravity, so the contact lasts
  Scene s = pressed_pair();
  s.particles.resize(1);
  s.particles[0].position = {0, 0, 0.0099};
  s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}));
  s.gravity = {0, 0, -9.81};
  // velocity Verlet is unstable past dt = 2 / omega; omega^2 = K_n / m with K_n = 2 k (rigid wall)
  s.time.dt = 2.02 * std::sqrt(sphere_mass(2500, 0.01) / 2e4);
  s.time.allow_unstable_dt = true;
  s.numerics.max_overlap_fraction = 1.0;  // let the energy check trip first
  const Stopped r = run_with_file(s);
  ASSERT_FALSE(r.outcome.ok);
  EXPECT_NE(r.outcome.error.find("energy grew"), std::string::npos) << r.outcome.error;
  EXPECT_NE(r.outcome.error.find("at step"), std::string::npos) << r.outcome.error;
  EXPECT_NE(r.outcome.error.find("particle "), std::string::npos) << r.outcome.error;
  EXPECT_NE(r.outcome.error.find("time step"), std::string::npos) << r.outcome.error;
  EXPECT_GT(r.outcome.steps, 1);  // it grew for a while before the guard saw it
  EXPECT_LT(r.outcome.steps, 2000);
  // every frame before the stop is in the file, whole (the failed step writes none)
  EXPECT_FALSE(r.frames.truncated) << r.frames.problem;
  EXPECT_EQ(static_cast<std::int64_t>(r.frames.frames.size()), r.outcome.steps);
}

TEST(StabilityGuard, OverlapBeyondTheLimitStopsTheRun) {
  Scene s = pressed_pair();
  // a fast head-on approach into a soft contact: the overlap passes a quarter of the radius
  s.particles[0].velocity = {5, 0, 0};
  s.particles[1].velocity = {-5, 0, 0};
  const Stopped r = run_with_file(s);
  ASSERT_FALSE(r.outcome.ok);
  EXPECT_NE(r.outcome.error.find("overlap of"), std::string::npos) << r.outcome.error;
  EXPECT_NE(r.outcome.error.find("stiffness"), std::string::npos) << r.outcome.error;
  // both particles of the contact are named (one was: in a row, it may be a bystander that was hit)
  EXPECT_NE(r.outcome.error.find("particle 1 (its contact with particle 2)"), std::string::npos) << r.outcome.error;
  EXPECT_FALSE(r.frames.truncated) << r.frames.problem;
  EXPECT_GE(r.frames.frames.size(), 1u);
}

// A contact that passes the overlap limit and parts again between two checks (every 100 steps;
// the contact lasts 50): the force loop sees it, the run stops at that step. It once ran to its end.
TEST(StabilityGuard, AnOverlapPastTheLimitBetweenChecksStopsTheRun) {
  Scene s = pressed_pair();
  s.particles.resize(1);
  s.particles[0].position = {0, 0, 0.01};
  s.particles[0].velocity = {0, 0, -20};  // k = 2e4 N/m against a rigid floor: overlap ~0.75 r
  s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}));
  s.numerics.check_interval = 100;
  s.outputs.every_steps = 1000;
  Simulation sim(s);
  const RunOutcome outcome = run(sim, {});
  ASSERT_FALSE(outcome.ok);
  EXPECT_NE(outcome.error.find("overlap of"), std::string::npos) << outcome.error;
  EXPECT_NE(outcome.steps % 100, 0) << "stopped at a step of its own, not at a check";
}

TEST(StabilityGuard, NotANumberStopsTheRun) {
  Scene s = pressed_pair();
  s.particles[0].velocity = {std::nan(""), 0, 0};
  Simulation sim(s);
  const RunOutcome outcome = run(sim, {});
  ASSERT_FALSE(outcome.ok);
  EXPECT_NE(outcome.error.find("not a finite number"), std::string::npos) << outcome.error;
  EXPECT_NE(outcome.error.find("particle 1"), std::string::npos) << outcome.error;
}

// The kick sums every particle's squared position and mass-weighted squared speeds (a sum is finite
// exactly when its terms are, but for an overflow of the sum itself): two spheres far apart, each
// spinning with three quarters of the largest double of m w^2, are finite, though their sum is not;
// no particle is named and the steps go on.
TEST(StabilityGuard, LargeButFiniteStatesWhoseSumOverflowsAreNotABlowUp) {
  Scene s = base_scene(LinearNormal::kName, 2500, 0, 0.25, 1.0, 0.0, 1e4);
  const double radius = 0.1, mass = sphere_mass(2500, radius);
  ASSERT_GT(mass, 1.0) << "so that w^2 alone does not overflow where m w^2 does not";
  const double spin = std::sqrt(0.75 * std::numeric_limits<double>::max() / mass);
  s.particles.push_back(sphere({-1, 0, 0}, radius, Vec3::Zero(), {spin, 0, 0}));
  s.particles.push_back(sphere({1, 0, 0}, radius, Vec3::Zero(), {spin, 0, 0}));
  s.time.steps = 3;
  Simulation sim(s);
  for (int k = 0; k < 3; ++k) sim.step();
  for (std::size_t i = 0; i < 2; ++i)
    ASSERT_TRUE(
        state_is_finite(sim.particles().x[i], sim.particles().v[i], sim.particles().w[i], sim.particles().mass[i]));
  EXPECT_FALSE(sim.first_non_finite()) << "particle " << sim.first_non_finite()->particle_id + 1 << ", "
                                       << sim.first_non_finite()->particles << " particles";
}

// A row of 12 touching spheres between two planes, the ninth pushed by a constant force, at ten
// times the stable step: the blow-up overflows the numbers within a hundred steps, before the
// energy check would look. Frames every step and the default check interval (100
// steps): no frame and no statistics row may hold a non-finite number, and the message names the
// step and the particle where it started (found here by stepping the same scene alone), not the
// first particle the guard looked at later.
Scene confined_row() {
  Scene s = base_scene(LinearNormal::kName, 2500, 0, 0.25, 1.0, 0.0, 1e4);
  for (int k = 0; k < 12; ++k) s.particles.push_back(sphere({0.02 * k, 0, 0}, 0.01));
  s.particles[8].force = {0.5, 0, 0};
  s.walls.push_back(plane({-0.01, 0, 0}, {1, 0, 0}, "left"));
  s.walls.push_back(plane({0.23, 0, 0}, {-1, 0, 0}, "right"));
  s.time.steps = 20000;
  s.outputs.every_steps = 1;
  s.outputs.force_chains = true;
  s.numerics.max_overlap_fraction = 1e300;  // let the blow-up run: the overlap check would stop it first
  s.time.dt = 10 * std::sqrt(sphere_mass(2500, 0.01) / 2e4);
  s.time.allow_unstable_dt = true;
  return s;
}

TEST(StabilityGuard, ABlowUpNeverReachesTheFilesAndIsTracedToWhereItStarted) {
  // where it starts: the first step with a particle whose position or energy is not finite, and the
  // lowest id among them
  std::int64_t first_step = -1;
  int first_id = -1;
  {
    Simulation alone(confined_row());
    while (first_step < 0 && alone.step_count() < 20000) {
      alone.step();
      const Particles& p = alone.particles();
      for (std::size_t i = 0; i < p.size(); ++i) {
        const double ke = p.mass[i] * (p.v[i].squaredNorm() + p.w[i].squaredNorm());
        if (!p.x[i].allFinite() || !std::isfinite(ke))
          if (first_id < 0 || p.id[i] + 1 < first_id) first_id = p.id[i] + 1;
      }
      if (first_id > 0) first_step = alone.step_count();
    }
  }
  ASSERT_GT(first_step, 0) << "the set-up must blow up";
  ASSERT_LT(first_step, 100) << "the set-up must blow up before the first check";

  const auto folder = std::filesystem::temp_directory_path() / ("dem_blowup_" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  Simulation sim(confined_row());
  RunOutcome outcome;
  {
    auto writers = make_run_writers(sim, folder.string(), false);
    std::vector<Observer*> observers;
    for (auto& w : writers) observers.push_back(w.get());
    outcome = run(sim, observers);
  }
  ASSERT_FALSE(outcome.ok);
  EXPECT_NE(outcome.error.find("not a finite number"), std::string::npos) << outcome.error;
  EXPECT_NE(outcome.error.find("at step " + std::to_string(first_step) + " "), std::string::npos) << outcome.error;
  EXPECT_NE(outcome.error.find("particle " + std::to_string(first_id) + ","), std::string::npos)
      << "it started at particle " << first_id << ": " << outcome.error;
  int files = 0;
  for (const auto& file : std::filesystem::directory_iterator(folder)) {
    if (file.path().extension() != ".dat" || file.path().filename() == "restart.dat") continue;
    ++files;
    std::ifstream in(file.path());
    std::string word;
    while (in >> word) {
      const bool bad = word.find("nan") != std::string::npos || word.find("inf") != std::string::npos ||
                       word.find("NaN") != std::string::npos || word.find("Inf") != std::string::npos;
      ASSERT_FALSE(bad) << file.path().filename() << " holds " << word;
    }
  }
  EXPECT_GE(files, 5);  // animation, force chains, walls, statistics
  std::filesystem::remove_all(folder);
}

// A stored energy that is not a number (a bond disc so thin that its moments of area underflow to 0,
// which the spec refuses, built here directly) stops the run before any file holds it: Energy.dat once
// got -nan in its bond and dissipated columns on every row, and the run "succeeded".
TEST(StabilityGuard, ANonFiniteStoredEnergyNeverReachesTheFiles) {
  Scene s = pressed_pair();
  s.particles[1].position.x() = 0.0101;  // a hair apart: bonded, not touching
  BondSettings b;
  b.youngs_modulus = 1e8;
  b.tensile_strength = b.shear_strength = 1e12;
  b.radius_multiplier = 1e-80;
  s.bonds = b;
  s.particles[1].velocity = {0, 0.01, 0};  // shears the bond a little
  s.time.steps = 50;
  Simulation sim(std::move(s));
  const RunOutcome outcome = run(sim, {});
  ASSERT_FALSE(outcome.ok);
  EXPECT_NE(outcome.error.find("stored elastic energy"), std::string::npos) << outcome.error;
}

// Two spheres meeting at 10 km/s: each step moves them past each other's reach, so no force loop
// ever sees them overlap. They once passed through each other and the run "succeeded" with both
// still at full speed; now the first step stops it, naming the particle and how far it moved.
TEST(StabilityGuard, SpheresFastEnoughToPassThroughEachOtherStopTheRun) {
  for (const std::string_view law : {LinearNormal::kName, HertzNormal::kName}) {
    Scene s = base_scene(law, 2500, 1e9, 0.25, 0.5, 0.0, 1e4);
    s.particles.push_back(sphere({-0.0055, 0, 0}, 0.005, {5000, 0, 0}));
    s.particles.push_back(sphere({0.0055, 0, 0}, 0.005, {-5000, 0, 0}));
    s.time.steps = 200;
    Simulation sim(std::move(s));
    const RunOutcome outcome = run(sim, {});
    ASSERT_FALSE(outcome.ok) << law;
    EXPECT_EQ(outcome.steps, 1) << law;
    EXPECT_NE(outcome.error.find("moved"), std::string::npos) << outcome.error;
    EXPECT_NE(outcome.error.find("in one step at step 1"), std::string::npos) << outcome.error;
  }
}

// The distance named is the one the drift moved the particle, dt times its half-step speed: a sphere
// resting on a plane at a step of 1 s falls 4.905 m in its first drift. It was dt times the speed after
// the step's second half kick, which the plane's push had made 5.3e6 m; at a step of 1e200 s a sphere
// whose speed overflowed was said to have moved -8e-3 m (an independent check).
TEST(StabilityGuard, TheDistanceNamedIsTheOneTheDriftMoved) {
  Scene s = base_scene(LinearNormal::kName, 2500, 0, 0.25, 0.5, 0.0, 1e4);
  s.particles.push_back(sphere({0, 0, 0.01}, 0.01));
  s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}, "floor"));
  s.gravity = {0, 0, -9.81};
  s.time.dt = 1;
  s.time.allow_unstable_dt = true;
  s.time.steps = 10;
  {
    Simulation sim(s);
    const RunOutcome outcome = run(sim, {});
    ASSERT_FALSE(outcome.ok);
    EXPECT_NE(outcome.error.find("particle 1 moved 4.905e+00 m in one step at step 1 "), std::string::npos)
        << outcome.error;
  }
  s.time.dt = 1e200;
  Simulation sim(s);
  const RunOutcome outcome = run(sim, {});
  ASSERT_FALSE(outcome.ok);
  EXPECT_EQ(outcome.error.find("moved -"), std::string::npos) << outcome.error;
}

// Energy made by too large a step is blamed on the particle that holds it: a bonded pair, one sphere
// fixed and the other spinning about the bond's axis, twisted at a step of 1 s. Named by speed alone,
// the fixed sphere (still, the first) was "the fastest" (an independent check).
TEST(StabilityGuard, EnergyGrowthNamesTheParticleWithTheMostKineticEnergy) {
  const Scene s = spec::to_scene(spec::parse_json(R"({"name": "twist",
      "materials": [{"name": "m", "density": 1000, "normalStiffness": 1e6, "poissonRatio": 0.3}],
      "interactions": [{"a": "m", "b": "m", "restitution": 0.5, "friction": 0.5}],
      "particles": [{"position": {}, "radius": 1, "material": "m", "fixed": true},
                    {"position": {"x": 2}, "radius": 1, "material": "m", "angularVelocity": {"x": 1}}],
      "bonds": {"youngsModulus": 1e6, "tensileStrength": 1e6, "shearStrength": 1e6},
      "time": {"steps": 4, "dt": 1, "allowUnstableDt": true}})"));
  Simulation sim(s);
  const RunOutcome outcome = run(sim, {});
  ASSERT_FALSE(outcome.ok);
  EXPECT_NE(outcome.error.find("mechanical energy grew"), std::string::npos) << outcome.error;
  EXPECT_NE(outcome.error.find("particle 2 (the one with the most kinetic energy)"), std::string::npos)
      << outcome.error;
}

// A wall fast enough to pass through particles between two force evaluations. A plate pushed at
// 1e4 m/s (5 cm a step) once went straight through two 5 mm spheres, which kept still, and the run
// succeeded; a servo driving a plate the same way did too. A prescribed motion is refused at the
// set-up, naming the wall; a load is stopped at the step it moved too far.
TEST(StabilityGuard, AWallFastEnoughToPassThroughParticlesIsRefusedOrStopped) {
  auto plate_scene = [](const Vec3& velocity) {
    Scene s = base_scene(LinearNormal::kName, 2500, 0, 0.25, 0.5, 0.0, 1e4);
    s.particles.push_back(sphere({0, 0, 0.02}, 0.005));
    s.particles.push_back(sphere({0.03, 0, 0.02}, 0.005));
    WallInit plate{
        "press",
        1,
        PlateShape{{Vec3(-0.1, -0.1, 0.05), Vec3(0.1, -0.1, 0.05), Vec3(0.1, 0.1, 0.05), Vec3(-0.1, 0.1, 0.05)}},
        {},
        {}};
    if (velocity.norm() > 0) {
      PrescribedMotion m;
      m.velocity = velocity;
      plate.motion = m;
    }
    s.walls.push_back(plate);
    s.time.steps = 200;
    return s;
  };
  try {
    Simulation sim(plate_scene({0, 0, -1e4}));
    ADD_FAILURE() << "a plate moving 1e4 m/s was accepted";
  } catch (const SceneError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("walls[0] (press)"), std::string::npos) << m;
    EXPECT_NE(m.find("in one step"), std::string::npos) << m;
  }
  EXPECT_NO_THROW(Simulation sim(plate_scene({0, 0, -1})));
  // a servo whose speed limit lets it cross a sphere in a step
  Scene servo = plate_scene(Vec3::Zero());
  LoadControl load;
  load.kind = LoadControl::Kind::Servo;
  load.target = 1e6;
  load.gain = 1;
  load.max_speed = 1e4;
  servo.walls[0].load = load;
  Simulation sim(std::move(servo));
  const RunOutcome outcome = run(sim, {});
  ASSERT_FALSE(outcome.ok);
  EXPECT_NE(outcome.error.find("wall 1 (press) moved"), std::string::npos) << outcome.error;
  EXPECT_LE(outcome.steps, 2) << outcome.error;
}

// Causes named for what they are. Two particles at one point were "not a finite number at step 0
// ... likely cause: the time step is too large"; particles placed overlapping were blamed on the
// stiffness and the time step.
TEST(StabilityGuard, ParticlesAtOnePointAreASceneErrorNamingBoth) {
  Scene s = pressed_pair();
  s.particles[1].position = s.particles[0].position;
  try {
    Simulation sim(s);
    ADD_FAILURE() << "two particles at one point were accepted";
  } catch (const SceneError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("particles 1 and 2"), std::string::npos) << m;
    EXPECT_NE(m.find("same place"), std::string::npos) << m;
  }
}

TEST(StabilityGuard, AnOverlapAsPlacedIsBlamedOnThePlacement) {
  Scene s = pressed_pair();
  s.particles[1].position = {-0.0099 + 0.01, 0, 0};  // 50% of the radius
  Simulation sim(s);
  const RunOutcome outcome = run(sim, {});
  ASSERT_FALSE(outcome.ok);
  EXPECT_EQ(outcome.steps, 0);
  EXPECT_NE(outcome.error.find("as placed"), std::string::npos) << outcome.error;
  EXPECT_EQ(outcome.error.find("stiffness is too low"), std::string::npos) << outcome.error;
}

// Spheres grown threefold in one step overlap past the limit at once: the growth is the cause, not
// the stiffness or the step (an independent tester found the stop blaming "contact stiffness too
// low ... or time step too large" for two bonded spheres grown x3 over one step).
TEST(StabilityGuard, AnOverlapMadeByGrowthIsBlamedOnTheGrowth) {
  Scene s = pressed_pair();
  s.growth = Scene::Growth{3.0, 1};
  Simulation sim(s);
  const RunOutcome outcome = run(sim, {});
  ASSERT_FALSE(outcome.ok);
  EXPECT_NE(outcome.error.find("likely cause: the radii grow too fast"), std::string::npos) << outcome.error;
  EXPECT_NE(outcome.error.find("growth.steps"), std::string::npos) << outcome.error;
  EXPECT_EQ(outcome.error.find("stiffness is too low"), std::string::npos) << outcome.error;
}

// Energy made after much was lost is still made: the guard compares with the lowest the balance
// has been, not only with the start (a stiff rolling dashpot once made 1.65 times the initial
// energy after the pile had settled, and the run ended "ok").
TEST(StabilityGuard, EnergyMadeAfterLossesStopsTheRun) {
  // a damped drop loses most of its energy; then the contact's step goes unstable
  Scene s = base_scene(LinearNormal::kName, 2500, 0, 0.25, 0.1, 0.0, 1e4);
  s.particles.push_back(sphere({0, 0, 0.0105}, 0.01, {0, 0, -1}));
  s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}));
  s.gravity = {0, 0, -9.81};
  s.time.steps = 400000;
  s.numerics.check_interval = 10;
  s.numerics.max_overlap_fraction = 1.0;
  Simulation sim(s);
  StabilityGuard guard(sim);
  for (int k = 0; k < 20000; ++k) sim.step();
  ASSERT_LT(sim.mechanical_energy(), 0.5 * sim.energy_input().initial_energy) << "it did not lose much";
  EXPECT_NO_THROW(guard.check(sim));
  // now feed energy from nothing: kick the sphere up to a quarter of what it started with
  const double m = sphere_mass(2500, 0.01);
  const double lost_to = sim.mechanical_energy();
  const_cast<Vec3&>(sim.particles().v[0]) += Vec3(0, 0, std::sqrt(2 * 0.25 * sim.energy_input().initial_energy / m));
  ASSERT_LT(sim.mechanical_energy(), sim.energy_input().initial_energy);
  ASSERT_GT(sim.mechanical_energy(), lost_to + 0.2 * sim.energy_input().initial_energy);
  try {
    guard.check(sim);
    ADD_FAILURE() << "energy made after losses went unseen";
  } catch (const InstabilityError& e) {
    EXPECT_NE(std::string(e.what()).find("lowest"), std::string::npos) << e.what();
  }
}

TEST(StabilityGuard, AStableRunIsLeftAlone) {
  Scene s = pressed_pair();
  const RunOutcome outcome = run_with_file(s).outcome;
  EXPECT_TRUE(outcome.ok) << outcome.error;
  EXPECT_EQ(outcome.steps, 2000);
}

}  // namespace
}  // namespace dem::test
