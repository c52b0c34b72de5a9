#include "spec/inside_mesh.hpp"

#include <algorithm>
#include <vector>

namespace dem::spec {

ClosedMesh::ClosedMesh(const MeshShape& shape) {
  WallInit init;
  init.shape = shape;
  mesh_ = MeshWall::from(init, 0);
  lo_ = hi_ = shape.vertices[0];
  for (const Vec3& v : shape.vertices) {
    lo_ = lo_.cwiseMin(v);
    hi_ = hi_.cwiseMax(v);
  }
  mesh_.grid.build(mesh_.vertices, mesh_.triangles, 1e-9 * (hi_ - lo_).norm());
}

bool ClosedMesh::contains(const Vec3& x) const {
  // A ray along +x, nudged off the axis by irrational fractions of the size so that it does not
  // run exactly through an edge or a vertex (Moller & Trumbore 1997 for the crossing test).
  const double size = (hi_ - lo_).norm();
  const Vec3 o = x + size * Vec3(0, 1.4142135623e-9, 1.7320508075e-9);
  std::vector<int> near;
  mesh_.grid.for_each_in_box(o, Vec3(hi_.x() + 1, o.y(), o.z()), [&](int t) { near.push_back(t); });
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  int crossings = 0;
  for (int t : near) {
    const auto& tri = mesh_.triangles[t];
    const Vec3 a = mesh_.vertices[tri[0]], e1 = mesh_.vertices[tri[1]] - a, e2 = mesh_.vertices[tri[2]] - a;
    const Vec3 d = Vec3::UnitX();
    const Vec3 p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-300) continue;  // the ray runs along the triangle's plane
    const Vec3 s = o - a;
    const double u = s.dot(p) / det;
    if (u < 0 || u > 1) continue;
    const Vec3 q = s.cross(e1);
    const double v = d.dot(q) / det;
    if (v < 0 || u + v > 1) continue;
    if (e2.dot(q) / det > 0) ++crossings;
  }
  return crossings % 2 == 1;
}

bool ClosedMesh::holds(const Vec3& centre, double r) const {
  if (!contains(centre)) return false;
  bool clear = true;
  mesh_.grid.for_each_in_box(centre - Vec3::Constant(r), centre + Vec3::Constant(r), [&](int t) {
    if (!clear) return;
    const auto& tri = mesh_.triangles[t];
    const Vec3 q =
        closest_on_triangle(centre, mesh_.vertices[tri[0]], mesh_.vertices[tri[1]], mesh_.vertices[tri[2]]).point;
    clear = (centre - q).squaredNorm() >= r * r;
  });
  return clear;
}

}  // namespace dem::spec
