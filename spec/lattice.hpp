// Particle centres on a lattice filling a box: every sphere lies wholly inside it.
#pragma once

#include <vector>

#include "core/vec.hpp"

namespace dem::spec {

enum class LatticeKind { Cubic, Fcc, Hex };

// spacing: nearest-neighbour distance over the diameter. Order: z layers, then y rows, then x.
std::vector<Vec3> lattice_sites(LatticeKind kind, const Vec3& lo, const Vec3& hi, double radius, double spacing);

// How many sites lattice_sites would give at most (exact for a cubic lattice), counted without
// making them, in doubles: a box of 1e300 m must not overflow the count.
double lattice_site_bound(LatticeKind kind, const Vec3& lo, const Vec3& hi, double radius, double spacing);

}  // namespace dem::spec
