#include "mesh/mesh_wall.hpp"

#include <algorithm>
#include <cmath>

namespace dem {

void TriangleGrid::build(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles,
                         double min_cell) {
  Vec3 lo = vertices[0], hi = vertices[0];
  for (const Vec3& v : vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  // the typical (median) triangle extent: each triangle then spans about one to eight cells
  std::vector<double> extent(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    const Vec3 a = vertices[tri[0]], b = vertices[tri[1]], c = vertices[tri[2]];
    extent[t] = (a.cwiseMax(b).cwiseMax(c) - a.cwiseMin(b).cwiseMin(c)).maxCoeff();
  }
  std::nth_element(extent.begin(), extent.begin() + extent.size() / 2, extent.end());
  cell_ = std::max({min_cell, extent[extent.size() / 2], 1e-12});
  const Vec3 size = hi - lo;
  constexpr double kMaxCells = 4e6;
  auto cells_for = [&](double cell) {
    double total = 1;
    for (int d = 0; d < 3; ++d) total *= std::floor(size[d] / cell) + 1;
    return total;
  };
  while (cells_for(cell_) > kMaxCells) cell_ *= 1.25;
  origin_ = lo;
  for (int d = 0; d < 3; ++d) dims_[d] = static_cast<int>(std::floor(size[d] / cell_)) + 1;
  const std::size_t cells = static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2];

  auto cell_range = [&](int t, std::array<int, 3>& a, std::array<int, 3>& b) {
    const auto& tri = triangles[t];
    const Vec3 p = vertices[tri[0]], q = vertices[tri[1]], r = vertices[tri[2]];
    const Vec3 tlo = p.cwiseMin(q).cwiseMin(r), thi = p.cwiseMax(q).cwiseMax(r);
    for (int d = 0; d < 3; ++d) {
      a[d] = std::clamp(static_cast<int>(std::floor((tlo[d] - origin_[d]) / cell_)), 0, dims_[d] - 1);
      b[d] = std::clamp(static_cast<int>(std::floor((thi[d] - origin_[d]) / cell_)), 0, dims_[d] - 1);
    }
  };
  auto for_cells = [&](int t, auto&& use) {
    std::array<int, 3> a, b;
    cell_range(t, a, b);
    for (int iz = a[2]; iz <= b[2]; ++iz)
      for (int iy = a[1]; iy <= b[1]; ++iy)
        for (int ix = a[0]; ix <= b[0]; ++ix)
          use(ix + static_cast<std::size_t>(dims_[0]) * (iy + static_cast<std::size_t>(dims_[1]) * iz));
  };
  start_.assign(cells + 1, 0);
  const int nt = static_cast<int>(triangles.size());
  for (int t = 0; t < nt; ++t) for_cells(t, [&](std::size_t c) { ++start_[c + 1]; });
  for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  items_.resize(start_[cells]);
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (int t = 0; t < nt; ++t) for_cells(t, [&](std::size_t c) { items_[fill[c]++] = t; });
}

MeshWall MeshWall::from(const WallInit& init, int boundary) {
  const MeshShape& shape = std::get<MeshShape>(init.shape);
  MeshWall m;
  m.material = init.material;
  m.boundary = boundary;
  m.vertices0 = shape.vertices;
  m.triangles = shape.triangles;
  m.topology = MeshTopology(TriangleMesh{shape.vertices, shape.triangles});
  m.vertices = shape.vertices;
  m.update_planes();
  return m;
}

void MeshWall::update_planes() {
  normals.resize(triangles.size());
  offsets.resize(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    normals[t] = (vertices[tri[1]] - vertices[tri[0]]).cross(vertices[tri[2]] - vertices[tri[0]]).normalized();
    offsets[t] = normals[t].dot(vertices[tri[0]]);
  }
}

Vec3 MeshWall::centroid() const {
  Vec3 sum = Vec3::Zero();
  for (const Vec3& v : vertices) sum += v;
  return sum / static_cast<double>(vertices.size());
}

void MeshWall::move_to(const WallPose& next) {
  pose = next;
  grid_stale = true;
  for (std::size_t v = 0; v < vertices.size(); ++v) vertices[v] = next.place(vertices0[v]);
  update_planes();
}

namespace {

// Relative slack of the Voronoi tests: a centre exactly above a shared edge or vertex must pass
// them despite rounding (the duplicate is then removed by the feature and point tests).
constexpr double kSlack = 1e-9;

// The centre lies in the region of the surface closest to edge e: outside every triangle on e,
// across e (d . m >= 0 with m the in-plane normal of e pointing away from the triangle).
bool in_edge_region(const MeshWall& mesh, int e, const Vec3& d) {
  const auto& edge = mesh.topology.edges[e];
  const Vec3 p0 = mesh.vertices[edge[0]], p1 = mesh.vertices[edge[1]];
  const Vec3 u = (p1 - p0).normalized();
  const double d_len = d.norm();
  for (int k = mesh.topology.edge_triangle_start[e]; k < mesh.topology.edge_triangle_start[e + 1]; ++k) {
    const auto& tri = mesh.triangles[mesh.topology.edge_triangles[k]];
    int opposite = tri[0];
    for (int v : tri)
      if (v != edge[0] && v != edge[1]) opposite = v;
    Vec3 m = p0 - mesh.vertices[opposite];
    m -= m.dot(u) * u;
    if (d.dot(m) < -kSlack * d_len * m.norm()) return false;
  }
  return true;
}

// The centre lies in the region closest to vertex v: no edge from v leads towards it.
bool in_vertex_region(const MeshWall& mesh, int v, const Vec3& d) {
  const double d_len = d.norm();
  const Vec3 pv = mesh.vertices[v];
  for (int k = mesh.topology.vertex_neighbor_start[v]; k < mesh.topology.vertex_neighbor_start[v + 1]; ++k) {
    const Vec3 along = mesh.vertices[mesh.topology.vertex_neighbors[k]] - pv;
    if (d.dot(along) > kSlack * d_len * along.norm()) return false;
  }
  return true;
}

bool triangle_has_edge(const MeshWall& mesh, int t, int e) {
  const auto& edges = mesh.topology.triangle_edges[t];
  return edges[0] == e || edges[1] == e || edges[2] == e;
}

bool triangle_has_vertex(const MeshWall& mesh, int t, int v) {
  const auto& tri = mesh.triangles[t];
  return tri[0] == v || tri[1] == v || tri[2] == v;
}

}  // namespace

int mesh_touches(const MeshWall& mesh, const int* candidates, int candidate_count, const Vec3& x, double r,
                 MeshTouch* out, int out_capacity) {
  // The triangles within r, then their contacts by feature: faces first, so that an edge or vertex
  // of a touched face (the common case on a flat patch) is dismissed before its Voronoi test.
  constexpr int kNear = 32;
  struct Near {
    int triangle;
    ClosestPoint cp;
    double d2;
  } near[kNear];
  int near_count = 0;
  // Planes of the touched faces found so far: a triangle in one of them cannot add a contact (an
  // edge or vertex point there is dominated or outside its region), so it is not tested at all.
  // This is what keeps a terrain cheap: most candidates are coplanar neighbours of the face below.
  // Candidates come nearest first (ordered at the list build), so the face is usually found first.
  constexpr int kPlanes = 4;
  int face_tri[kPlanes];
  int planes = 0;
  for (int c = 0; c < candidate_count && near_count < kNear; ++c) {
    const int t = candidates[c];
    bool in_touched_plane = false;
    for (int k = 0; k < planes && !in_touched_plane; ++k) {
      const int f = face_tri[k];
      in_touched_plane = mesh.normals[t].dot(mesh.normals[f]) > 1 - 1e-12 &&
                         std::abs(mesh.offsets[t] - mesh.offsets[f]) <= kSlack * r;
    }
    if (in_touched_plane) continue;
    const auto& tri = mesh.triangles[t];
    const ClosestPoint cp = closest_on_triangle(x, mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]);
    const double d2 = (x - cp.point).squaredNorm();
    if (d2 >= r * r) continue;
    near[near_count++] = {t, cp, d2};
    if (cp.feature == Feature::Face && planes < kPlanes) face_tri[planes++] = t;
  }
  int written = 0;
  auto accept = [&](const Near& n, int key) {
    for (int k = 0; k < written; ++k)  // the same point reached through another triangle
      if ((out[k].point - n.cp.point).squaredNorm() <= kSlack * kSlack * r * r) return;
    if (written == out_capacity) return;
    MeshTouch& touch = out[written++];
    touch.feature = n.cp.feature;
    touch.key = key;
    touch.triangle = n.triangle;
    touch.point = n.cp.point;
    const double dist = std::sqrt(n.d2);
    if (dist > 0) {
      touch.normal = (x - n.cp.point) / dist;
    } else {  // centre on the surface: the face normal, either side will do
      const auto& tri = mesh.triangles[n.triangle];
      touch.normal = (mesh.vertices[tri[1]] - mesh.vertices[tri[0]]).cross(mesh.vertices[tri[2]] - mesh.vertices[tri[0]]).normalized();
    }
    touch.delta = r - dist;
  };
  for (int k = 0; k < near_count; ++k)
    if (near[k].cp.feature == Feature::Face) accept(near[k], near[k].triangle);
  for (int k = 0; k < near_count; ++k) {
    if (near[k].cp.feature != Feature::Edge) continue;
    const int e = mesh.topology.triangle_edges[near[k].triangle][near[k].cp.index];
    bool covered = false;
    for (int o = 0; o < written && !covered; ++o)
      covered = (out[o].feature == Feature::Face && triangle_has_edge(mesh, out[o].key, e)) ||
                (out[o].feature == Feature::Edge && out[o].key == e);
    if (!covered && in_edge_region(mesh, e, x - near[k].cp.point)) accept(near[k], e);
  }
  for (int k = 0; k < near_count; ++k) {
    if (near[k].cp.feature != Feature::Vertex) continue;
    const int v = mesh.triangles[near[k].triangle][near[k].cp.index];
    bool covered = false;
    for (int o = 0; o < written && !covered; ++o) {
      if (out[o].feature == Feature::Face) covered = triangle_has_vertex(mesh, out[o].key, v);
      else if (out[o].feature == Feature::Edge)
        covered = mesh.topology.edges[out[o].key][0] == v || mesh.topology.edges[out[o].key][1] == v;
      else covered = out[o].key == v;
    }
    if (!covered && in_vertex_region(mesh, v, x - near[k].cp.point)) accept(near[k], v);
  }
  return written;
}

}  // namespace dem
