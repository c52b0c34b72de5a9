// Restart: a run saved half way and continued in a new process gives the uninterrupted run's bits.
// The scene has everything with a memory: contact springs (tangential and rolling), a mesh floor,
// a loaded plate, bonds, neighbour rebuilds and re-sorts.
#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "sim/state_io.hpp"
#include "support/meshes.hpp"
#include "support/scenes.hpp"

namespace dem::test::test_restart {
namespace {

Scene remembering_scene() {
  Scene s = base_scene(HertzNormal::kName, 2500, 1e7, 0.25, 0.4, 0.5);
  set_rolling(s, EpsdRolling::kName, 0.05);
  s.gravity = {0, 0, -9.81};
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i)
        s.particles.push_back(sphere({0.01 * i, 0.01 * j, 0.0052 + 0.01 * k}, 0.005, {0.1 * u(rng), 0.1 * u(rng), 0}));
  s.walls.push_back(mesh_wall(grid_rectangle({-0.05, -0.05, 0}, {0.16, 0, 0}, {0, 0.16, 0}, 8, 8), "floor"));
  WallInit plate{"sleeper",
                 1,
                 PlateShape{{Vec3(-0.01, -0.01, 0.062), Vec3(0.06, -0.01, 0.062), Vec3(0.06, 0.06, 0.062),
                             Vec3(-0.01, 0.06, 0.062)}},
                 {},
                 {}};
  LoadControl load;
  load.mass = 0.05;
  load.f_min = 1;
  load.f_max = 10;
  load.frequency = 20;
  load.cycles = 2;
  plate.load = load;
  s.walls.push_back(plate);
  BondSettings bonds;
  bonds.youngs_modulus = 1e7;
  bonds.tensile_strength = 2e4;
  bonds.shear_strength = 2e4;
  bonds.gap_tolerance = 0.05;
  bonds.region = Box{Vec3(-1, -1, 0.02), Vec3(1, 1, 1)};  // the upper layers only
  s.bonds = bonds;
  s.numerics.reorder_interval = 2;
  return s;
}

TEST(Restart, ContinuingFromASavedStateGivesTheUninterruptedRun) {
  constexpr int kSteps = 4000;
  Simulation whole(remembering_scene());
  ASSERT_GT(whole.bonds().bonds().size(), 50u);
  for (int k = 0; k < kSteps; ++k) whole.step();

  Simulation first(remembering_scene());
  for (int k = 0; k < kSteps / 2; ++k) first.step();
  std::stringstream saved;
  StateIO::write(first, saved);
  Simulation second(remembering_scene());
  StateIO::read(second, saved);
  EXPECT_EQ(second.step_count(), kSteps / 2);
  for (int k = 0; k < kSteps / 2; ++k) second.step();

  EXPECT_GT(whole.neighbor_builds(), 3);
  EXPECT_GT(whole.bonds().counts().tension + whole.bonds().counts().shear, 0);  // some broke on the way
  for (std::size_t i = 0; i < whole.particles().size(); ++i) {
    ASSERT_EQ(whole.particles().x[i], second.particles().x[i]) << "particle " << i;
    ASSERT_EQ(whole.particles().w[i], second.particles().w[i]) << "particle " << i;
  }
  EXPECT_EQ(whole.wall_driver(1).load_displacement(), second.wall_driver(1).load_displacement());
  EXPECT_EQ(whole.fragments(), second.fragments());
}

// A stage of `settle` steps, then one of `glue` steps that glues the scene's bonds at its start.
std::vector<Stage> settle_then_glue(std::int64_t settle, std::int64_t glue) {
  std::vector<Stage> stages(2);
  stages[0].name = "settle";
  stages[0].steps = settle;
  stages[1].name = "glue";
  stages[1].steps = glue;
  stages[1].glue_bonds = true;
  return stages;
}

// Bonds that glue nothing leave the spheres' orientations untracked (only bonds read them): a run
// saved after a bonding stage that glued no pair holds none, and its continuation expects none.
TEST(Restart, AStageThatGluedNoBondIsContinuedFromItsSavedState) {
  auto scene = [] {
    Scene s = remembering_scene();
    s.bonds->region = Box{Vec3(5, 5, 5), Vec3(6, 6, 6)};  // no particle there
    s.stages = settle_then_glue(500, 1500);
    return s;
  };
  constexpr int kSteps = 2000, kSaved = 1000;
  Simulation whole(scene());
  EXPECT_EQ(whole.particles().q.size(), whole.particles().size());  // a later stage may glue
  for (int k = 0; k < kSteps; ++k) whole.step();
  EXPECT_TRUE(whole.bonds().bonds().empty());
  EXPECT_TRUE(whole.particles().q.empty());

  Simulation first(scene());
  for (int k = 0; k < kSaved; ++k) first.step();
  std::stringstream saved;
  StateIO::write(first, saved);
  Simulation second(scene());
  StateIO::read(second, saved);
  for (int k = kSaved; k < kSteps; ++k) second.step();
  for (std::size_t i = 0; i < whole.particles().size(); ++i) ASSERT_EQ(whole.particles().x[i], second.particles().x[i]);
}

// A state saved under a spec that glued nothing by then (no bonds block, or its stage not yet
// reached) has no orientations; a spec whose bonding stage is still to come reads it and starts them.
TEST(Restart, AStateWithoutOrientationsIsContinuedIntoASpecThatGluesLater) {
  const std::vector<Stage> stages = settle_then_glue(500, 500);
  Scene settle_only = remembering_scene();  // its first stage alone, and no bonds
  settle_only.bonds.reset();
  settle_only.stages = {stages[0]};
  settle_only.time.dt = 5e-6;  // the step of the spec with bonds (a state is continued at its own step)
  Simulation first(settle_only);
  for (int k = 0; k < 200; ++k) first.step();
  ASSERT_TRUE(first.particles().q.empty());
  std::stringstream saved;
  StateIO::write(first, saved);

  Scene glue_later = remembering_scene();
  glue_later.stages = stages;
  glue_later.time.dt = 5e-6;
  Simulation second(glue_later);
  StateIO::read(second, saved);
  EXPECT_EQ(second.particles().q.size(), second.particles().size());
  for (int k = 200; k < 1000; ++k) second.step();
  EXPECT_GT(second.bonds().bonds().size(), 50u);  // glued at the second stage's start
}

TEST(Restart, ABondsBlockThatGluesNothingTracksNoOrientation) {
  Scene s = remembering_scene();
  s.bonds->region = Box{Vec3(5, 5, 5), Vec3(6, 6, 6)};
  const Simulation sim(s);
  EXPECT_TRUE(sim.bonds().bonds().empty());
  EXPECT_TRUE(sim.particles().q.empty());
  const Simulation bonded(remembering_scene());
  EXPECT_EQ(bonded.particles().q.size(), bonded.particles().size());
}

TEST(Restart, AStateOfAnotherJobIsRefused) {
  Simulation a(remembering_scene());
  std::stringstream saved;
  StateIO::write(a, saved);
  Scene other = remembering_scene();
  other.particles.pop_back();
  Simulation b(other);
  try {
    StateIO::read(b, saved);
    FAIL() << "read a state of 216 particles into a scene of 215";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("the saved state was written for another job: particles 216", 0), 0u)
        << e.what();
  }
  std::stringstream cut(saved.str().substr(0, 500));
  Simulation c(remembering_scene());
  EXPECT_THROW(StateIO::read(c, cut), std::runtime_error);
}

}  // namespace
}  // namespace dem::test::test_restart
