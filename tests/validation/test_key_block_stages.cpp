// The PDEM-EGD manual's key block, set up as its users set it up, in one staged job spec: a
// funnel-shaped closed mesh filled with a HEX packing (its `inside`), which settles in the funnel
// under gravity (NFILL), grows into contact (GROWTH, NGROWTH), is glued (BOND_MODEL) and released
// onto the slope below when the funnel goes.
#include <gtest/gtest.h>

#include <map>
#include <algorithm>
#include <string>

#include "sim/runner.hpp"
#include "sim/simulation.hpp"
#include "spec/spec_loader.hpp"

namespace dem::test::test_key_block_stages {
namespace {

// A closed frustum, narrow end down: the square at z0 of half-side a0, at z1 of half-side a1.
std::string funnel_mesh(double z0, double a0, double z1, double a1) {
  std::string v;
  auto vertex = [&](double x, double y, double z) {
    v += (v.empty() ? "" : ", ") + std::string("{\"x\": ") + std::to_string(x) + ", \"y\": " + std::to_string(y) +
         ", \"z\": " + std::to_string(z) + "}";
  };
  for (const auto& [z, a] : {std::pair{z0, a0}, std::pair{z1, a1}}) {
    vertex(-a, -a, z);
    vertex(a, -a, z);
    vertex(a, a, z);
    vertex(-a, a, z);
  }
  // bottom 1-4, top 5-8; outward normals
  const int t[12][3] = {{1, 3, 2}, {1, 4, 3}, {5, 6, 7}, {5, 7, 8}, {1, 2, 6}, {1, 6, 5},
                        {2, 3, 7}, {2, 7, 6}, {3, 4, 8}, {3, 8, 7}, {4, 1, 5}, {4, 5, 8}};
  std::string tri;
  for (const auto& f : t)
    tri += (tri.empty() ? "" : ", ") + std::string("{\"i\": ") + std::to_string(f[0]) +
           ", \"j\": " + std::to_string(f[1]) + ", \"k\": " + std::to_string(f[2]) + "}";
  return R"({"vertices": [)" + v + R"(], "triangles": [)" + tri + "]}";
}

std::string key_block_spec() {
  const std::string funnel = funnel_mesh(0.10, 0.04, 0.22, 0.08);
  return R"({
  "name": "key block in a funnel",
  "materials": [{"name": "rock", "density": 2500, "normalStiffness": 5e4},
                {"name": "steel", "rigid": true}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.2, "friction": 0.5},
                   {"a": "rock", "b": "steel", "restitution": 0.2, "friction": 0.2}],
  "lattices": [{"kind": "HEX", "material": "rock", "radius": 0.009, "spacing": 1.1, "inside": )" +
         funnel + R"(}],
  "walls": [{"name": "funnel", "material": "steel", "mesh": )" +
         funnel + R"(},
            {"name": "slope", "material": "steel", "plane": {"normal": {"x": 0.2, "z": 1}}}],
  "bonds": {"youngsModulus": 1e8, "tensileStrength": 1e9, "shearStrength": 1e9, "gapTolerance": 0.01},
  "gravity": {"z": -9.81},
  "numerics": {"localDamping": 0.3},
  "time": {"dtFraction": 0.05},
  "stages": [
    {"name": "fill", "duration": 0.3, "untilKineticEnergy": 1e-5, "minDuration": 0.05},
    {"name": "grow", "duration": 0.1, "growthFactor": 1.12},
    {"name": "settle", "duration": 0.05},
    {"name": "bond", "steps": 1, "bond": true},
    {"name": "release", "duration": 0.15, "removeWalls": ["funnel"], "localDamping": 0}
  ]
})";
}

TEST(KeyBlockStages, AFunnelFilledWithHexIsGrownBondedAndReleasedWhole) {
  Simulation sim(spec::to_scene(spec::parse_json(key_block_spec())));
  const std::size_t n = sim.particles().size();
  ASSERT_GT(n, 100u);
  std::int64_t bond_start = -1;
  std::size_t touching_at_bond = 0, bonds_glued = 0;
  double lowest_before_release = 1;
  while (sim.step_count() < sim.total_steps()) {
    const bool last_before_bond = sim.stage() == 2 && sim.step_count() + 1 == sim.stage_end_step();
    sim.record_contacts(last_before_bond);
    sim.step();
    if (last_before_bond) touching_at_bond = sim.pair_contacts().size();
    if (sim.stage() == 3 && bond_start < 0) {
      bond_start = sim.stage_start_step();
      bonds_glued = sim.bonds().bonds().size();
    }
    if (sim.stage() < 4)
      for (const Vec3& x : sim.particles().x) lowest_before_release = std::min(lowest_before_release, x.z());
  }
  ASSERT_GE(bond_start, 0);
  // the fill settled before its longest time, and every pair touching then was glued
  EXPECT_LT(bond_start, static_cast<std::int64_t>((0.3 + 0.1 + 0.05) / sim.dt()));
  EXPECT_GE(bonds_glued, touching_at_bond);
  EXPECT_GT(static_cast<double>(bonds_glued) / static_cast<double>(n), 1.5);  // a packed block (3 contacts a sphere)
  EXPECT_GT(lowest_before_release, 0.10);                                     // held by the funnel until then
  // released, it fell onto the slope as one block
  // released, it fell onto the slope as one block: the only other fragments are single spheres
  // that touched nothing when the bonds were glued (rattlers in the packing's cages)
  const std::vector<int> part = sim.fragments();
  std::map<int, int> sizes;
  for (int p : part) ++sizes[p];
  int largest = 0, singles = 0;
  for (const auto& [fragment, size] : sizes) {
    largest = std::max(largest, size);
    singles += size == 1;
  }
  EXPECT_EQ(largest + singles, static_cast<int>(n));
  EXPECT_LE(singles, static_cast<int>(n) / 20);
  double lowest = 1;
  for (const Vec3& x : sim.particles().x) lowest = std::min(lowest, x.z());
  EXPECT_LT(lowest, 0.05);
  EXPECT_FALSE(sim.first_non_finite());
}

}  // namespace
}  // namespace dem::test::test_key_block_stages
