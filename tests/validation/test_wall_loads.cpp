// Load-controlled walls on a bed of spheres (the ballast test's loading plate): a plate pushed by
// a cyclic force passes that force to the bed, and a servo plate holds its target force.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <variant>

#include "sim/state_io.hpp"
#include "support/report.hpp"
#include "support/scenes.hpp"

namespace dem::test::test_wall_loads {
namespace {

constexpr double kR = 0.005, kG = 9.81, kPlateMass = 1.0;

// A 4 x 4 x 4 stack of touching spheres in a 4 cm box (settled from the start: the columns rest
// on each other), under a plate lying on the top layer, pushed down by `load`.
Scene loaded_bed(const LoadControl& load, double plate_gap) {
  Scene s = base_scene(LinearNormal::kName, 2500, 1e8, 0.25, 0.3, 0.3, 1e5);
  s.gravity = {0, 0, -kG};
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i)
        s.particles.push_back(sphere({kR + 2 * kR * i, kR + 2 * kR * j, kR + 2 * kR * k}, kR));
  const double side = 8 * kR;
  s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}, "floor"));
  s.walls.push_back(plane({0, 0, 0}, {1, 0, 0}, "x-low"));
  s.walls.push_back(plane({side, 0, 0}, {-1, 0, 0}, "x-high"));
  s.walls.push_back(plane({0, 0, 0}, {0, 1, 0}, "y-low"));
  s.walls.push_back(plane({0, side, 0}, {0, -1, 0}, "y-high"));
  const double z = side + plate_gap;
  WallInit plate{
      "sleeper",
      1,
      PlateShape{{Vec3(-kR, -kR, z), Vec3(side + kR, -kR, z), Vec3(side + kR, side + kR, z), Vec3(-kR, side + kR, z)}},
      {},
      {}};
  plate.load = load;
  s.walls.push_back(plate);
  return s;
}

// F between 100 N and 1000 N at 5 Hz for 3 cycles, on a plate of kPlateMass.
LoadControl cyclic_load() {
  LoadControl load;
  load.kind = LoadControl::Kind::Cyclic;
  load.direction = {0, 0, -1};
  load.mass = kPlateMass;
  load.f_min = 100;
  load.f_max = 1000;
  load.frequency = 5;
  load.cycles = 3;
  return load;
}

// Over the third cycle the force the plate applies to the bed must follow F(t) + its weight
// within 1% of F_max.
TEST(LoadedPlate, FollowsItsForceCycle) {
  const LoadControl load = cyclic_load();
  Simulation sim(loaded_bed(load, 0));
  const int plate = static_cast<int>(sim.scene().walls.size()) - 1;
  double worst = 0, peak = 0, lowest = 1e9, deepest = 0;
  while (sim.time() < 0.6) {
    sim.step();
    if (sim.time() < 0.4) continue;  // two cycles settle the bed (it starts with a step load of F_min)
    const double applied = sim.wall_driver(plate).applied_force();
    const double want = load.force_at(sim.time()) + kPlateMass * kG;
    worst = std::max(worst, std::abs(applied - want));
    peak = std::max(peak, applied);
    lowest = std::min(lowest, applied);
    deepest = std::max(deepest, sim.wall_driver(plate).load_displacement());
    // the boundary total seen by observers is the bed's push on the plate: up, the same size
    ASSERT_NEAR(sim.boundary_loads()[plate].force.z(), applied, 1e-9 * load.f_max);
  }
  report("cyclic plate: largest |applied - prescribed| / F_max", worst / load.f_max, 0.0);
  EXPECT_LT(worst, 0.01 * load.f_max);
  EXPECT_NEAR(peak, load.f_max + kPlateMass * kG, 0.01 * load.f_max);
  EXPECT_NEAR(lowest, load.f_min + kPlateMass * kG, 0.01 * load.f_max);
  EXPECT_GT(deepest, 0);  // it pressed the bed down
  // the floor carries the plate's push and the bed's weight, downwards
  const double bed_weight = 64 * sphere_mass(2500, kR) * kG;
  EXPECT_NEAR(sim.boundary_loads()[0].force.z(), -(sim.wall_driver(plate).applied_force() + bed_weight),
              0.01 * load.f_max);
}

