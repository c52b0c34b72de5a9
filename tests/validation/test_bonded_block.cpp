// A bonded block thrown at a plane (the landslide key block in miniature): with no strength it
// falls apart into single grains, with a huge strength it bounces whole, and in between it breaks
// into fragments, more of them and more broken bonds the weaker it is.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "support/report.hpp"
#include "support/scenes.hpp"

namespace dem::test::test_bonded_block {
namespace {

constexpr double kR = 0.005;
constexpr int kSide = 13;  // 2197 spheres

struct Outcome {
  int fragments = 0;
  int broken = 0;
  int bonds = 0;
  double rebound = 0;  // mean vertical velocity at the end, m/s
};

Outcome throw_block(double strength) {
  Scene s = base_scene(LinearNormal::kName, 2600, 1e8, 0.25, 0.5, 0.5, 1e5);
  for (int k = 0; k < kSide; ++k)
    for (int j = 0; j < kSide; ++j)
      for (int i = 0; i < kSide; ++i)
        s.particles.push_back(sphere({2 * kR * i, 2 * kR * j, kR * 1.001 + 2 * kR * k}, kR, {0, 0, -2.0}));
  s.walls.push_back(plane(Vec3::Zero(), Vec3::UnitZ()));
  BondSettings bonds;
  bonds.youngs_modulus = 2e7;
  bonds.tensile_strength = strength;
  bonds.shear_strength = strength;
  bonds.strength_spread = 0.3;  // a perfect lattice with equal bonds would only split into slabs
  bonds.seed = 11;
  s.bonds = bonds;
  Simulation sim(s);
  while (sim.time() < 0.02) sim.step();
  Outcome o;
  const std::vector<int> part = sim.fragments();
  o.fragments = static_cast<int>(std::set<int>(part.begin(), part.end()).size());
  const BondCounts c = sim.bonds().counts();
  o.bonds = c.intact + c.tension + c.shear;
  o.broken = c.tension + c.shear;
  for (const Vec3& v : sim.particles().v) o.rebound += v.z() / static_cast<double>(sim.particles().size());
  return o;
}

TEST(BondedBlock, BreaksMoreTheWeakerItIs) {
  const double strengths[] = {0.0, 3e3, 1.5e5, 1e12};
  Outcome o[4];
  for (int k = 0; k < 4; ++k) {
    o[k] = throw_block(strengths[k]);
    report("bonded block, strength " + std::to_string(strengths[k]) + " Pa: fragments", o[k].fragments, 0.0);
    report("bonded block, strength " + std::to_string(strengths[k]) + " Pa: broken bonds", o[k].broken, 0.0);
  }
  const int n = kSide * kSide * kSide;
  EXPECT_EQ(o[0].bonds, 3 * kSide * kSide * (kSide - 1));  // the cubic lattice's neighbours
  // no strength: every bond goes at once, the grains are loose
  EXPECT_EQ(o[0].broken, o[0].bonds);
  EXPECT_EQ(o[0].fragments, n);
  // a huge strength: one body that bounced
  EXPECT_EQ(o[3].broken, 0);
  EXPECT_EQ(o[3].fragments, 1);
  EXPECT_GT(o[3].rebound, 0.2);
  // in between: fragments, more and with more broken bonds the weaker the block
  EXPECT_GT(o[1].fragments, o[2].fragments);
  EXPECT_GT(o[2].fragments, 1);
  EXPECT_GT(o[1].broken, o[2].broken);
  EXPECT_GT(o[2].broken, 0);
  EXPECT_LT(o[1].fragments, n);
}

}  // namespace
}  // namespace dem::test::test_bonded_block
