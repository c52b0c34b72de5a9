// Sphere-mesh contact: one contact per touching surface patch, whatever triangle, edge or vertex the
// closest point falls on; real edges and valleys keep their own contacts.
#include <gtest/gtest.h>

#include <numeric>

#include "mesh/mesh_wall.hpp"
#include "support/meshes.hpp"

namespace dem::test {
namespace {

MeshWall wall_of(const MeshShape& shape) {
  WallInit init = mesh_wall(shape);
  return MeshWall::from(init, 0);
}

std::vector<MeshTouch> touches(const MeshWall& mesh, const Vec3& x, double r) {
  std::vector<int> all(mesh.triangles.size());
  std::iota(all.begin(), all.end(), 0);
  MeshTouch out[8];
  const int n = mesh_touches(mesh, all.data(), static_cast<int>(all.size()), x, r, out, 8);
  return {out, out + n};
}

TEST(ClosestOnTriangle, NamesTheFeature) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_EQ(closest_on_triangle({0.2, 0.2, 1}, a, b, c).feature, Feature::Face);
  const ClosestPoint edge = closest_on_triangle({0.5, -1, 1}, a, b, c);
  EXPECT_EQ(edge.feature, Feature::Edge);
  EXPECT_EQ(edge.index, 0);
  EXPECT_TRUE(edge.point.isApprox(Vec3(0.5, 0, 0)));
  const ClosestPoint vertex = closest_on_triangle({2, -1, 0}, a, b, c);
  EXPECT_EQ(vertex.feature, Feature::Vertex);
  EXPECT_EQ(vertex.index, 1);
  const ClosestPoint hyp = closest_on_triangle({1, 1, 0}, a, b, c);
  EXPECT_EQ(hyp.feature, Feature::Edge);
  EXPECT_EQ(hyp.index, 1);
  EXPECT_TRUE(hyp.point.isApprox(Vec3(0.5, 0.5, 0)));
}

// A flat plane of 8 x 8 cells: wherever the sphere sits - inside a triangle, on an edge, on the
// diagonal, on a vertex shared by 4 or 8 triangles, or just off them - one contact, normal up.
TEST(MeshTouches, FlatGridGivesOneContactEverywhere) {
  const MeshWall mesh = wall_of(grid_rectangle({0, 0, 0}, {8, 0, 0}, {0, 8, 0}, 8, 8));
  const double r = 0.3, h = 0.25;
  const Vec3 spots[] = {{2.3, 3.6, h}, {2.0, 3.6, h}, {2.5, 3.5, h},
                        {2.0, 3.0, h}, {3.0, 3.0, h}, {2.0 + 1e-12, 3.0 - 1e-12, h},
                        {4.0, 4.5, h}, {4.5, 4.5, h}, {5.0, 5.0, h}};
  for (const Vec3& x : spots) {
    const auto found = touches(mesh, x, r);
    ASSERT_EQ(found.size(), 1u) << "at " << x.transpose();
    EXPECT_NEAR(found[0].normal.z(), 1.0, 1e-12) << "at " << x.transpose();
    EXPECT_NEAR(found[0].delta, r - h, 1e-12) << "at " << x.transpose();
  }
  // from below, the other face
  const auto below = touches(mesh, {3.0, 3.0, -h}, r);
  ASSERT_EQ(below.size(), 1u);
  EXPECT_NEAR(below[0].normal.z(), -1.0, 1e-12);
}

// A roof ridge (convex edge): above the ridge one edge contact; beside it one face contact.
TEST(MeshTouches, ConvexRidgeGivesOneContact) {
  MeshShape roof;
  roof.vertices = {{0, 0, 0}, {0, 4, 0}, {2, 0, 1}, {2, 4, 1}, {4, 0, 0}, {4, 4, 0}};
  roof.triangles = {{0, 2, 1}, {1, 2, 3}, {2, 4, 3}, {3, 4, 5}};
  const MeshWall mesh = wall_of(roof);
  const auto top = touches(mesh, {2, 2, 1.2}, 0.3);
  ASSERT_EQ(top.size(), 1u);
  EXPECT_EQ(top[0].feature, Feature::Edge);
  EXPECT_NEAR(top[0].normal.z(), 1.0, 1e-12);
  const auto side = touches(mesh, Vec3(0.8, 1.0, 0.4) + 0.25 * Vec3(-1, 0, 2).normalized(), 0.3);
  ASSERT_EQ(side.size(), 1u);
  EXPECT_EQ(side[0].feature, Feature::Face);
}

// A V-shaped valley (concave edge): a sphere resting in it touches both faces, not the edge.
TEST(MeshTouches, ConcaveValleyGivesTwoFaceContacts) {
  MeshShape valley;
  valley.vertices = {{-2, 0, 2}, {-2, 4, 2}, {0, 0, 0}, {0, 4, 0}, {2, 0, 2}, {2, 4, 2}};
  valley.triangles = {{0, 2, 1}, {1, 2, 3}, {2, 4, 3}, {3, 4, 5}};
  const MeshWall mesh = wall_of(valley);
  // the centre is 0.28 above the valley's edge (within reach) and 0.198 from each face
  const auto found = touches(mesh, {0, 2, 0.28}, 0.3);
  ASSERT_EQ(found.size(), 2u);
  for (const MeshTouch& t : found) {
    EXPECT_EQ(t.feature, Feature::Face);
    EXPECT_NEAR(t.delta, 0.3 - 0.28 / std::sqrt(2.0), 1e-12);
  }
}

// A box corner seen from inside: three faces, three contacts.
TEST(MeshTouches, InsideCornerOfABoxGivesThreeContacts) {
  const MeshWall mesh = wall_of(box_mesh({0, 0, 0}, {1, 1, 1}, 2));
  const auto found = touches(mesh, {0.08, 0.09, 0.07}, 0.1);
  ASSERT_EQ(found.size(), 3u);
  for (const MeshTouch& t : found) EXPECT_EQ(t.feature, Feature::Face);
}

// A sphere past the end of an open plane touches its rim: one contact pointing from the rim.
TEST(MeshTouches, OpenBoundaryEdgeAndCorner) {
  const MeshWall mesh = wall_of(grid_rectangle({0, 0, 0}, {2, 0, 0}, {0, 2, 0}, 2, 2));
  const auto edge = touches(mesh, {2.1, 0.5, 0.1}, 0.2);
  ASSERT_EQ(edge.size(), 1u);
  EXPECT_EQ(edge[0].feature, Feature::Edge);
  EXPECT_TRUE(edge[0].normal.isApprox(Vec3(1, 0, 1).normalized(), 1e-12));
  const auto corner = touches(mesh, {2.1, 2.1, 0.1}, 0.2);
  ASSERT_EQ(corner.size(), 1u);
  EXPECT_EQ(corner[0].feature, Feature::Vertex);
}

// The share of a contact disc on a triangle's side of its edges, against counting points of a fine
// grid over the disc, and its derivatives against finite differences.
TEST(DiscShare, MatchesAGridCountAndItsDerivatives) {
  MeshShape one;
  one.vertices = {{0, 0, 0}, {1, 0, 0}, {0.3, 0.8, 0}};
  one.triangles = {{0, 1, 2}};
  const MeshWall mesh = wall_of(one);
  auto counted = [&](const Vec3& p, double a, const std::vector<int>& edges) {
    // inward normals and offsets of the listed edges, the same way the share defines them
    const int n = 801;
    int in = 0, all = 0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const Vec3 q = p + Vec3(a * (2.0 * (i + 0.5) / n - 1), a * (2.0 * (j + 0.5) / n - 1), 0);
        if ((q - p).squaredNorm() > a * a) continue;
        ++all;
        bool ok = true;
        for (int e : edges) {
          const Vec3 a0 = mesh.vertices[mesh.triangles[0][e]], a1 = mesh.vertices[mesh.triangles[0][(e + 1) % 3]];
          const Vec3 opposite = mesh.vertices[mesh.triangles[0][(e + 2) % 3]];
          Vec3 m = Vec3::UnitZ().cross(a1 - a0);
          if (m.dot(opposite - a0) < 0) m = -m;
          ok = ok && m.dot(q - a0) >= 0;
        }
        in += ok;
      }
    return static_cast<double>(in) / all;
  };
  const std::vector<std::vector<int>> edge_sets = {{0}, {0, 1}, {0, 1, 2}, {2, 1}};
  const Vec3 spots[] = {{0.4, 0.05, 0}, {0.9, 0.05, 0}, {0.35, 0.3, 0}, {0.4, -0.03, 0}, {0.3, 0.75, 0}};
  for (const auto& edges : edge_sets)
    for (const Vec3& p : spots)
      for (double a : {0.04, 0.2, 0.6}) {
        const DiscShare got = disc_share(mesh, 0, p, a, edges.data(), static_cast<int>(edges.size()));
        EXPECT_NEAR(got.share, counted(p, a, edges), 4e-3) << p.transpose() << " a " << a << " edges " << edges.size();
        const double h = 1e-6;
        for (int d = 0; d < 2; ++d) {
          const Vec3 step = h * Vec3::Unit(d);
          const double plus = disc_share(mesh, 0, p + step, a, edges.data(), static_cast<int>(edges.size())).share;
          const double minus = disc_share(mesh, 0, p - step, a, edges.data(), static_cast<int>(edges.size())).share;
          EXPECT_NEAR(got.d_centre[d], (plus - minus) / (2 * h), 1e-5 / a) << p.transpose() << " a " << a;
        }
        const double grown = disc_share(mesh, 0, p, a + 1e-7, edges.data(), static_cast<int>(edges.size())).share;
        const double shrunk = disc_share(mesh, 0, p, a - 1e-7, edges.data(), static_cast<int>(edges.size())).share;
        EXPECT_NEAR(got.d_radius, (grown - shrunk) / 2e-7, 1e-4 / a) << p.transpose() << " a " << a;
      }
}

