#include "mesh/triangle_mesh.hpp"

#include <algorithm>
#include <map>

namespace dem {

void TriangleMesh::transform(double scale, const Eigen::Matrix3d& rotation, const Vec3& translation) {
  for (Vec3& v : vertices) v = rotation * (scale * v) + translation;
}

namespace {

// Compressed rows from (key, value) pairs: start has keys + 1 entries.
void to_rows(int keys, std::vector<std::pair<int, int>> pairs, std::vector<int>& start, std::vector<int>& values) {
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  start.assign(keys + 1, 0);
  for (const auto& [k, v] : pairs) ++start[k + 1];
  for (int k = 0; k < keys; ++k) start[k + 1] += start[k];
  values.resize(pairs.size());
  for (std::size_t a = 0; a < pairs.size(); ++a) values[a] = pairs[a].second;
}

}  // namespace

MeshTopology::MeshTopology(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> edge_id;
  std::vector<std::pair<int, int>> edge_tri, vertex_pairs;
  triangle_edges.resize(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const int a = std::min(tri[k], tri[(k + 1) % 3]), b = std::max(tri[k], tri[(k + 1) % 3]);
      auto [it, added] = edge_id.try_emplace({a, b}, static_cast<int>(edges.size()));
      if (added) edges.push_back({a, b});
      triangle_edges[t][k] = it->second;
      edge_tri.emplace_back(it->second, static_cast<int>(t));
      vertex_pairs.emplace_back(a, b);
      vertex_pairs.emplace_back(b, a);
    }
  }
  to_rows(static_cast<int>(edges.size()), std::move(edge_tri), edge_triangle_start, edge_triangles);
  to_rows(static_cast<int>(mesh.vertices.size()), std::move(vertex_pairs), vertex_neighbor_start, vertex_neighbors);
}

ClosestPoint closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {a, Feature::Vertex, 0};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {b, Feature::Vertex, 1};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return {a + (d1 / (d1 - d3)) * ab, Feature::Edge, 0};
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {c, Feature::Vertex, 2};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return {a + (d2 / (d2 - d6)) * ac, Feature::Edge, 2};
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return {b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b), Feature::Edge, 1};
  const double denom = 1 / (va + vb + vc);
  return {a + (vb * denom) * ab + (vc * denom) * ac, Feature::Face, 0};
}

}  // namespace dem
