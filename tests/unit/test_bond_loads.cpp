// Bonds loaded several at a time (bond_loads, kBondLanes in lanes) give the bits of bond_load on each
// bond in turn: the loads, the bond's kept state (forces, moments) and its break, for parallel and
// contact bonds, stretched, sheared, bent and twisted, some past their strength.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "bonds/bond_law.hpp"
#include "bonds/bond_models.hpp"
#include "core/rotation.hpp"

namespace dem::test::test_bond_loads {
namespace {

bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0; }

bool same_bits(const Bond& a, const Bond& b) { return std::memcmp(&a, &b, sizeof(Bond)) == 0; }

TEST(BondLoads, ManyAtOnceGiveTheBitsOfOneAtATime) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  auto random_turn = [&](double max_angle) {
    return rotation_by(max_angle * std::abs(u(rng)) * Vec3(u(rng), u(rng), u(rng)).normalized());
  };
  // 4 lanes twice and 3 left over (bond_loads' remainder), each bond glued in a random pose and
  // then moved, turned and strained; a third of them weak enough to break in tension or shear
  constexpr int kCount = 2 * kBondLanes + 3;
  std::vector<Bond> bonds;
  std::vector<BondEnd> ends_i, ends_j;
  for (int k = 0; k < kCount; ++k) {
    BondSettings settings;
    settings.model = k % 3 == 2 ? ContactBond::kName : ParallelBond::kName;
    settings.youngs_modulus = 5e9;
    settings.tensile_strength = k % 3 == 1 ? 1e5 : 1e12;
    settings.shear_strength = k % 5 == 1 ? 1e5 : 2e12;
    const BondEnd i0{Vec3(u(rng), u(rng), u(rng)) * 0.01, random_turn(3.1), 0.012};
    const Vec3 dir = Vec3(u(rng), u(rng), u(rng)).normalized();
    const BondEnd j0{i0.x - (0.02 + 1e-4 * u(rng)) * dir, random_turn(3.1), 0.009};
    Bond b = bond_between(settings, i0.radius, j0.radius, 1.0);
    glue(b, i0, j0);
    bonds.push_back(b);
    // strained: i moved by up to 0.2 mm and turned by up to 0.05 rad, j turned too
    ends_i.push_back({i0.x + 2e-4 * Vec3(u(rng), u(rng), u(rng)), random_turn(0.05) * i0.q, i0.radius});
    ends_j.push_back({j0.x, random_turn(0.05) * j0.q, j0.radius});
  }
  std::vector<Bond> one_at_a_time = bonds, at_once = bonds;
  std::vector<BondLoad> expected;
  for (int k = 0; k < kCount; ++k) expected.push_back(bond_load(one_at_a_time[k], ends_i[k], ends_j[k], 0.25));
  std::vector<Bond*> group;
  for (Bond& b : at_once) group.push_back(&b);
  std::vector<BondLoad> loads(kCount);
  bond_loads(group.data(), ends_i.data(), ends_j.data(), kCount, 0.25, loads.data());

  int broken = 0, loaded = 0;
  for (int k = 0; k < kCount; ++k) {
    EXPECT_TRUE(same_bits(loads[k].force, expected[k].force)) << "bond " << k;
    EXPECT_TRUE(same_bits(loads[k].moment_i, expected[k].moment_i)) << "bond " << k;
    EXPECT_TRUE(same_bits(loads[k].moment_j, expected[k].moment_j)) << "bond " << k;
    EXPECT_TRUE(same_bits(at_once[k], one_at_a_time[k])) << "bond " << k << ": its kept state";
    broken += at_once[k].state != BondBreak::Intact;
    loaded += expected[k].force.norm() > 0 && expected[k].moment_i.norm() > 0;
  }
  // the draw covers what it should: bonds that broke, and loaded bonds that did not
  EXPECT_GE(broken, 3);
  EXPECT_GE(loaded, 4);
}

}  // namespace
}  // namespace dem::test::test_bond_loads
