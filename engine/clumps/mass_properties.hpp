// Mass, centre of mass and inertia of a clump: the union of overlapping spheres (overlaps counted
// once), as BallastDEM finds them by finite subdivision (its section 4.1). The subdivision here is
// adaptive: cells wholly inside a sphere or wholly outside all of them are integrated exactly, and
// only cells the surface cuts are divided further.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/vec.hpp"

namespace dem {

struct MemberSphere {
  Vec3 centre;
  double radius = 0;
};

struct MassProperties {
  double volume = 0;
  Vec3 centroid = Vec3::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();             // about the centroid, for density 1
  Vec3 principal_moments = Vec3::Zero();                         // ascending, for density 1
  Eigen::Matrix3d principal_axes = Eigen::Matrix3d::Identity();  // columns, right-handed
  double relative_accuracy = 0;                                  // the change of the last refinement
};

// Refines until the volume and the principal moments change by less than `relative_accuracy`
// between two levels (at most 2^11 cells a side of a root cell: the root cells are cubes about the
// largest sphere's diameter, so a long or sparse shape is resolved as finely as a compact one).
// A shape asked again (the same spheres, to the bit, and accuracy) gets the first answer, kept.
MassProperties union_mass_properties(const std::vector<MemberSphere>& spheres, double relative_accuracy = 1e-5);

// How many integrations union_mass_properties has made in this process (a shape asked again is not
// integrated again): the set-up's costliest work (seconds for a shape of many spheres at a fine
// accuracy), which a shape that no clump uses must not pay (tests count it).
std::uint64_t union_mass_property_integrations();

}  // namespace dem
