// Determinism: the same spec gives bit-identical ANIMATION_3D.dat on 1 and 2 threads, run after run.
// The scene is big enough for several particle blocks, neighbour rebuilds and spatial re-sorts, and
// has walls (a plate and a mesh floor), friction and rolling springs, so every parallel path is
// exercised.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <tuple>
#include <vector>

#include "output/legacy_output.hpp"
#include "support/meshes.hpp"
#include "spec/spec_loader.hpp"
#include "support/scenes.hpp"

namespace dem::test::test_determinism {
namespace {

Scene falling_heap() {
  Scene s = base_scene(HertzNormal::kName, 2500, 1e7, 0.25, 0.4, 0.5);
  set_rolling(s, EpsdRolling::kName, 0.05);
  s.gravity = {0, 0, -9.81};
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.0005, 0.0005);
  for (int k = 0; k < 20; ++k)
    for (int j = 0; j < 20; ++j)
      for (int i = 0; i < 25; ++i) {
        const double r = (i + j + k) % 3 == 0 ? 0.004 : 0.0025;  // two sizes: two grid levels
        s.particles.push_back(sphere({0.01 * i + jitter(rng), 0.01 * j + jitter(rng), 0.01 * k + 0.005}, r,
                                     {-0.5 + 0.2 * jitter(rng) * 1000, 0, 0}));
      }
  // the floor as a triangle mesh (mesh contacts are summed per particle, walls' totals serially)
  s.walls.push_back(mesh_wall(grid_rectangle({-0.05, -0.05, 0}, {0.4, 0, 0}, {0, 0.3, 0}, 16, 12), "floor"));
  // a side plate the heap drifts towards (x = -0.01, facing +x)
  s.walls.push_back(
      WallInit{"plate",
               1,
               PlateShape{{Vec3(-0.01, -0.1, 0), Vec3(-0.01, 0.3, 0), Vec3(-0.01, 0.3, 0.3), Vec3(-0.01, -0.1, 0.3)}},
               {},
               {}});
  s.time.steps = 3000;
  s.outputs.every_steps = 500;
  s.outputs.animation = true;
  return s;
}

std::string run_to_text(int threads) {
  Scene s = falling_heap();
  s.numerics.threads = threads;
  Simulation sim(s);
  const auto path = std::filesystem::temp_directory_path() /
                    ("dem_determinism_" + std::to_string(threads) + "_" + std::to_string(::getpid()) + ".dat");
  {
    AnimationWriter writer(path.string(), sim);
    const RunOutcome outcome = run(sim, {&writer});
    EXPECT_TRUE(outcome.ok) << outcome.error;
    EXPECT_GT(sim.neighbor_builds(), 2);
    int on_floor = 0;
    for (const WallContact& c : sim.wall_contacts()) on_floor += c.wall == 0;
    EXPECT_GT(on_floor, 0);  // the heap has reached the mesh floor
  }
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  std::filesystem::remove(path);
  return text.str();
}

TEST(Determinism, OneAndTwoThreadsWriteIdenticalBytes) {
  const std::string one = run_to_text(1);
  const std::string two = run_to_text(2);
  ASSERT_GT(one.size(), 100000u);
  EXPECT_TRUE(one == two) << "ANIMATION_3D.dat differs between 1 and 2 threads";
}

TEST(Determinism, RepeatedRunsWriteIdenticalBytes) { EXPECT_TRUE(run_to_text(2) == run_to_text(2)); }

// The work of constant external forces (the energy ledger, Energy.csv's column, results.json's
// energy input): 6,000 free spheres in three particle blocks, each pushed by a force of its own, summed
// block by block in block order, so bit-identical on 1 and 2 threads. It was summed per thread's range,
// whose grouping changes with the thread count (an independent check found the column's last digits
// differing).
TEST(Determinism, TheWorkOfExternalForcesIsTheSameOnOneAndTwoThreads) {
  auto work_with = [](int threads) {
    Scene s = base_scene(LinearNormal::kName, 2500, 0, 0.25, 1.0, 0.0, 1e4);
    for (int k = 0; k < 6000; ++k) {
      ParticleInit p = sphere({0.01 * (k % 100), 0.01 * (k / 100), 0}, 0.002, {0.1 * std::sin(k), 0.3, 0});
      p.force = {1e-3 * std::cos(0.7 * k), 2e-3 * std::sin(1.3 * k), 1e-4 * k};
      s.particles.push_back(p);
    }
    s.time.steps = 20;
    s.numerics.threads = threads;
    Simulation sim(s);
    const RunOutcome outcome = run(sim, {});
    EXPECT_TRUE(outcome.ok) << outcome.error;
    return sim.energy_input().external;
  };
  const double one = work_with(1), two = work_with(2);
  EXPECT_NE(one, 0.0);
  EXPECT_EQ(std::memcmp(&one, &two, sizeof one), 0) << std::hexfloat << one << " on 1 thread, " << two << " on 2";
}

// A bonded block (FCC, 4,248 bonds: enough to load them on both threads) thrown at a plane,
// breaking 40% of its bonds: the same particles and the same bonds, bit for bit, on 1 and 2 threads.
TEST(Determinism, ABondedBlockBreaksTheSameOnOneAndTwoThreads) {
  auto run_bonded = [](int threads) {
    const std::string spec = R"({"materials": [{"name": "rock", "density": 2600, "normalStiffness": 2e7},
        {"name": "ground", "rigid": true}],
      "interactions": [{"a": "rock", "b": "rock", "restitution": 0.3, "friction": 0.5},
                       {"a": "rock", "b": "ground", "restitution": 0.3, "friction": 0.3}],
      "contact": {"normal": "LINEAR"},
      "lattices": [{"kind": "FCC", "min": {"z": 0.05}, "max": {"x": 1, "y": 1, "z": 0.8}, "radius": 0.05,
                    "material": "rock", "velocity": {"x": 1, "z": -6}}],
      "bonds": {"youngsModulus": 5e7, "tensileStrength": 5e5, "shearStrength": 5e5, "strengthSpread": 0.3, "seed": 3},
      "walls": [{"material": "ground", "plane": {"point": {}, "normal": {"z": 1}}}],
      "gravity": {"z": -9.81}, "time": {"steps": 1500}, "numerics": {"threads": )" +
                             std::to_string(threads) + "}}";
    Simulation sim(spec::to_scene(spec::parse_json(spec)));
    const RunOutcome outcome = run(sim, {});
    EXPECT_TRUE(outcome.ok) << outcome.error;
    return std::pair{sim.particles().x, sim.state().bonds.counts()};
  };
  const auto [x1, bonds1] = run_bonded(1);
  const auto [x2, bonds2] = run_bonded(2);
  std::printf("bonds: %d intact, %d broken in tension, %d in shear\n", bonds1.intact, bonds1.tension, bonds1.shear);
  EXPECT_GT(bonds1.intact + bonds1.tension + bonds1.shear, 2048);
  EXPECT_GT(bonds1.tension + bonds1.shear, 0) << "the impact breaks bonds";
  EXPECT_GT(bonds1.intact, 0);
  EXPECT_EQ(bonds1.intact, bonds2.intact);
  EXPECT_EQ(bonds1.tension, bonds2.tension);
  EXPECT_TRUE(x1 == x2) << "the particles' positions differ between 1 and 2 threads";
}

