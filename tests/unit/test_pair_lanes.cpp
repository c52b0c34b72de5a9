// The force loop evaluates sphere pairs four at a time (AVX2 lanes) or one at a time; both must give
// the same bits for every contact law, with mixed materials and sizes, sliding and sticking
// contacts and partings, and in a pack larger than one particle block.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <tuple>

#include "support/scenes.hpp"

namespace dem::test {
namespace {

struct LawCase {
  std::string_view normal;
  bool no_tensile;
  double friction;
  std::string_view rolling;
};

// A loose heap of two materials and two sizes thrown at a floor: contacts open, close and slide.
Scene heap(const LawCase& law) {
  Scene s = base_scene(law.normal, 2500, 1e7, 0.25, 0.5, law.friction, 2e4);
  s.materials.insert(s.materials.begin() + 1, Material{"q", 1800, 3e7, 0.3, 5e4, false});
  s.interactions.clear();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      s.interactions.push_back({0.3 + 0.1 * ((a + b) % 3), law.friction * (1 + 0.2 * (a + b)), 0});
  if (law.rolling != NoRolling::kName) set_rolling(s, law.rolling, 0.1);
  s.contact.no_tensile_force = law.no_tensile;
  s.gravity = {0, 0, -9.81};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i) {
        const double r = (i + j + k) % 2 == 0 ? 0.0026 : 0.0018;
        ParticleInit p = sphere({0.0045 * i + 0.0003 * u(rng), 0.0045 * j + 0.0003 * u(rng), 0.0045 * k + 0.003}, r,
                                {0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng)}, {20 * u(rng), 20 * u(rng), 20 * u(rng)});
        p.material = (i + 2 * j + k) % 2;
        s.particles.push_back(p);
      }
  s.walls.push_back(WallInit{"floor", 2, PlaneShape{{0, 0, 0}, {0, 0, 1}}, {}, {}});
  s.time.steps = 400;
  return s;
}

struct Bits {
  std::vector<Vec3> x, v, w;
};

Bits run_with_lanes(const LawCase& law, int lanes) {
  set_pair_lanes(lanes);
  Simulation sim(heap(law));
  for (int k = 0; k < 400; ++k) sim.step();
  set_pair_lanes(1);
  return {sim.particles().x, sim.particles().v, sim.particles().w};
}

std::string law_name(const ::testing::TestParamInfo<LawCase>& info) {
  const LawCase& c = info.param;
  const std::string rolling = c.rolling == NoRolling::kName    ? "NoRolling"
                              : c.rolling == CdtRolling::kName ? "Cdt"
                                                               : "Epsd";
  return std::string(c.normal == LinearNormal::kName ? "Linear" : "Hertz") + (c.no_tensile ? "NoTension" : "") +
         (c.friction > 0 ? "Friction" : "Frictionless") + rolling;
}

class PairLanes : public ::testing::TestWithParam<LawCase> {};

TEST_P(PairLanes, FourLanesGiveTheBitsOfOne) {
  int lanes = 1;
  try {
    set_pair_lanes(4);
    lanes = 4;
  } catch (const std::invalid_argument&) {
    GTEST_SKIP() << "this CPU has no AVX2: only the one-lane loop runs here";
  }
  ASSERT_EQ(lanes, 4);
  const Bits one = run_with_lanes(GetParam(), 1);
  const Bits four = run_with_lanes(GetParam(), 4);
  int moved = 0;
  for (std::size_t i = 0; i < one.x.size(); ++i) {
    ASSERT_EQ(one.x[i], four.x[i]) << "position of particle " << i;
    ASSERT_EQ(one.v[i], four.v[i]) << "velocity of particle " << i;
    ASSERT_EQ(one.w[i], four.w[i]) << "angular velocity of particle " << i;
    moved += one.w[i].norm() > 0;
  }
  EXPECT_GT(moved, 100);
}

INSTANTIATE_TEST_SUITE_P(Laws, PairLanes,
                         ::testing::Values(LawCase{LinearNormal::kName, false, 0.5, NoRolling::kName},
                                           LawCase{LinearNormal::kName, true, 0.0, NoRolling::kName},
                                           LawCase{LinearNormal::kName, false, 0.3, CdtRolling::kName},
                                           LawCase{HertzNormal::kName, true, 0.5, EpsdRolling::kName},
                                           LawCase{HertzNormal::kName, false, 0.2, CdtRolling::kName},
                                           LawCase{HertzNormal::kName, false, 0.0, NoRolling::kName}),
                         law_name);

// A jostled cubic pack of 5,832 spheres: more than one particle block (4,096), so pairs that cross
// into a later block leave their share in a deferred slot, and rows of ~3 pairs share groups.
TEST(PairLanesAcrossBlocks, FourLanesGiveTheBitsOfOne) {
  try {
    set_pair_lanes(4);
  } catch (const std::invalid_argument&) {
    GTEST_SKIP() << "this CPU has no AVX2: only the one-lane loop runs here";
  }
  auto run = [](int lanes) {
    Scene s = base_scene(LinearNormal::kName, 2500, 1e7, 0.25, 0.5, 0.5, 2e4);
    s.gravity = {0, 0, -9.81};
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    const double r = 0.001, spacing = 0.001998;  // neighbours overlap by 2 um, give or take 0.6 um
    for (int k = 0; k < 18; ++k)
      for (int j = 0; j < 18; ++j)
        for (int i = 0; i < 18; ++i)
          s.particles.push_back(sphere({spacing * i + 3e-7 * u(rng), spacing * j + 3e-7 * u(rng), r + spacing * k}, r,
                                       {0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng)}));
    s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}, "floor"));
    set_pair_lanes(lanes);
    Simulation sim(std::move(s));
    for (int k = 0; k < 100; ++k) sim.step();
    set_pair_lanes(1);
    return Bits{sim.particles().x, sim.particles().v, sim.particles().w};
  };
  const Bits one = run(1), four = run(4);
  ASSERT_EQ(one.x.size(), 5832u);
  int spinning = 0;  // friction turned them: the contacts were there
  for (std::size_t i = 0; i < one.x.size(); ++i) {
    ASSERT_EQ(one.x[i], four.x[i]) << "position of particle " << i;
    ASSERT_EQ(one.v[i], four.v[i]) << "velocity of particle " << i;
    ASSERT_EQ(one.w[i], four.w[i]) << "angular velocity of particle " << i;
    spinning += one.w[i].norm() > 0;
  }
  EXPECT_GT(spinning, 5000);
}

TEST(PairLanesSetting, RejectsAWidthThatDoesNotExist) {
  EXPECT_THROW(set_pair_lanes(3), std::invalid_argument);
  EXPECT_NO_THROW(set_pair_lanes(1));
  EXPECT_EQ(pair_lanes(), 1);
}

}  // namespace
}  // namespace dem::test
