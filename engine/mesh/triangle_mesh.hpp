// A triangle-mesh boundary (terrain, box, sleeper) with the connectivity the contact test needs:
// which triangles share an edge, which vertices neighbour a vertex.
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/vec.hpp"

namespace dem {

struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;  // 0-based vertex indices

  // Moves every vertex: x -> R (scale x) + translation.
  void transform(double scale, const Eigen::Matrix3d& rotation, const Vec3& translation);
};

// A mesh that cannot be used: the message says which triangle and why.
class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Checks every index and every triangle's area; throws MeshError naming the first bad triangle
// (`where(t)` says where triangle t came from, e.g. "line 12").
template <class Where>
void check_mesh(const TriangleMesh& mesh, Where&& where);

// Connectivity of a mesh, built once.
struct MeshTopology {
  std::vector<std::array<int, 2>> edges;           // vertex pairs, lower index first
  std::vector<std::array<int, 3>> triangle_edges;  // edge ids of (v0 v1), (v1 v2), (v2 v0)
  std::vector<int> edge_triangle_start;            // triangles of edge e: edge_triangles[start[e] .. start[e+1])
  std::vector<int> edge_triangles;
  std::vector<int> vertex_neighbor_start;  // vertices joined to v by an edge, the same layout
  std::vector<int> vertex_neighbors;

  explicit MeshTopology(const TriangleMesh& mesh);
  MeshTopology() = default;
};

// Where on a triangle the closest point to a query point lies.
enum class Feature { Face, Edge, Vertex };

struct ClosestPoint {
  Vec3 point;
  Feature feature;
  int index;  // edge 0..2 ((v0 v1), (v1 v2), (v2 v0)) or vertex 0..2 of the triangle; unused for Face
};

// Closest point on triangle (a, b, c) to p, with its feature (Ericson, Real-Time Collision
// Detection, 2005, section 5.1.5: Voronoi regions of the vertices, then edges, then the face).
ClosestPoint closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

template <class Where>
void check_mesh(const TriangleMesh& mesh, Where&& where) {
  const int nv = static_cast<int>(mesh.vertices.size());
  if (mesh.triangles.empty()) throw MeshError("the mesh has no triangles");
  Vec3 lo = mesh.vertices.empty() ? Vec3::Zero() : mesh.vertices[0], hi = lo;
  for (const Vec3& v : mesh.vertices) {
    if (!v.allFinite()) throw MeshError("a vertex coordinate is not a finite number");
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const double size2 = (hi - lo).squaredNorm();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    for (int k = 0; k < 3; ++k)
      if (tri[k] < 0 || tri[k] >= nv)
        throw MeshError(where(t) + ": triangle " + std::to_string(t + 1) + " refers to vertex " +
                        std::to_string(tri[k] + 1) + ", but the vertices are numbered 1 to " + std::to_string(nv));
    const Vec3 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]], &c = mesh.vertices[tri[2]];
    // twice the area, against the mesh's size: 1e-12 relative catches collinear and repeated corners
    if ((b - a).cross(c - a).squaredNorm() <= 1e-24 * size2 * size2)
      throw MeshError(where(t) + ": triangle " + std::to_string(t + 1) +
                      " is degenerate (its corners are repeated or on one line)");
  }
}

}  // namespace dem
