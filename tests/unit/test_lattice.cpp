// Tests of the lattice generator (spec/lattice.hpp): site counts worked out by hand, every sphere
// inside the box, and the nearest-neighbour geometry of each lattice by brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <vector>

#include "spec/lattice.hpp"

namespace dem::spec {
namespace {

const double kSqrt2 = std::sqrt(2.0);
const double kSqrt3 = std::sqrt(3.0);

// A box at `lo` whose sides hold exactly the given centre-to-centre extents plus one diameter:
// the outermost spheres touch its faces.
std::pair<Vec3, Vec3> tight_box(const Vec3& lo, const Vec3& centre_extent, double radius) {
  return {lo, lo + centre_extent + Vec3::Constant(2 * radius)};
}

void expect_all_inside(const std::vector<Vec3>& sites, const Vec3& lo, const Vec3& hi, double radius) {
  const double tol = 1e-12 * (hi - lo).norm();
  for (const Vec3& c : sites)
    for (int d = 0; d < 3; ++d) {
      ASSERT_GE(c[d] - radius, lo[d] - tol) << "site " << c.transpose();
      ASSERT_LE(c[d] + radius, hi[d] + tol) << "site " << c.transpose();
    }
}

struct NeighbourStats {
  double nearest = 1e300;  // smallest centre distance
  int max_at_nearest = 0;  // most neighbours of one site at that distance (its coordination)
};

NeighbourStats brute_force_neighbours(const std::vector<Vec3>& sites, double expected_spacing) {
  NeighbourStats s;
  for (std::size_t i = 0; i < sites.size(); ++i) {
    int at_spacing = 0;
    for (std::size_t j = 0; j < sites.size(); ++j) {
      if (i == j) continue;
      const double d = (sites[i] - sites[j]).norm();
      s.nearest = std::min(s.nearest, d);
      if (std::abs(d - expected_spacing) < 1e-9 * expected_spacing) ++at_spacing;
    }
    s.max_at_nearest = std::max(s.max_at_nearest, at_spacing);
  }
  return s;
}

// ---------------------------------------------------------------------------------------------
// Counts

TEST(Lattice, CubicCountInATightBox) {
  // 3 x 4 x 5 sites at spacing s = 2 r: centre extents 2s, 3s, 4s.
  const double r = 0.01, s = 2 * r;
  const auto [lo, hi] = tight_box(Vec3(0, 0, 0), Vec3(2 * s, 3 * s, 4 * s), r);
  const auto sites = lattice_sites(LatticeKind::Cubic, lo, hi, r, 1.0);
  EXPECT_EQ(sites.size(), 60u);
  expect_all_inside(sites, lo, hi, r);
}

TEST(Lattice, CubicSpacingSlightlyAboveTheBoxLosesOneLayerPerAxis) {
  // Same box, spacing 1.001: the last layer in each direction no longer fits: 2 x 3 x 4.
  const double r = 0.01, s = 2 * r;
  const auto [lo, hi] = tight_box(Vec3(0, 0, 0), Vec3(2 * s, 3 * s, 4 * s), r);
  EXPECT_EQ(lattice_sites(LatticeKind::Cubic, lo, hi, r, 1.001).size(), 24u);
}

TEST(Lattice, FccTwoByTwoByTwoCellsHold32Sites) {
  // A cubic fcc cell of side a = sqrt(2) s holds 4 sites; 2 x 2 x 2 cells are 4 half-cell layers
  // (h = a / 2) per axis, the even points of a 4 x 4 x 4 grid: 32 sites. The tight box has centre
  // extent 3 h per axis.
  const double r = 0.005, s = 2 * r, h = s / kSqrt2;
  const auto [lo, hi] = tight_box(Vec3(-1, -1, -1), Vec3::Constant(3 * h), r);
  const auto sites = lattice_sites(LatticeKind::Fcc, lo, hi, r, 1.0);
  EXPECT_EQ(sites.size(), 32u);
  expect_all_inside(sites, lo, hi, r);
}

TEST(Lattice, FccTwentyCellsPerSideWithSpacing0999Holds32000Sites) {
  // 20 cells per side = 40 half-cell layers, sized at spacing 1; a spacing of 0.999 leaves the
  // layer count at 40 (39 / 0.999 < 40) and no longer depends on rounding at the faces.
  const double r = 0.001, h = 2 * r / kSqrt2;
  const auto [lo, hi] = tight_box(Vec3(0, 0, 0), Vec3::Constant(39 * h), r);
  const auto sites = lattice_sites(LatticeKind::Fcc, lo, hi, r, 0.999);
  EXPECT_EQ(sites.size(), 32000u);
  expect_all_inside(sites, lo, hi, r);
}

TEST(Lattice, FccSpacingSlightlyTooLargeDropsALayerPerAxis) {
  // 39 half-cell layers per axis, an odd count: (39^3 + 1) / 2 even points of the grid.
  const double r = 0.001, h = 2 * r / kSqrt2;
  const auto [lo, hi] = tight_box(Vec3(0, 0, 0), Vec3::Constant(39 * h), r);
  EXPECT_EQ(lattice_sites(LatticeKind::Fcc, lo, hi, r, 1.001).size(), (39u * 39u * 39u + 1) / 2);
}

// Hand count of the hexagonal close packing generated in a box chosen so that:
//  x: 2r + (nx - 1) s + 0.75 s: rows offset by 0 or s/2 hold nx sites, rows offset by s hold nx - 1;
//  y: 2r + (ny - 1) row + 0.5 s: ny rows in every layer (the odd layers' y shift s / (2 sqrt 3) fits);
//  z: 2r + (nz - 1) layer + 0.1 s: nz layers.
// Even layers: rows offset 0 (even rows) and s/2 (odd rows): nx sites each. Odd layers are shifted by
// s/2 in x: even rows offset s/2 (nx sites), odd rows offset s (nx - 1 sites).
std::size_t hex_count(int nx, int ny, int nz) {
  const int even_layers = (nz + 1) / 2, odd_layers = nz / 2;
  return static_cast<std::size_t>(even_layers * nx * ny + odd_layers * (nx * ny - ny / 2));
}

std::pair<Vec3, Vec3> hex_box(int nx, int ny, int nz, double r, double s) {
  const double row = s * kSqrt3 / 2, layer = s * std::sqrt(2.0 / 3.0);
  return tight_box(Vec3(0, 0, 0), Vec3((nx - 1) * s + 0.75 * s, (ny - 1) * row + 0.5 * s, (nz - 1) * layer + 0.1 * s),
                   r);
}

TEST(Lattice, HexCountMatchesTheHandCount) {
  const double r = 0.02, s = 2 * r;
  for (const auto& [nx, ny, nz] : {std::array<int, 3>{4, 4, 3}, {5, 3, 4}, {1, 1, 1}, {6, 5, 2}}) {
    const auto [lo, hi] = hex_box(nx, ny, nz, r, s);
    const auto sites = lattice_sites(LatticeKind::Hex, lo, hi, r, 1.0);
    EXPECT_EQ(sites.size(), hex_count(nx, ny, nz)) << nx << " x " << ny << " x " << nz;
    expect_all_inside(sites, lo, hi, r);
  }
  EXPECT_EQ(hex_count(4, 4, 3), 46u);  // the formula itself, for the first case: 16 + 14 + 16
}

TEST(Lattice, BoxSmallerThanOneSphereIsEmpty) {
  for (LatticeKind kind : {LatticeKind::Cubic, LatticeKind::Fcc, LatticeKind::Hex})
    EXPECT_TRUE(lattice_sites(kind, Vec3(0, 0, 0), Vec3(1, 1, 0.19), 0.1, 1.0).empty());
}

TEST(Lattice, EverySphereInsideAnArbitraryBox) {
  // A box sized for no lattice in particular, with spacings around the allowed range.
  const Vec3 lo(-0.37, 0.11, -2.0), hi(0.41, 0.93, -1.13);
  for (LatticeKind kind : {LatticeKind::Cubic, LatticeKind::Fcc, LatticeKind::Hex})
    for (double spacing : {0.51, 1.0, 1.3, 2.7}) {
      const auto sites = lattice_sites(kind, lo, hi, 0.03, spacing);
      EXPECT_FALSE(sites.empty());
      expect_all_inside(sites, lo, hi, 0.03);
    }
}

TEST(Lattice, MovingTheBoxMovesTheSites) {
  const Vec3 shift(-1.5, 2.25, 3.0);
  for (LatticeKind kind : {LatticeKind::Cubic, LatticeKind::Fcc, LatticeKind::Hex}) {
    const auto a = lattice_sites(kind, Vec3(0, 0, 0), Vec3(0.3, 0.2, 0.25), 0.02, 1.1);
    const auto b = lattice_sites(kind, shift, shift + Vec3(0.3, 0.2, 0.25), 0.02, 1.1);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) EXPECT_NEAR((b[k] - a[k] - shift).norm(), 0.0, 1e-12);
  }
}

TEST(Lattice, SitesComeInZThenYThenXOrder) {
  for (LatticeKind kind : {LatticeKind::Cubic, LatticeKind::Fcc, LatticeKind::Hex}) {
    const auto sites = lattice_sites(kind, Vec3(0, 0, 0), Vec3(0.3, 0.3, 0.3), 0.02, 1.0);
    const auto zyx = [](const Vec3& a, const Vec3& b) {
      return std::make_tuple(a.z(), a.y(), a.x()) < std::make_tuple(b.z(), b.y(), b.x());
    };
    EXPECT_TRUE(std::is_sorted(sites.begin(), sites.end(), zyx));
  }
}

// ---------------------------------------------------------------------------------------------
// Geometry: nearest-neighbour distance spacing * diameter, and each lattice's coordination

TEST(Lattice, CubicNearestNeighboursAtSpacingTimesDiameterSixOfThem) {
  const double r = 0.01;
  for (double spacing : {1.0, 1.3}) {
    const double s = spacing * 2 * r;
    const auto [lo, hi] = tight_box(Vec3(0, 0, 0), Vec3::Constant(3 * s), r);
    const NeighbourStats n = brute_force_neighbours(lattice_sites(LatticeKind::Cubic, lo, hi, r, spacing), s);
    EXPECT_NEAR(n.nearest, s, 1e-12);
    EXPECT_EQ(n.max_at_nearest, 6);
  }
}

TEST(Lattice, FccNearestNeighboursAtSpacingTimesDiameterTwelveOfThem) {
  const double r = 0.01;
  for (double spacing : {1.0, 1.3}) {
    const double s = spacing * 2 * r, h = s / kSqrt2;
    const auto [lo, hi] = tight_box(Vec3(0, 0, 0), Vec3::Constant(4 * h), r);
    const NeighbourStats n = brute_force_neighbours(lattice_sites(LatticeKind::Fcc, lo, hi, r, spacing), s);
    EXPECT_NEAR(n.nearest, s, 1e-12);
    EXPECT_EQ(n.max_at_nearest, 12);
  }
}

TEST(Lattice, HexNearestNeighboursAtSpacingTimesDiameterTwelveOfThem) {
  const double r = 0.01;
  for (double spacing : {1.0, 1.3}) {
    const double s = spacing * 2 * r;
    const auto [lo, hi] = hex_box(5, 5, 4, r, s);
    const auto sites = lattice_sites(LatticeKind::Hex, lo, hi, r, spacing);
    const NeighbourStats n = brute_force_neighbours(sites, s);
    EXPECT_NEAR(n.nearest, s, 1e-12);
    EXPECT_EQ(n.max_at_nearest, 12);
    // Hexagonal (ABAB), not fcc (ABC): layer 2 lies straight above layer 0, two layer gaps up.
    const Vec3 above = sites[0] + Vec3(0, 0, 2 * s * std::sqrt(2.0 / 3.0));
    const bool found =
        std::any_of(sites.begin(), sites.end(), [&](const Vec3& c) { return (c - above).norm() < 1e-12; });
    EXPECT_TRUE(found);
  }
}

// The count a spec's particle limit is checked with, before any site is made: the exact count for
// a cubic lattice, an upper bound for the others, and no overflow for a box of 1e300 m.
TEST(Lattice, SiteBoundIsTheCountOrAboveIt) {
  const double r = 0.01;
  for (const Vec3& hi : {Vec3(0.1, 0.13, 0.171), Vec3(0.2, 0.05, 0.3), Vec3(0.021, 0.3, 0.11), Vec3(0.019, 1, 1)})
    for (double spacing : {1.0, 1.05, 1.7}) {
      const Vec3 lo(-0.01, 0.003, 0);
      const double cubic = lattice_site_bound(LatticeKind::Cubic, lo, lo + hi, r, spacing);
      EXPECT_EQ(cubic, static_cast<double>(lattice_sites(LatticeKind::Cubic, lo, lo + hi, r, spacing).size()))
          << hi.transpose() << " spacing " << spacing;
      for (LatticeKind kind : {LatticeKind::Fcc, LatticeKind::Hex}) {
        const double bound = lattice_site_bound(kind, lo, lo + hi, r, spacing);
        const double made = static_cast<double>(lattice_sites(kind, lo, lo + hi, r, spacing).size());
        EXPECT_GE(bound, made) << hi.transpose() << " spacing " << spacing;
        // and not far above it where the box holds several spheres across (a box one sphere thick
        // loses the shifted rows of a hexagonal lattice)
        if (hi.minCoeff() > 4 * r) {
          EXPECT_LE(bound, 1.5 * made + 8) << hi.transpose() << " spacing " << spacing;
        }
      }
    }
  const double huge = lattice_site_bound(LatticeKind::Fcc, Vec3::Zero(), Vec3::Constant(1e300), r, 1);
  EXPECT_TRUE(std::isfinite(huge) || huge == INFINITY);
  EXPECT_GT(huge, 1e100);
}

// ---------------------------------------------------------------------------------------------
// Counted lattices (the PDEM-EGD manual's NICEX, NICEY, NICEZ)

TEST(Lattice, ACountedLatticeHoldsTheProductOfItsCountsAtItsSpacing) {
  const std::array<int, 3> counts{11, 13, 42};  // the manual's sample
  for (LatticeKind kind : {LatticeKind::Cubic, LatticeKind::Fcc, LatticeKind::Hex}) {
    const std::vector<Vec3> sites = lattice_sites_counted(kind, Vec3(1, 2, 3), 0.0075, 1.02, counts);
    ASSERT_EQ(sites.size(), 11u * 13u * 42u) << static_cast<int>(kind);
    const Vec3 lo = Vec3(1, 2, 3);
    for (const Vec3& c : sites) ASSERT_TRUE((c.array() >= (lo.array() + 0.0075 - 1e-12)).all());
  }
  // the nearest neighbours at spacing x diameter, twelve of them in the close packings
  for (LatticeKind kind : {LatticeKind::Fcc, LatticeKind::Hex}) {
    const std::vector<Vec3> sites = lattice_sites_counted(kind, Vec3::Zero(), 0.5, 1.0, {4, 4, 4});
    const NeighbourStats n = brute_force_neighbours(sites, 1.0);
    EXPECT_NEAR(n.nearest, 1.0, 1e-12);
    EXPECT_EQ(n.max_at_nearest, 12);
  }
}

TEST(Lattice, ACountedLatticeIsTheFilledBoxOfItsSize) {
  // counted from lo, the same sites as the box that holds exactly that many
  const double r = 0.5, s = 1.0;
  const std::vector<Vec3> counted = lattice_sites_counted(LatticeKind::Cubic, Vec3::Zero(), r, s, {3, 4, 5});
  const auto [lo, hi] = tight_box(Vec3::Zero(), Vec3(2, 3, 4), r);
  EXPECT_EQ(counted, lattice_sites(LatticeKind::Cubic, lo, hi, r, s));
}

}  // namespace
}  // namespace dem::spec
