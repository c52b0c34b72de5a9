// Random loose packings (LOS, the PDEM-EGD manual's packing pattern, section 4.2.1) and particle size distributions
// (its IPATTERN: one size, two sizes, uniform, normal, lognormal), reproducible from a seed.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/vec.hpp"

namespace dem::spec {

enum class SizeKind { One, Two, Uniform, Normal, Lognormal };

// Diameters: `mean` and `spread` (standard deviation) are those of the diameter itself, for every
// kind (the lognormal's log-space parameters are derived from them); samples outside
// [d_min, d_max] are drawn again. Two sizes: d_min and d_max, a `small_fraction` of them d_min.
struct SizeDistribution {
  SizeKind kind = SizeKind::One;
  double mean = 0;
  double spread = 0;
  double d_min = 0;
  double d_max = 0;
  double small_fraction = 0.5;
};

// The draws made and the diameters kept by the calls of one sampling (a packing filled to a solid
// fraction asks for its diameters one at a time): its budget of draws is the whole sampling's.
struct SizeDraws {
  double made = 0;
  double kept = 0;
};

// `count` diameters from `d`, truncated ones drawn again. Throws std::runtime_error when the draws
// pass 100 per diameter kept (over `so_far` and this call) plus 100,000.
std::vector<double> sample_diameters(const SizeDistribution& d, int count, std::mt19937_64& rng,
                                     SizeDraws* so_far = nullptr);

// Places spheres of the given diameters at random in the box [lo, hi] without overlap, largest
// first (random sequential addition), each wholly inside. Throws std::runtime_error naming how many
// could be placed when the box is too full (random addition stalls near a solid fraction of ~0.35).
// `accept(x, r)`, when given, must also hold for each sphere (a region inside a mesh); no sphere
// overlaps one of the `obstacles` (the particles already in the scene).
struct Sphere {
  Vec3 centre;
  double radius;
};
std::vector<Vec3> random_packing(const Vec3& lo, const Vec3& hi, std::vector<double>& diameters, std::mt19937_64& rng,
                                 const std::function<bool(const Vec3&, double)>& accept = {},
                                 const std::vector<Sphere>& obstacles = {});

}  // namespace dem::spec