// A servo holding 500 N, at most 5 cm/s.
LoadControl servo_load() {
  LoadControl load;
  load.kind = LoadControl::Kind::Servo;
  load.direction = {0, 0, -1};
  load.target = 500;
  load.gain = 1e-3;
  load.max_speed = 0.05;
  return load;
}

// A servo plate starting 2 mm above the bed closes the gap and holds 500 N within 1%.
TEST(ServoPlate, HoldsItsTargetForce) {
  const LoadControl load = servo_load();
  Simulation sim(loaded_bed(load, 0.002));
  const int plate = static_cast<int>(sim.scene().walls.size()) - 1;
  double worst = 0;
  while (sim.time() < 0.2) {
    sim.step();
    if (sim.time() >= 0.15) worst = std::max(worst, std::abs(sim.wall_driver(plate).applied_force() - load.target));
  }
  report("servo plate: largest |force - target| / target over the last 50 ms", worst / load.target, 0.0);
  EXPECT_LT(worst, 0.01 * load.target);
}

// A servo whose gain is far past what the bed's contacts allow at this step: each step's correction
// would overshoot the target by more than the gap it closes, and the plate's force would alternate
// step by step and grow (a 5,000-stone bed under a 250 kN servo did, at gain 1e-5: the contacts'
// dashpots made the loop's gain 1.8 of its limit 2). The engine caps the gain at what its contacts
// allow (docs/physics.md, "Loaded walls"), so the plate holds its target as a slower servo does.
TEST(ServoPlate, HoldsItsTargetWithAGainPastTheLoopsLimit) {
  LoadControl load = servo_load();
  load.gain = 1.0;  // 1,000x the gain above: g C alone is about 60 for this bed's contacts
  Simulation sim(loaded_bed(load, 0.002));
  const int plate = static_cast<int>(sim.scene().walls.size()) - 1;
  double worst = 0;
  while (sim.time() < 0.2) {
    sim.step();
    ASSERT_TRUE(std::isfinite(sim.wall_driver(plate).applied_force())) << "at t = " << sim.time();
    if (sim.time() >= 0.15) worst = std::max(worst, std::abs(sim.wall_driver(plate).applied_force() - load.target));
  }
  report("servo plate, gain 1 m/(N s): largest |force - target| / target over the last 50 ms", worst / load.target,
         0.0);
  EXPECT_LT(worst, 0.01 * load.target);
}

// The capped servo at the stable limit over a sphere whose dashpots relax its speed fast (linear law,
// restitution 0.05, C dt / m = 0.36): the particle answers within the step, and with the last
// step's force alone the plate's force swung between 1.4 and 16.4 N for ever around its 10 N target
// (an independent tester's scene). The servo closes the gap of the last two steps' mean force.
TEST(ServoPlate, HoldsItsTargetOverAHeavilyDampedSphereAtTheStableLimit) {
  Scene s = base_scene(LinearNormal::kName, 2500, 0, 0.25, 0.05, 0.3, 1e5);
  const double r = 0.005;
  s.gravity = {0, 0, -kG};
  s.particles.push_back(sphere({0, 0, r}, r));
  s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}, "floor"));
  const double z = 2 * r + 1e-4;
  WallInit plate{
      "press",
      1,
      PlateShape{{Vec3(-2 * r, -2 * r, z), Vec3(2 * r, -2 * r, z), Vec3(2 * r, 2 * r, z), Vec3(-2 * r, 2 * r, z)}},
      {},
      {}};
  LoadControl load;
  load.kind = LoadControl::Kind::Servo;
  load.direction = {0, 0, -1};
  load.target = 10;
  load.gain = 1e6;
  load.max_speed = 0.05;
  plate.load = load;
  s.walls.push_back(plate);
  s.time.dt = Simulation(s).time_step().stable_limit;
  s.time.steps = 13300;
  Simulation sim(s);
  const int press = 1;
  double worst = 0;
  while (sim.step_count() < sim.total_steps()) {
    sim.step();
    if (sim.step_count() > 12000) worst = std::max(worst, std::abs(sim.wall_driver(press).applied_force() - 10));
  }
  report("servo over a damped sphere at the stable limit: largest |force - target| / target, last 1,300 steps",
         worst / 10, 0.0);
  EXPECT_LT(worst, 0.01 * 10);
}

