// Particle centres on a lattice filling a box: every sphere lies wholly inside it.
#pragma once

#include <array>
#include <vector>

#include "core/vec.hpp"

namespace dem::spec {

enum class LatticeKind { Cubic, Fcc, Hex };

// spacing: nearest-neighbour distance over the diameter. Order: z layers, then y rows, then x.
std::vector<Vec3> lattice_sites(LatticeKind kind, const Vec3& lo, const Vec3& hi, double radius, double spacing);

// The PDEM-EGD manual's NICEX, NICEY, NICEZ: `counts` sites along x in each row, rows along y and
// layers along z, the first sphere's box corner at lo (FCC: a row is every other site of the
// half-cell grid, so each row still holds counts[0]). Same order as lattice_sites.
std::vector<Vec3> lattice_sites_counted(LatticeKind kind, const Vec3& lo, double radius, double spacing,
                                        const std::array<int, 3>& counts);

// How many sites lattice_sites would give at most (exact for a cubic lattice), counted without
// making them, in doubles: a box of 1e300 m must not overflow the count.
double lattice_site_bound(LatticeKind kind, const Vec3& lo, const Vec3& hi, double radius, double spacing);

}  // namespace dem::spec
