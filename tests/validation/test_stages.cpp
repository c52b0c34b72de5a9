// Staged runs (Scene::stages): what a stage changes acts from its first step, exactly (free fall,
// a wall's motion from the stage's start); a wall removed or added; bonds glued between the pairs
// touching at the bond stage; end conditions; and a run saved anywhere around a stage boundary
// continues to the uninterrupted run's bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <sstream>
#include <utility>

#include "core/errors.hpp"
#include "sim/runner.hpp"
#include "sim/state_io.hpp"
#include "support/scenes.hpp"

namespace dem::test::test_stages {
namespace {

constexpr double kG = 9.81;

Stage stage_of(const std::string& name, std::int64_t steps) {
  Stage s;
  s.name = name;
  s.steps = steps;
  return s;
}

// One sphere in empty space, with a fixed step (no contact chooses one).
Scene lone_sphere(const Vec3& x) {
  Scene s = base_scene(LinearNormal::kName, 2500, 0, 0.25, 0.5, 0.3, 1e5);
  s.particles.push_back(sphere(x, 0.01));
  s.time.dt = 5e-5;
  return s;
}

TEST(Stages, GravityGivenAtAStagePullsFromItsFirstStepExactly) {
  Scene s = lone_sphere({0, 0, 1});
  s.stages.push_back(stage_of("weightless", 100));
  Stage fall = stage_of("fall", 200);
  fall.gravity = Vec3(0, 0, -kG);
  s.stages.push_back(fall);
  Simulation sim(std::move(s));
  EXPECT_EQ(sim.total_steps(), 300);
  EXPECT_EQ(sim.stage_name(), "weightless");
  for (int k = 0; k < 100; ++k) sim.step();
  EXPECT_EQ(sim.particles().x[0].z(), 1.0);
  for (int k = 0; k < 200; ++k) sim.step();
  EXPECT_EQ(sim.stage(), 1);
  EXPECT_EQ(sim.stage_name(), "fall");
  EXPECT_EQ(sim.stage_start_step(), 100);
  const double t = 200 * 5e-5;  // velocity Verlet is exact under a constant force
  EXPECT_NEAR(sim.particles().x[0].z(), 1 - 0.5 * kG * t * t, 1e-14);
  EXPECT_NEAR(sim.particles().v[0].z(), -kG * t, 1e-14);
}

// A sphere resting on a floor; the floor goes at the second stage.
Scene sphere_on_floor() {
  Scene s = base_scene(LinearNormal::kName, 2500, 0, 0.25, 0.2, 0.3, 1e5);
  s.particles.push_back(sphere({0, 0, 0.0099}, 0.01));
  s.walls.push_back(plane(Vec3::Zero(), Vec3::UnitZ(), "floor"));
  s.gravity = {0, 0, -kG};
  s.numerics.local_damping = 0.7;
  return s;
}

TEST(Stages, AFloorRemovedAtAStageNoLongerPushesFromItsFirstStep) {
  Scene s = sphere_on_floor();
  s.stages.push_back(stage_of("rest", 3000));
  Stage drop = stage_of("drop", 400);
  drop.local_damping = 0.0;
  s.walls[0].last_stage = 0;
  s.stages.push_back(drop);
  Simulation sim(std::move(s));
  for (int k = 0; k < 3000; ++k) sim.step();
  EXPECT_TRUE(sim.wall_present(0));
  const double z0 = sim.particles().x[0].z(), v0 = sim.particles().v[0].z();
  EXPECT_NEAR(z0, 0.01, 1e-4);  // resting, pressed in by its weight
  for (int k = 0; k < 400; ++k) sim.step();
  EXPECT_FALSE(sim.wall_present(0));
  const double t = 400 * sim.dt();
  // free fall from where the stage found it: the floor's last push is not in the first half kick
  EXPECT_NEAR(sim.particles().x[0].z(), z0 + v0 * t - 0.5 * kG * t * t, 1e-12);
  EXPECT_NEAR(sim.particles().v[0].z(), v0 - kG * t, 1e-12);
}

TEST(Stages, AFloorAddedAtAStageIsNotThereBeforeAndCatchesTheSphereAfter) {
  Scene s = base_scene(LinearNormal::kName, 2500, 0, 0.25, 0.2, 0.3, 1e5);
  s.particles.push_back(sphere({0, 0, 0.03}, 0.01));
  s.walls.push_back(plane(Vec3(0, 0, 0.025), Vec3::UnitZ(), "shelf"));  // in the way from the start...
  s.walls[0].last_stage = -1;                                           // ...but never there
  s.walls.push_back(plane(Vec3::Zero(), Vec3::UnitZ(), "floor"));
  s.walls[1].first_stage = 1;  // the floor comes at the second stage
  s.gravity = {0, 0, -kG};
  s.stages.push_back(stage_of("fall", 4000));
  Stage caught = stage_of("caught", 30000);
  caught.local_damping = 0.5;
  s.stages.push_back(caught);
  Simulation sim(std::move(s));
  for (int k = 0; k < 4000; ++k) sim.step();
  const double t = 4000 * sim.dt();
  EXPECT_NEAR(sim.particles().x[0].z(), 0.03 - 0.5 * kG * t * t, 1e-12);  // nothing in the way
  EXPECT_FALSE(sim.wall_present(0));
  EXPECT_FALSE(sim.wall_present(1));
  ASSERT_GT(sim.particles().x[0].z(), 0.0101);  // above the floor to come
  while (sim.step_count() < sim.total_steps()) sim.step();
  EXPECT_TRUE(sim.wall_present(1));
  EXPECT_NEAR(sim.particles().x[0].z(), 0.01, 2e-5);  // resting on the floor
  EXPECT_NEAR(sim.particles().v[0].z(), 0, 1e-4);
}

// A wall a stage adds through a particle stops the run at that stage's first step, and the error
// says so: it named only "its contact with a wall" (a sleeper added below the top of a ballast bed
// stopped a 5-minute settling with no word of the sleeper).
TEST(Stages, AWallAddedThroughAParticleIsNamedInTheError) {
  Scene s = base_scene(LinearNormal::kName, 2500, 0, 0.25, 0.2, 0.3, 1e5);
  s.particles.push_back(sphere({0, 0, 0.01}, 0.01));
  s.walls.push_back(plane(Vec3::Zero(), Vec3::UnitZ(), "floor"));
  s.walls.push_back(plane(Vec3(0, 0, 0.012), -Vec3::UnitZ(), "lid"));
  s.walls[1].first_stage = 1;
  s.gravity = {0, 0, -kG};
  s.stages.push_back(stage_of("settle", 200));
  s.stages.push_back(stage_of("close", 200));
  Simulation sim(std::move(s));
  const RunOutcome outcome = run(sim, {});
  ASSERT_FALSE(outcome.ok);
  EXPECT_NE(outcome.error.find("first step of stage \"close\""), std::string::npos) << outcome.error;
  EXPECT_NE(outcome.error.find("the wall it adds (\"lid\")"), std::string::npos) << outcome.error;
}

TEST(Stages, AMotionGivenAtAStageCountsItsTimeFromTheStageStart) {
  Scene s = lone_sphere({1, 1, 1});
  s.walls.push_back(
      WallInit{"plate", 1, PlateShape{{Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0.1, 0.1, 0), Vec3(0, 0.1, 0)}}, {}, {}});
  s.stages.push_back(stage_of("still", 123));
  Stage shake = stage_of("shake", 500);
  PrescribedMotion m;
  m.velocity = {0, 0, 0.01};
  m.amplitude = {0.02, 0, 0};
  m.frequency = 7;
  m.phase = 0.3;
  shake.wall_changes.push_back({0, m, {}});
  s.stages.push_back(shake);
  Simulation sim(std::move(s));
  for (int k = 0; k < 123; ++k) sim.step();
  EXPECT_TRUE(sim.wall_driver(0).pose().displacement.isZero(0));
  for (int k = 0; k < 500; ++k) sim.step();
  const double t = 500 * sim.dt(), w = 2 * std::numbers::pi * 7;
  const Vec3 expected = m.velocity * t + m.amplitude * ((std::cos(0.3) - std::cos(w * t + 0.3)) / w);
  EXPECT_LT((sim.wall_driver(0).pose().displacement - expected).norm(), 1e-15);
}

// Spheres dropped into a box of planes, damped: they come to rest in a pile.
Scene pile(int side) {
  Scene s = base_scene(LinearNormal::kName, 2500, 0, 0.25, 0.3, 0.4, 2e4);
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (int k = 0; k < side; ++k)
        s.particles.push_back(sphere({0.011 + 0.021 * i, 0.011 + 0.021 * j, 0.011 + 0.0215 * k}, 0.01));
  const double box = 0.021 * side + 0.001;
  s.walls.push_back(plane(Vec3::Zero(), Vec3::UnitZ(), "floor"));
  s.walls.push_back(plane(Vec3::Zero(), Vec3::UnitX(), "x0"));
  s.walls.push_back(plane(Vec3(box, 0, 0), -Vec3::UnitX(), "x1"));
  s.walls.push_back(plane(Vec3::Zero(), Vec3::UnitY(), "y0"));
  s.walls.push_back(plane(Vec3(0, box, 0), -Vec3::UnitY(), "y1"));
  s.gravity = {0, 0, -kG};
  s.numerics.local_damping = 0.3;
  BondSettings bonds;
  bonds.youngs_modulus = 1e6;
  bonds.tensile_strength = 1e9;
  bonds.shear_strength = 1e9;
  s.bonds = bonds;
  return s;
}

TEST(Stages, TheBondStageGluesEveryPairTouchingAtItsStartAndNoneBefore) {
  Scene s = pile(4);
  s.stages.push_back(stage_of("settle", 4000));
  Stage bond = stage_of("bond", 10);
  bond.glue_bonds = true;
  s.stages.push_back(bond);
  Simulation sim(std::move(s));
  EXPECT_TRUE(sim.bonds().empty());  // not at t = 0: the spheres touch nothing yet
  for (int k = 0; k < 3999; ++k) sim.step();
  sim.record_contacts(true);
  sim.step();
  ASSERT_EQ(sim.step_count(), sim.stage_end_step());
  std::set<std::pair<int, int>> touching;
  for (const PairContact& c : sim.pair_contacts()) {
    const int a = sim.particles().id[c.i], b = sim.particles().id[c.j];
    touching.insert({std::min(a, b), std::max(a, b)});
  }
  ASSERT_GT(touching.size(), 40u);
  sim.step();  // the bond stage's first
  std::set<std::pair<int, int>> bonded;
  for (const Bond& b : sim.bonds().bonds()) {
    const int a = sim.particles().id[b.i], c = sim.particles().id[b.j];
    bonded.insert({std::min(a, c), std::max(a, c)});
  }
  for (const auto& pair : touching)
    EXPECT_TRUE(bonded.count(pair)) << "particles " << pair.first << " and " << pair.second << " touch, unbonded";
  // and no pair farther apart than the gap tolerance (1e-3 of the radius)
  EXPECT_LE(bonded.size(), touching.size() + touching.size() / 10);
}

TEST(Stages, AStageEndsAtTheFirstStepItsKineticEnergyIsBelowTheThresholdAfterItsWait) {
  Scene s = pile(3);
  s.bonds.reset();
  Stage settle = stage_of("settle", 200000);
  settle.until_kinetic_energy = 1e-7;
  settle.min_duration = 0.05;
  s.stages.push_back(settle);
  s.stages.push_back(stage_of("after", 50));
  Simulation sim(std::move(s));
  const std::int64_t wait = std::llround(0.05 / sim.dt());
  std::vector<double> energy{sim.kinetic_energy()};
  while (sim.stage() == 0 && sim.step_count() < sim.total_steps()) {
    sim.step();
    energy.push_back(sim.kinetic_energy());
  }
  ASSERT_EQ(sim.stage(), 1);
  // it held at step s, so step s + 1 was the stage's last; the next step entered stage 2
  std::int64_t first = -1;
  for (std::int64_t k = wait; k < static_cast<std::int64_t>(energy.size()); ++k)
    if (energy[k] < 1e-7) {
      first = k;
      break;
    }
  ASSERT_GT(first, 0);
  EXPECT_EQ(sim.stage_start_step(), first + 1);
  EXPECT_LT(first, 200000 / 2);
  EXPECT_EQ(sim.total_steps(), first + 1 + 50);
}

TEST(Stages, AStageEndsWhenItsWallIsPushedHardEnoughAndTheNextStopsTheWall) {
  Scene s = pile(3);
  s.bonds.reset();
  s.stages.push_back(stage_of("settle", 4000));
  // a lid that comes down at a stage onto the settled pile
  WallInit lid{"lid", 1, PlaneShape{Vec3(0, 0, 0.075), -Vec3::UnitZ()}, {}, {}};
  lid.first_stage = 1;
  PrescribedMotion down;
  down.velocity = {0, 0, -0.02};
  lid.motion = down;
  s.walls.push_back(lid);
  Stage press = stage_of("press", 400000);
  press.until_wall = 5;
  press.until_wall_force = 20;
  press.min_duration = 0;
  s.stages.push_back(press);
  Stage hold = stage_of("hold", 2000);
  hold.wall_changes.push_back({5, {}, {}});
  s.stages.push_back(hold);
  Simulation sim(std::move(s));
  double force_at_end = 0;
  Vec3 lid_at_end = Vec3::Zero();
  while (sim.step_count() < sim.total_steps()) {
    sim.step();
    if (sim.stage() == 1 && sim.step_count() == sim.stage_end_step()) {
      force_at_end = sim.boundary_loads()[5].force.norm();
      lid_at_end = sim.wall_driver(5).pose().displacement;
    }
  }
  EXPECT_EQ(sim.stage(), 2);
  EXPECT_GE(force_at_end, 20);
  EXPECT_LT(force_at_end, 40);                                    // it stopped near the force, not long after
  EXPECT_EQ(sim.wall_driver(5).pose().displacement, lid_at_end);  // held still from there
}

// Every kind of change at a boundary: gravity turned, a wall removed, bonds glued, an end condition,
// a wall given a load.
Scene staged_scene() {
  Scene s = pile(3);
  s.numerics.reorder_interval = 2;
  WallInit lid{"lid", 1, PlaneShape{Vec3(0, 0, 0.066), -Vec3::UnitZ()}, {}, {}};
  s.walls.push_back(lid);
  Stage settle = stage_of("settle", 3000);
  settle.until_kinetic_energy = 1e-6;
  s.stages.push_back(settle);
  Stage bond = stage_of("bond", 500);
  bond.glue_bonds = true;
  bond.gravity = Vec3(0.5, 0, -kG);
  s.stages.push_back(bond);
  Stage release = stage_of("release", 1500);
  release.local_damping = 0.0;
  LoadControl servo;
  servo.kind = LoadControl::Kind::Servo;
  servo.target = 5;
  servo.gain = 1e-3;
  servo.max_speed = 0.05;
  release.wall_changes.push_back({5, {}, servo});
  s.walls[2].last_stage = 1;  // the side x1 goes
  s.stages.push_back(release);
  return s;
}

TEST(Stages, ARunSavedAroundEveryStageBoundaryContinuesToTheUninterruptedRunsBits) {
  Simulation whole(staged_scene());
  std::vector<std::int64_t> starts;
  while (whole.step_count() < whole.total_steps()) {
    whole.step();
    if (starts.empty() || whole.stage() + 1 > static_cast<int>(starts.size()))
      starts.push_back(whole.stage_start_step());
  }
  ASSERT_EQ(starts.size(), 3u);
  ASSERT_LT(whole.stage_start_step(), 3000 + 500);  // the settling ended early
  ASSERT_FALSE(whole.bonds().empty());
  std::vector<std::int64_t> saves;
  for (std::int64_t boundary : {starts[1], starts[2]})
    for (std::int64_t d : {-1, 0, 1}) saves.push_back(boundary + d);
  saves.push_back(200);
  for (std::int64_t at : saves) {
    Simulation first(staged_scene());
    while (first.step_count() < at) first.step();
    std::stringstream saved;
    StateIO::write(first, saved);
    Simulation second(staged_scene());
    StateIO::read(second, saved);
    ASSERT_EQ(second.stage(), first.stage()) << "saved at step " << at;
    while (second.step_count() < second.total_steps()) second.step();
    ASSERT_EQ(second.total_steps(), whole.total_steps()) << "saved at step " << at;
    for (std::size_t i = 0; i < whole.particles().size(); ++i) {
      ASSERT_EQ(whole.particles().x[i], second.particles().x[i]) << "saved at step " << at << ", particle " << i;
      ASSERT_EQ(whole.particles().w[i], second.particles().w[i]) << "saved at step " << at << ", particle " << i;
    }
    EXPECT_EQ(whole.wall_driver(5).pose().displacement, second.wall_driver(5).pose().displacement);
    EXPECT_EQ(whole.bonds().bonds().size(), second.bonds().bonds().size());
  }
}

TEST(Stages, TheEnergyGuardCountsAStagesChangesAsInput) {
  Scene s = sphere_on_floor();
  s.stages.push_back(stage_of("rest", 2000));
  Stage heavier = stage_of("heavier", 2000);
  heavier.gravity = Vec3(0, 0, -3 * kG);
  s.stages.push_back(heavier);
  Simulation sim(std::move(s));
  for (int k = 0; k < 2000; ++k) sim.step();
  const double z = sim.particles().x[0].z();  // where the stronger pull finds it
  const RunOutcome outcome = run(sim, {});
  ASSERT_TRUE(outcome.ok) << outcome.error;
  // a stronger pull raises the gravitational energy (m g z, from the origin) at the boundary: the
  // stage's input, not energy the integration made
  const double jump = 2 * kG * sim.particles().mass[0] * z;
  EXPECT_NEAR(sim.energy_input().stages, jump, 1e-9 * jump);
  const double balance = sim.mechanical_energy() - sim.energy_input().total() - sim.energy_input().initial_energy;
  EXPECT_LE(balance, 1e-6 * jump);  // only damping took energy out
}

// BallastDEM's sleeper load (1.5 to 51.84 kN at 3 Hz on a 1 kg plate) given at a stage that starts
// at the load's peak time of the run (t = 1/6 s): its cycle starts with the stage, at F_min.
TEST(Stages, ACyclicLoadGivenAtAStageStartsItsCycleThere) {
  for (const bool added : {false, true}) {
    Scene s = lone_sphere({0, 0, 1});
    s.particles[0].fixed = true;
    s.time.dt = 1e-5;
    s.gravity = {0, 0, -kG};
    WallInit sleeper{"sleeper",
                     1,
                     PlateShape{{Vec3(-0.1, -0.05, 0), Vec3(0.1, -0.05, 0), Vec3(0.1, 0.05, 0), Vec3(-0.1, 0.05, 0)}},
                     {},
                     {}};
    LoadControl load;
    load.mass = 1;
    load.f_min = 1500;
    load.f_max = 51840;
    load.frequency = 3;
    load.cycles = 15;
    s.stages.push_back(stage_of("settle", 16667));
    Stage loaded = stage_of("load", 100);
    if (added) {
      sleeper.first_stage = 1;
      sleeper.load = load;
    } else {
      loaded.wall_changes.push_back({0, {}, load});
    }
    s.walls.push_back(sleeper);
    s.stages.push_back(loaded);
    Simulation sim(std::move(s));
    while (sim.step_count() < sim.total_steps()) sim.step();
    // 100 steps of 1e-5 s under F(t) ~ F_min (it rises by 1.5 N in a millisecond) and the weight
    const double t = 1e-3, expected = 0.5 * (1500 + kG) * t * t;
    EXPECT_NEAR(sim.wall_driver(0).load_displacement(), expected, 1e-3 * expected) << (added ? "added" : "changed");
  }
}

TEST(Stages, AFinishedStagedRunContinuedWithItsLastStageLengthenedRunsOn) {
  auto scene = [](std::int64_t last) {
    Scene s = lone_sphere({0, 0, 1});
    s.gravity = {0, 0, -kG};
    s.stages.push_back(stage_of("a", 100));
    s.stages.push_back(stage_of("b", last));
    return s;
  };
  Simulation first(scene(200));
  while (first.step_count() < first.total_steps()) first.step();
  std::stringstream saved;
  StateIO::write(first, saved);
  Simulation longer(scene(500));
  StateIO::read(longer, saved);
  EXPECT_EQ(longer.stage_end_step(), 600);  // not the saved run's 300: it did not end early
  EXPECT_EQ(longer.total_steps(), 600);
}

TEST(Stages, AContinuedRunMayNotChangeAGrowthUnderWay) {
  auto scene = [](double factor) {
    Scene s = pile(2);
    s.bonds.reset();
    Stage grow = stage_of("grow", 400);
    grow.growth_factor = factor;
    s.stages.push_back(grow);
    s.stages.push_back(stage_of("after", 100));
    return s;
  };
  Simulation first(scene(1.1));
  for (int k = 0; k < 200; ++k) first.step();
  std::stringstream saved;
  StateIO::write(first, saved);
  Simulation other(scene(1.2));
  try {
    StateIO::read(other, saved);
    FAIL() << "a changed growth was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("a continued run may not change a growth under way or done"),
              std::string::npos)
        << e.what();
  }
}

TEST(Stages, AStagesRestitutionHoldsTheStepToItsLimit) {
  Scene s = sphere_on_floor();
  s.interactions.assign(4, Interaction{0.99, 0.3, 0});
  s.stages.push_back(stage_of("elastic", 10));
  Stage damped = stage_of("damped", 10);
  damped.interactions = std::vector<Interaction>(4, Interaction{0.001, 0.3, 0});
  s.stages.push_back(damped);
  Scene alone = s;
  alone.stages.clear();
  alone.time.steps = 20;
  alone.interactions = *damped.interactions;
  const double dt_alone = Simulation(alone).dt();
  EXPECT_EQ(Simulation(s).dt(), dt_alone);  // the damped contact's shorter time sets it
  s.time.dt = 6 * dt_alone;                 // above the damped stage's limit (t_c / 10), below the elastic one's
  try {
    Simulation refused(s);
    FAIL() << "a step above a stage's limit was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("stages[1] (damped): time.dt"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dem::test::test_stages
