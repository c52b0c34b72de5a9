// Triangle meshes built in code for the tests: a rectangle cut into a grid, a closed box.
#pragma once

#include <string>

#include "core/scene.hpp"

namespace dem::test {

// The rectangle origin + a u + b v (a, b in [0, 1]) cut into nu x nv cells, two triangles each
// (split along alternating diagonals, so that vertices join 4 or 8 triangles).
inline MeshShape grid_rectangle(const Vec3& origin, const Vec3& u, const Vec3& v, int nu, int nv) {
  MeshShape m;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) m.vertices.push_back(origin + (double(i) / nu) * u + (double(j) / nv) * v);
  auto at = [&](int i, int j) { return j * (nu + 1) + i; };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      if ((i + j) % 2 == 0) {
        m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      } else {
        m.triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        m.triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    }
  m.source = "grid";
  return m;
}

// Appends mesh b to a (vertices are not merged: faces of a box keep their own edges).
inline void append(MeshShape& a, const MeshShape& b) {
  const int base = static_cast<int>(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (auto t : b.triangles) a.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
}

// The six faces of the box [lo, hi], each an n x n grid.
inline MeshShape box_mesh(const Vec3& lo, const Vec3& hi, int n) {
  const Vec3 d = hi - lo;
  const Vec3 ex(d.x(), 0, 0), ey(0, d.y(), 0), ez(0, 0, d.z());
  MeshShape m;
  append(m, grid_rectangle(lo, ex, ey, n, n));
  append(m, grid_rectangle(lo + ez, ex, ey, n, n));
  append(m, grid_rectangle(lo, ex, ez, n, n));
  append(m, grid_rectangle(lo + ey, ex, ez, n, n));
  append(m, grid_rectangle(lo, ey, ez, n, n));
  append(m, grid_rectangle(lo + ex, ey, ez, n, n));
  m.source = "box";
  return m;
}

inline WallInit mesh_wall(const MeshShape& shape, const std::string& name = "mesh", int material = 1) {
  WallInit w;
  w.name = name;
  w.material = material;
  w.shape = shape;
  return w;
}

}  // namespace dem::test
