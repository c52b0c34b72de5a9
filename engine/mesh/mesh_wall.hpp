// A triangle-mesh wall at run time: its triangles where they are now, binned in a cell grid so that
// a sphere finds the few triangles near it whatever the size of the mesh, and the contact test that
// gives a sphere one contact per touching surface patch, not one per triangle.
#pragma once

#include <array>
#include <vector>

#include "core/scene.hpp"
#include "mesh/triangle_mesh.hpp"
#include "walls/wall_motion.hpp"

namespace dem {

// Triangles binned by their bounding boxes in a uniform grid. Cells are at least `min_cell` (the
// particles' reach) and at least the typical triangle's extent, so that a triangle covers a few
// cells and a sphere's query visits a few.
class TriangleGrid {
 public:
  void build(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles, double min_cell);

  // Calls visit(t) for the triangles binned in the cells overlapping [lo, hi]; a triangle in
  // several of those cells is visited once per cell.
  template <class Visit>
  void for_each_in_box(const Vec3& lo, const Vec3& hi, Visit&& visit) const {
    std::array<int, 3> a, b;
    for (int d = 0; d < 3; ++d) {
      const double from = (lo[d] - origin_[d]) / cell_, to = (hi[d] - origin_[d]) / cell_;
      // the box misses the mesh (or is not a box: a NaN coordinate, reached by the saved-state fuzzer)
      if (!(to >= 0 && from < dims_[d])) return;
      a[d] = from < 0 ? 0 : static_cast<int>(from);
      b[d] = to >= dims_[d] ? dims_[d] - 1 : static_cast<int>(to);
    }
    for (int iz = a[2]; iz <= b[2]; ++iz)
      for (int iy = a[1]; iy <= b[1]; ++iy)
        for (int ix = a[0]; ix <= b[0]; ++ix) {
          const std::size_t c =
              ix + static_cast<std::size_t>(dims_[0]) * (iy + static_cast<std::size_t>(dims_[1]) * iz);
          for (int k = start_[c]; k < start_[c + 1]; ++k) visit(items_[k]);
        }
  }

  double cell_size() const { return cell_; }

 private:
  Vec3 origin_ = Vec3::Zero();
  double cell_ = 1;
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<int> start_;
  std::vector<int> items_;
};

struct MeshWall {
  int material = 0;
  int boundary = 0;             // index of the wall in Scene::walls
  std::vector<Vec3> vertices0;  // at the start
  std::vector<std::array<int, 3>> triangles;
  MeshTopology topology;
  std::vector<Vec3> vertices;   // now
  std::vector<Vec3> normals;    // unit normal of each triangle now (v1 - v0) x (v2 - v0)
  std::vector<double> offsets;  // normal . v0
  // Per triangle and edge ((v0 v1), (v1 v2), (v2 v0)): how far the other triangle on that edge
  // rises out of this one's plane along its normal (its far corner's height over the edge's
  // length; a rigid motion keeps it). > 0: a valley seen from the normal's side, < 0: from the
  // other side; 0 for a flat seam, an open edge or one shared by more than two triangles.
  std::vector<std::array<double, 3>> fold;
  std::vector<std::array<int, 3>> across;  // the other triangle on each edge where fold is not 0, else -1
  WallPose pose;
  TriangleGrid grid;       // of `vertices` when it was built
  bool grid_stale = true;  // the mesh moved since (a fixed mesh is binned once)

  static MeshWall from(const WallInit& init, int boundary);
  Vec3 centroid() const;
  void move_to(const WallPose& next);  // rigid motion from vertices0
  void update_planes();
};

// One contact of a sphere with a mesh: a face, edge or vertex that is a local minimum of the
// distance from the sphere's centre to the mesh surface, or a face beside a valley (below).
struct MeshTouch {
  Feature feature;
  int key;                              // triangle (face), edge id (edge) or vertex index (vertex)
  int triangle;                         // a triangle the point lies on
  Vec3 point;                           // closest point on the mesh (a face's: the centre's projection on its plane)
  Vec3 normal;                          // unit, mesh -> sphere
  double delta;                         // overlap
  double weight = 1;                    // the share of the contact's force (below 1 only for faces at a valley)
  Vec3 weight_gradient = Vec3::Zero();  // of the weight in the sphere's centre (1 / m)
};

// The contacts of a sphere (centre x, radius r) with `mesh`, testing the given candidate triangles.
// Sound across edges and vertices (the PDEM-EGD manual's finite-wall method, section 4.1.2, with the mesh's
// connectivity): an edge or vertex point counts only when the centre lies in that feature's own
// Voronoi region of the surface, a feature is counted once however many triangles share it, and an
// edge (vertex) that borders a touched face (edge) is not counted again. A sphere resting across
// two coplanar triangles therefore gets one contact with the plane's normal, not two.
//
// Valleys (concave edges) are shared out instead: a face's contact there is weighted by the share
// of its contact disc (the sphere's section by the face's plane) on the face's own side of the
// valley edge, and a face counts while any of its disc lies on its side, even with the centre's
// projection just beyond the edge. Counted as local minima alone, the contacts of a shallow valley
// went from two to one while the face dropped still overlapped as deeply as the other one: energy
// jumped by a whole contact's worth (a drop beside a fold of 0.5 degrees lost 48% of its energy).
// Shared out, a flat fold weighs one contact, a sharp valley two, and the force changes
// continuously in between and as the sphere moves. The stored energy is the weighted sum of the
// faces' energies; its gradient has, besides the weighted normal forces, the pull of the weights
// changing, -U grad(weight), which the force loop adds through the centre, so that valleys keep
// the elastic energy as a plane does.
// Returns the number written to `out` (at most out_capacity; further contacts are dropped). At most
// 32 triangles within r are considered (a sphere touches far fewer on any sane mesh).
int mesh_touches(const MeshWall& mesh, const int* candidates, int candidate_count, const Vec3& x, double r,
                 MeshTouch* out, int out_capacity);

// The share of the disc of radius a about p (a point of triangle t's plane) that lies on t's inner
// side of each of the edges listed (0..2, as in MeshTopology::triangle_edges), and its derivatives
// in p (within the plane) and in a.
struct DiscShare {
  double share = 1;
  Vec3 d_centre = Vec3::Zero();
  double d_radius = 0;
};
DiscShare disc_share(const MeshWall& mesh, int t, const Vec3& p, double a, const int* edges, int edge_count);

}  // namespace dem
