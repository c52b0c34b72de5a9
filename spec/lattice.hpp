// Particle centres on a lattice filling a box: every sphere lies wholly inside it.
#pragma once

#include <array>
#include <vector>

#include "core/vec.hpp"

namespace dem::spec {

enum class LatticeKind { Cubic, Fcc, Hex };

// spacing: nearest-neighbour distance over the diameter. Order: z layers, then y rows, then x.
// `planar` (a 2D run): the lattice's layer in the x-z plane, at y = 0 (the box's y range is not used): CUBIC
// square, HEX the hexagonal packing of discs (rows along x, odd layers shifted half a spacing), FCC the square
// lattice turned 45 degrees (the FCC lattice's cube face).
std::vector<Vec3> lattice_sites(LatticeKind kind, const Vec3& lo, const Vec3& hi, double radius, double spacing,
                                bool planar = false);

// The PDEM-EGD manual's NICEX, NICEY, NICEZ: `counts` sites along x in each row, rows along y and
// layers along z, the first sphere's box corner at lo (FCC: a row is every other site of the
// half-cell grid, so each row still holds counts[0]). Same order as lattice_sites.
// `planar`: counts[1] is 1, the layer at y = 0.
std::vector<Vec3> lattice_sites_counted(LatticeKind kind, const Vec3& lo, double radius, double spacing,
                                        const std::array<int, 3>& counts, bool planar = false);

// How many sites lattice_sites would give at most (exact for a cubic lattice), counted without
// making them, in doubles: a box of 1e300 m must not overflow the count.
double lattice_site_bound(LatticeKind kind, const Vec3& lo, const Vec3& hi, double radius, double spacing,
                          bool planar = false);

}  // namespace dem::spec
