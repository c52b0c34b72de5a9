// Tests of the Verlet neighbour list (engine/neighbor/neighbor_list.hpp): the pairs found against a
// brute-force O(n^2) search, the row layout, thread independence, and the carry-over of contact
// history through a spatial re-sort.
#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "neighbor/neighbor_list.hpp"

namespace dem {
namespace {

using Pair = std::pair<int, int>;

// Particles with every per-particle array sized (permute() touches all of them).
Particles make_particles(const std::vector<Vec3>& x, const std::vector<double>& radius) {
  Particles p;
  const std::size_t n = x.size();
  p.x = x;
  p.radius = radius;
  p.v.assign(n, Vec3::Zero());
  p.w.assign(n, Vec3::Zero());
  p.f.assign(n, Vec3::Zero());
  p.t.assign(n, Vec3::Zero());
  p.mass.assign(n, 1.0);
  p.inv_mass.assign(n, 1.0);
  p.inv_inertia.assign(n, 1.0);
  p.material.assign(n, 0);
  p.id.resize(n);
  std::iota(p.id.begin(), p.id.end(), 0);
  return p;
}

// n particles uniformly in a cube of side `box`, radii drawn from `radii` (uniformly among them).
Particles random_particles(int n, double box, const std::vector<double>& radii, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(0.0, box);
  std::uniform_int_distribution<std::size_t> pick(0, radii.size() - 1);
  std::vector<Vec3> x(n);
  std::vector<double> r(n);
  for (int i = 0; i < n; ++i) {
    x[i] = Vec3(pos(rng), pos(rng), pos(rng));
    r[i] = radii[pick(rng)];
  }
  return make_particles(x, r);
}

// Radii drawn continuously in [r_min, r_max].
Particles random_polydisperse(int n, double box, double r_min, double r_max, unsigned seed) {
  Particles p = random_particles(n, box, {1.0}, seed);
  std::mt19937 rng(seed + 1);
  std::uniform_real_distribution<double> r(r_min, r_max);
  for (double& ri : p.radius) ri = r(rng);
  return p;
}

// The definition of the list, checked pair by pair: i < j and |x_i - x_j| < r_i + r_j + skin.
std::set<Pair> brute_force_pairs(const Particles& p, double skin) {
  std::set<Pair> pairs;
  const int n = static_cast<int>(p.size());
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const double cut = p.radius[i] + p.radius[j] + skin;
      if ((p.x[i] - p.x[j]).squaredNorm() < cut * cut) pairs.emplace(i, j);
    }
  return pairs;
}

std::set<Pair> listed_pairs(const NeighborList& list) {
  std::set<Pair> pairs;
  const int n = static_cast<int>(list.row_start.size()) - 1;
  for (int i = 0; i < n; ++i)
    for (int k = list.row_start[i]; k < list.row_start[i + 1]; ++k) pairs.emplace(i, list.partner[k]);
  return pairs;
}

NeighborList build(const Particles& p, double skin, bool keep_roll = false) {
  NeighborList list;
  build_neighbor_list(p, {skin, keep_roll}, NeighborList{}, {}, list);
  return list;
}

// The compressed-row layout: n + 1 monotone offsets ending at the pair count, each row strictly
// ascending (sorted, no duplicates) with every partner j > i, history arrays sized like the pairs.
void expect_well_formed(const NeighborList& list, int n) {
  ASSERT_EQ(list.row_start.size(), static_cast<std::size_t>(n + 1));
  EXPECT_EQ(list.row_start.front(), 0);
  EXPECT_EQ(list.row_start.back(), static_cast<int>(list.partner.size()));
  EXPECT_EQ(list.shear.size(), list.partner.size());
  for (int i = 0; i < n; ++i) {
    ASSERT_LE(list.row_start[i], list.row_start[i + 1]) << "row " << i;
    for (int k = list.row_start[i]; k < list.row_start[i + 1]; ++k) {
      EXPECT_GT(list.partner[k], i) << "row " << i;
      EXPECT_LT(list.partner[k], n) << "row " << i;
      if (k > list.row_start[i]) {
        EXPECT_LT(list.partner[k - 1], list.partner[k]) << "row " << i << " not sorted";
      }
    }
  }
}

// Compares with the brute force and reports the first few differences (not thousands of lines).
void expect_matches_brute_force(const Particles& p, double skin) {
  const NeighborList list = build(p, skin);
  expect_well_formed(list, static_cast<int>(p.size()));
  const std::set<Pair> expected = brute_force_pairs(p, skin);
  const std::set<Pair> got = listed_pairs(list);
  // Every pair once: duplicates would make the set smaller than the list.
  EXPECT_EQ(got.size(), list.pair_count());
  std::vector<Pair> missing, extra;
  std::set_difference(expected.begin(), expected.end(), got.begin(), got.end(), std::back_inserter(missing));
  std::set_difference(got.begin(), got.end(), expected.begin(), expected.end(), std::back_inserter(extra));
  EXPECT_TRUE(missing.empty()) << missing.size() << " pairs missing, first (" << missing[0].first << ", "
                               << missing[0].second << ") with skin " << skin;
  EXPECT_TRUE(extra.empty()) << extra.size() << " pairs too many, first (" << extra[0].first << ", " << extra[0].second
                             << ") with skin " << skin;
  // The comparison means something only if there are pairs to find.
  EXPECT_GT(expected.size(), p.size() / 2);
}

// Restores the OpenMP thread count however a test ends.
class ThreadCount {
 public:
  ThreadCount() : saved_(omp_get_max_threads()) {}
  ~ThreadCount() { omp_set_num_threads(saved_); }

