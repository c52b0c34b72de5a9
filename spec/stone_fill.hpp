// Breakable stones (BallastDEM's bonded stones, its section 4.1.2): a stone's shape, the union of
// overlapping spheres, filled with equal small spheres that the parallel bonds then glue together.
#pragma once

#include <vector>

#include "clumps/mass_properties.hpp"
#include "core/vec.hpp"

namespace dem::spec {

// Centres of spheres of radius `r` on a face-centred cubic lattice of touching spheres (each
// touches up to 12 others), origin at the shape's origin, kept where the centre lies inside the
// union of `shape`. Only the largest set of spheres connected through touching neighbours is
// returned: a stone is one piece (a thin neck the lattice cannot follow would split it).
std::vector<Vec3> fill_with_spheres(const std::vector<MemberSphere>& shape, double r);

}  // namespace dem::spec
