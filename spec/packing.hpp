// Random loose packings (LOS, the PDEM-EGD manual's packing pattern, section 4.2.1) and particle size distributions
// (its IPATTERN: one size, two sizes, uniform, normal, lognormal), reproducible from a seed.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/size_distribution.hpp"
#include "core/vec.hpp"

namespace dem::spec {

using dem::sample_diameters;
using dem::SizeDistribution;
using dem::SizeDraws;
using dem::SizeKind;

// Places spheres of the given diameters at random in the box [lo, hi] without overlap, largest
// first (random sequential addition), each wholly inside. Throws std::runtime_error naming how many
// could be placed when the box is too full (random addition stalls near a solid fraction of ~0.35).
// `accept(x, r)`, when given, must also hold for each sphere (a region inside a mesh); no sphere
// overlaps one of the `obstacles` (the particles already in the scene). `planar` (a 2D run): every centre at
// y = 0 (the box's y range is not used).
struct Sphere {
  Vec3 centre;
  double radius;
};
std::vector<Vec3> random_packing(const Vec3& lo, const Vec3& hi, std::vector<double>& diameters, std::mt19937_64& rng,
                                 const std::function<bool(const Vec3&, double)>& accept = {},
                                 const std::vector<Sphere>& obstacles = {}, bool planar = false);

}  // namespace dem::spec