 private:
  int saved_;
};

// ---------------------------------------------------------------------------------------------
// Pairs found

TEST(NeighborList, MonodisperseMatchesBruteForceForSeveralSkins) {
  // 2000 particles: several 512-particle blocks of the parallel search.
  const Particles p = random_particles(2000, 0.3, {0.01}, 1);
  for (double skin : {0.0, 0.001, 0.005, 0.02}) expect_matches_brute_force(p, skin);
}

TEST(NeighborList, TenToOneRadiusRatioInThreeSizeLevelsMatchesBruteForce) {
  // 0.01, 0.03 and 0.1 fall in three different factor-2 size levels (0, 1 and 3): small particles
  // must find the large ones in the large particles' grid, and the reverse.
  const Particles p = random_particles(2000, 0.5, {0.01, 0.03, 0.1}, 2);
  for (double skin : {0.0, 0.002, 0.01, 0.05}) expect_matches_brute_force(p, skin);
}

TEST(NeighborList, ContinuousTenToOneRadiiMatchBruteForce) {
  // Radii spread over [0.01, 0.1]: every size level is populated, up to the level boundaries.
  const Particles p = random_polydisperse(1500, 0.5, 0.01, 0.1, 3);
  for (double skin : {0.0, 0.003, 0.03}) expect_matches_brute_force(p, skin);
}

TEST(NeighborList, FewLargeAmongManySmallMatchesBruteForce) {
  // A 10:1 mixture dominated by small particles: the large level has only a handful of members.
  Particles p = random_particles(1500, 0.4, {0.01}, 4);
  for (int i = 0; i < 1500; i += 300) p.radius[i] = 0.1;
  expect_matches_brute_force(p, 0.004);
}

TEST(NeighborList, FarOutliersEnlargeTheCellsButNoPairIsLost) {
  // A few particles far away stretch the bounding box: the grid grows its cells to stay small
  // (cell_grid.cpp), which must not lose pairs in the dense cluster.
  Particles p = random_particles(1000, 0.2, {0.01, 0.02}, 5);
  p.x[10] = Vec3(1e4, 0, 0);
  p.x[20] = Vec3(0, -1e4, 3e3);
  p.x[30] = Vec3(1e4 + 0.015, 0, 0);  // still touches particle 10
  const std::set<Pair> expected = brute_force_pairs(p, 0.002);
  ASSERT_TRUE(expected.count({10, 30}));
  EXPECT_EQ(listed_pairs(build(p, 0.002)), expected);
}

TEST(NeighborList, PairJustInsideTheCutIsListedAndJustOutsideIsNot) {
  // Radii 0.5 and 0.25, skin 0.1: the cut-off distance is 0.85.
  const Particles p = make_particles({Vec3(0, 0, 0), Vec3(0.8499, 0, 0), Vec3(0, 0.8501, 0)}, {0.5, 0.25, 0.25});
  const std::set<Pair> got = listed_pairs(build(p, 0.1));
  EXPECT_TRUE(got.count({0, 1}));
  EXPECT_FALSE(got.count({0, 2}));
}

TEST(NeighborList, EmptyAndSingleParticleGiveNoPairs) {
  const NeighborList none = build(make_particles({}, {}), 0.1);
  EXPECT_EQ(none.row_start, std::vector<int>{0});
  EXPECT_EQ(none.pair_count(), 0u);
  const NeighborList one = build(make_particles({Vec3(1, 2, 3)}, {0.5}), 0.1);
  EXPECT_EQ(one.row_start, (std::vector<int>{0, 0}));
  EXPECT_EQ(one.pair_count(), 0u);
}

TEST(NeighborList, CoincidentParticlesAreAllPaired) {
  // Ten particles at one point: all 45 pairs, each once.
  const Particles p = make_particles(std::vector<Vec3>(10, Vec3(0.1, 0.2, 0.3)), std::vector<double>(10, 0.01));
  const NeighborList list = build(p, 0.0);
  expect_well_formed(list, 10);
  EXPECT_EQ(list.pair_count(), 45u);
}

TEST(NeighborList, SameListWithOneAndTwoThreads) {
  ThreadCount restore;
  // Past kParallelMinParticles, below which the search runs on one thread whatever the count (3000
  // particles, as here before, never made a team of two); the box grown to keep the density.
  const Particles p = random_particles(6000, 0.57, {0.01, 0.03, 0.1}, 6);
  ASSERT_GE(static_cast<int>(p.size()), kParallelMinParticles);
  omp_set_num_threads(1);
  const NeighborList one = build(p, 0.004);
  omp_set_num_threads(2);
  const NeighborList two = build(p, 0.004);
  EXPECT_EQ(one.row_start, two.row_start);
  EXPECT_EQ(one.partner, two.partner);
  EXPECT_GT(one.pair_count(), 1000u);
}

// ---------------------------------------------------------------------------------------------
// spatial_order

bool is_permutation_of_indices(std::vector<int> order, int n) {
  if (static_cast<int>(order.size()) != n) return false;
  std::sort(order.begin(), order.end());
  for (int k = 0; k < n; ++k)
    if (order[k] != k) return false;
  return true;
}

TEST(SpatialOrder, ReturnsAPermutation) {
  const Particles p = random_particles(2500, 0.3, {0.01, 0.05}, 7);
  const std::vector<int> order = spatial_order(p, 0.03);
  EXPECT_TRUE(is_permutation_of_indices(order, 2500));
  // Random input is not already in grid order: the sort must actually move particles.
  std::vector<int> identity(2500);
  std::iota(identity.begin(), identity.end(), 0);
  EXPECT_NE(order, identity);
}

TEST(SpatialOrder, EdgeCasesAreStillPermutations) {
  EXPECT_TRUE(spatial_order(make_particles({}, {}), 0.1).empty());
  EXPECT_EQ(spatial_order(make_particles({Vec3(1, 1, 1)}, {0.1}), 0.1), std::vector<int>{0});
  // All at one point, and a cell size far larger than the cloud: one cell, order kept (stable).
  const Particles same = make_particles(std::vector<Vec3>(50, Vec3(0.5, 0.5, 0.5)), std::vector<double>(50, 0.1));
  std::vector<int> identity(50);
  std::iota(identity.begin(), identity.end(), 0);
  EXPECT_EQ(spatial_order(same, 0.2), identity);
  // Far outliers (the grid must grow its cells rather than allocate billions).
  Particles spread = random_particles(300, 0.1, {0.01}, 8);
  spread.x[0] = Vec3(1e6, -1e6, 1e6);
  EXPECT_TRUE(is_permutation_of_indices(spatial_order(spread, 0.02), 300));
}

// ---------------------------------------------------------------------------------------------
// Contact history through a re-sort

// A history vector that names its pair (old indices, i < j), so a misplaced vector is caught.
Vec3 tag(int old_i, int old_j) { return Vec3(old_i + 1, 1000.0 * (old_j + 1), 0.5); }

TEST(NeighborList, HistoryFollowsPairsThroughASpatialResort) {
  Particles p = random_particles(1500, 0.25, {0.01, 0.02, 0.05}, 9);
  const double skin = 0.003;
  NeighborList old_list = build(p, skin, /*keep_roll=*/true);
  ASSERT_EQ(old_list.roll.size(), old_list.pair_count());
  for (int i = 0; i + 1 < static_cast<int>(old_list.row_start.size()); ++i)
    for (int k = old_list.row_start[i]; k < old_list.row_start[i + 1]; ++k) {
      old_list.shear[k] = tag(i, old_list.partner[k]);
      old_list.roll[k] = -2.0 * tag(i, old_list.partner[k]);
    }

  const std::vector<int> new_to_old = spatial_order(p, 0.05);
  ASSERT_TRUE(is_permutation_of_indices(new_to_old, 1500));
  p.permute(new_to_old);
  NeighborList new_list;
  build_neighbor_list(p, {skin, true}, old_list, new_to_old, new_list);

  // Same positions, so the same pairs: every new pair had a vector, and it must be that pair's.
  ASSERT_EQ(new_list.pair_count(), old_list.pair_count());
  int kept = 0, swapped = 0;
  for (int a = 0; a + 1 < static_cast<int>(new_list.row_start.size()); ++a)
    for (int k = new_list.row_start[a]; k < new_list.row_start[a + 1]; ++k) {
      const int oi = new_to_old[a], oj = new_to_old[new_list.partner[k]];
      // The stored vector belongs to the pair seen from the lower old index; seen from the other
      // particle (roles swapped) it is the opposite vector.
      const bool roles_swapped = oi > oj;
      const Vec3 stored = roles_swapped ? tag(oj, oi) : tag(oi, oj);
      const double sign = roles_swapped ? -1.0 : 1.0;
      ASSERT_EQ(new_list.shear[k], sign * stored) << "new pair (" << a << ", " << new_list.partner[k] << ")";
      ASSERT_EQ(new_list.roll[k], -2.0 * sign * stored) << "new pair (" << a << ", " << new_list.partner[k] << ")";
      (roles_swapped ? swapped : kept) += 1;
    }
  // Both branches exercised.
  EXPECT_GT(kept, 100);
  EXPECT_GT(swapped, 100);
}

TEST(NeighborList, NewPairsStartWithZeroHistoryAndRollIsDroppedWhenNotKept) {
  Particles p = random_particles(800, 0.2, {0.01}, 10);
  NeighborList old_list = build(p, 0.0, true);
  std::set<Pair> old_pairs = listed_pairs(old_list);
  for (std::size_t k = 0; k < old_list.pair_count(); ++k) {
    old_list.shear[k] = Vec3(1, 2, 3);
    old_list.roll[k] = Vec3(4, 5, 6);
  }
  // A larger skin lists more pairs; without re-sorting (empty map) indices are unchanged.
  NeighborList new_list;
  build_neighbor_list(p, {0.01, false}, old_list, {}, new_list);
  EXPECT_TRUE(new_list.roll.empty());
  int fresh = 0;
  for (int i = 0; i + 1 < static_cast<int>(new_list.row_start.size()); ++i)
    for (int k = new_list.row_start[i]; k < new_list.row_start[i + 1]; ++k) {
      const bool was_listed = old_pairs.count({i, new_list.partner[k]}) > 0;
      EXPECT_EQ(new_list.shear[k], was_listed ? Vec3(1, 2, 3) : Vec3::Zero());
      fresh += was_listed ? 0 : 1;
    }
  EXPECT_GT(fresh, 0);
}

}  // namespace
}  // namespace dem