// A heap of 1,400 tumbling clumps of three spheres (4,200 members: the bodies' loops and the members'
// passes are both shared between the threads, as are the particles' blocks) falling onto a plane,
// locally damped: the same members, bodies and orientations, bit for bit, on 1 and 2 threads.
Scene clump_heap() {
  std::ostringstream s;
  s.precision(17);
  s << R"({"name": "clump heap",
  "materials": [{"name": "rock", "density": 2650, "normalStiffness": 2e5}, {"name": "steel", "rigid": true}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5, "friction": 0.5},
                   {"a": "rock", "b": "steel", "restitution": 0.5, "friction": 0.5}],
  "contact": {"normal": "LINEAR", "rolling": "NONE"},
  "numerics": {"localDamping": 0.1},
  "clumpShapes": [{"name": "odd", "spheres": [{"center": {}, "radius": 0.01}, {"center": {"x": 0.012}, "radius": 0.006},
                                               {"center": {"y": 0.009, "z": 0.004}, "radius": 0.007}]}],
  "walls": [{"material": "steel", "plane": {"point": {}, "normal": {"z": 1}}}],
  "gravity": {"z": -9.81},
  "time": {"dt": 3e-5, "steps": 1600},
  "outputs": {"everySteps": 1000000},
  "clumps": [)";
  for (int k = 0; k < 1400; ++k) {
    // seven layers 45 mm apart (a body reaches 21 mm from its centroid), every other one falling faster
    const double x = 0.045 * (k % 20), y = 0.045 * ((k / 20) % 10), z = 0.025 + 0.045 * (k / 200);
    s << (k ? ", " : "") << R"({"shape": "odd", "material": "rock", "position": {"x": )" << x << R"(, "y": )" << y
      << R"(, "z": )" << z << R"(}, "rotationAxis": {"x": 1, "y": )" << k % 7 << R"(}, "rotationDegrees": )" << 13 * k
      << R"(, "velocity": {"z": )" << -1.0 - 0.8 * ((k / 200) % 2) << R"(}, "angularVelocity": {"z": )" << (k % 5) - 2
      << R"(, "x": )" << (k % 3) - 1 << "}}";
  }
  s << "]}";
  return spec::to_scene(spec::parse_json(s.str()));
}

TEST(Determinism, ManyClumpsTumbleTheSameOnOneAndTwoThreads) {
  auto run_with = [](int threads) {
    Scene s = clump_heap();
    s.numerics.threads = threads;
    Simulation sim(s);
    EXPECT_GE(sim.particles().size(), 4096u);
    std::size_t most_contacts = 0;  // the bodies collide and part: the most at any 50th step
    while (sim.step_count() < sim.total_steps()) {
      sim.step();
      if (sim.step_count() % 50 == 0) most_contacts = std::max(most_contacts, sim.contact_summary().contacts);
    }
    std::vector<Eigen::Vector4d> orientation;
    for (const RigidRotation& r : sim.state().bodies.rotation) orientation.push_back(r.orientation.coeffs());
    return std::tuple{sim.particles().x, sim.particles().v, sim.particles().w, orientation, most_contacts};
  };
  const auto one = run_with(1), two = run_with(2);
  EXPECT_GT(std::get<4>(one), 100u) << "the bodies collide (127 contacts at most, measured)";
  EXPECT_TRUE(std::get<0>(one) == std::get<0>(two)) << "positions";
  EXPECT_TRUE(std::get<1>(one) == std::get<1>(two)) << "velocities";
  EXPECT_TRUE(std::get<2>(one) == std::get<2>(two)) << "spins";
  EXPECT_TRUE(std::get<3>(one) == std::get<3>(two)) << "the bodies' orientations";
}

}  // namespace
}  // namespace dem::test::test_determinism