// A valley so shallow it is almost flat weighs one contact between its two faces, a sharp one two.
TEST(MeshTouches, AValleysFacesShareOneContactWhenShallowAndCountTwiceWhenSharp) {
  for (double slope : {1e-4, 0.01, 0.05}) {
    MeshShape v;
    const double h = 2 * slope;
    v.vertices = {{-2, 0, h}, {-2, 4, h}, {0, 0, 0}, {0, 4, 0}, {2, 0, h}, {2, 4, h}};
    v.triangles = {{0, 2, 1}, {1, 2, 3}, {2, 4, 3}, {3, 4, 5}};
    const MeshWall mesh = wall_of(v);
    for (double x : {-0.05, -0.01, 0.0, 0.02, 0.07}) {
      const auto found = touches(mesh, {x, 2, 0.28}, 0.3);
      double total = 0;
      for (const MeshTouch& t : found) {
        EXPECT_EQ(t.feature, Feature::Face);
        total += t.weight;
      }
      // the two discs' shares: about half a disc each side of the fold; each face's projection
      // lies d tan(slope) past the fold, which adds about (4 / pi) (d / a) slope in all
      EXPECT_NEAR(total, 1.0, 5 * slope) << "slope " << slope << " at x " << x;
    }
  }
  // 45 degrees, an overlap of 3% of the radius: two contacts at full weight (the disc of radius
  // 0.077 lies 0.29 from the fold)
  MeshShape sharp;
  sharp.vertices = {{-2, 0, 2}, {-2, 4, 2}, {0, 0, 0}, {0, 4, 0}, {2, 0, 2}, {2, 4, 2}};
  sharp.triangles = {{0, 2, 1}, {1, 2, 3}, {2, 4, 3}, {3, 4, 5}};
  const auto both = touches(wall_of(sharp), {0, 2, 0.29 * std::sqrt(2.0)}, 0.3);
  ASSERT_EQ(both.size(), 2u);
  for (const MeshTouch& t : both) EXPECT_DOUBLE_EQ(t.weight, 1.0);
}

TEST(TriangleGrid, FindsTheTrianglesNearAPoint) {
  MeshWall mesh = wall_of(grid_rectangle({0, 0, 0}, {100, 0, 0}, {0, 100, 0}, 100, 100));
  mesh.grid.build(mesh.vertices, mesh.triangles, 0.5);
  std::vector<int> near;
  mesh.grid.for_each_in_box({50.2, 50.2, -0.3}, {50.8, 50.8, 0.3}, [&](int t) { near.push_back(t); });
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  EXPECT_GE(near.size(), 2u);   // the two triangles of the cell, at least
  EXPECT_LE(near.size(), 50u);  // a neighbourhood, not the mesh of 20,000
  bool has_cell = false;
  for (int t : near)
    for (int v : mesh.triangles[t]) has_cell = has_cell || mesh.vertices[v].isApprox(Vec3(50, 50, 0));
  EXPECT_TRUE(has_cell);
  near.clear();
  mesh.grid.for_each_in_box({200, 200, 0}, {201, 201, 1}, [&](int t) { near.push_back(t); });
  EXPECT_TRUE(near.empty());
}

}  // namespace
}  // namespace dem::test
