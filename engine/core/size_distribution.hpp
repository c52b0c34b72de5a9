// Particle size distributions (the PDEM-EGD manual's IPATTERN: one size, two sizes, uniform, normal,
// lognormal; the BallastDEM manual's mass distribution), shared by the packings of the spec and the
// particle sources of a run.
#pragma once

#include <random>
#include <vector>

namespace dem {

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

// The smallest and largest diameter `d` can give.
inline double smallest_diameter(const SizeDistribution& d) { return d.kind == SizeKind::One ? d.mean : d.d_min; }
inline double largest_diameter(const SizeDistribution& d) { return d.kind == SizeKind::One ? d.mean : d.d_max; }

}  // namespace dem
