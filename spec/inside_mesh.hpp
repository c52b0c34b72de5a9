// A closed triangle mesh as a region to fill (PDEM-EGD's key block: the sliding mass is a closed
// mesh filled with particles, then bonded): is a sphere wholly inside it?
#pragma once

#include "mesh/mesh_wall.hpp"

namespace dem::spec {

class ClosedMesh {
 public:
  explicit ClosedMesh(const MeshShape& shape);

  // The centre is inside (a ray crosses the surface an odd number of times) and no triangle comes
  // closer than r.
  bool holds(const Vec3& centre, double r) const;

  Vec3 min() const { return lo_; }
  Vec3 max() const { return hi_; }

 private:
  bool contains(const Vec3& x) const;

  MeshWall mesh_;
  Vec3 lo_, hi_;
};

}  // namespace dem::spec