// BallastDEM's two stages: the bed settles under a plate that only rests on it, the state is saved,
// and a run continued from it with a spec that loads the plate follows the load's cycle from the
// continuation on (its clock starts there).
TEST(LoadedPlate, AContinuedRunTakesTheLoadItsSpecAdds) {
  const LoadControl load = cyclic_load();
  Scene resting = loaded_bed(load, -2e-6);  // pressed 2 um into the top layer: the bed pushes back
  resting.walls.back().load.reset();
  Simulation first(resting);
  while (first.time() < 0.05) first.step();
  std::stringstream saved;
  StateIO::write(first, saved);
  Simulation second(loaded_bed(load, -2e-6));
  StateIO::read(second, saved);
  const double t0 = second.time();
  ASSERT_NEAR(t0, first.time(), 1e-15);
  const int plate = static_cast<int>(second.scene().walls.size()) - 1;
  // the new load feels the bed's push from its first step, as a fresh run's does at t = 0
  std::printf("the bed pushes the plate with %.4g N at the continuation\n", second.wall_driver(plate).applied_force());
  EXPECT_GT(second.wall_driver(plate).applied_force(), 0);
  EXPECT_EQ(second.wall_driver(plate).applied_force(), second.boundary_loads()[plate].force.z());
  double worst = 0;
  while (second.time() < t0 + 0.6) {
    second.step();
    const double t = second.time() - t0;
    ASSERT_EQ(second.wall_driver(plate).prescribed_force(second.time()), load.force_at(t));
    if (t < 0.4) continue;  // two cycles settle the bed under the load
    worst = std::max(worst, std::abs(second.wall_driver(plate).applied_force() - (load.force_at(t) + kPlateMass * kG)));
  }
  report("continued run, load added: largest |applied - prescribed| / F_max", worst / load.f_max, 0.0);
  EXPECT_LT(worst, 0.01 * load.f_max);
}

// A prescribed motion is a function of the time since the start: a continued run cannot change it,
// and says which wall.
TEST(LoadedPlate, AContinuedRunRefusesAChangedMotion) {
  Scene moving = loaded_bed(cyclic_load(), 0.002);
  moving.walls.back().load.reset();
  moving.walls.back().motion = PrescribedMotion{};
  moving.walls.back().motion->velocity = {0, 0, -0.01};
  Simulation first(moving);
  for (int k = 0; k < 10; ++k) first.step();
  std::stringstream saved;
  StateIO::write(first, saved);
  Scene still = moving;
  still.walls.back().motion->velocity = {0, 0, -0.02};
  Simulation second(still);
  try {
    StateIO::read(second, saved);
    FAIL() << "expected the changed motion to be refused";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("walls[5] (sleeper): its prescribed motion differs from the saved run's"),
              std::string::npos)
        << e.what();
  }
}

// A mesh plate pressed down by a servo, then continued with its load dropped, stays where it was
// left, and so it does when that continued run is itself continued.
TEST(LoadedPlate, AMeshWhoseLoadWasDroppedStaysWhereItWasLeft) {
  const LoadControl servo = servo_load();
  auto scene = [&](bool loaded) {
    Scene s = loaded_bed(servo, 0.002);
    const PlateShape plate = std::get<PlateShape>(s.walls.back().shape);
    MeshShape mesh;
    mesh.vertices.assign(plate.corners.begin(), plate.corners.end());
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    mesh.source = "square";
    s.walls.back().shape = mesh;
    if (!loaded) s.walls.back().load.reset();
    return s;
  };
  auto height = [](const Simulation& sim) { return sim.meshes().back().vertices[0].z(); };
  Simulation pressed(scene(true));
  while (pressed.time() < 0.05) pressed.step();
  const double left_at = height(pressed);
  ASSERT_LT(left_at, std::get<MeshShape>(scene(true).walls.back().shape).vertices[0].z() - 1e-4)
      << "the servo moved it";
  std::stringstream first;
  StateIO::write(pressed, first);
  Simulation dropped(scene(false));
  StateIO::read(dropped, first);
  for (int k = 0; k < 100; ++k) dropped.step();
  EXPECT_EQ(height(dropped), left_at);
  std::stringstream second;
  StateIO::write(dropped, second);
  Simulation again(scene(false));
  StateIO::read(again, second);
  EXPECT_EQ(height(again), left_at);
}

}  // namespace
}  // namespace dem::test::test_wall_loads
