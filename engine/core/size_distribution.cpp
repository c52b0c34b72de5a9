#include "core/size_distribution.hpp"

#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

namespace dem {

std::vector<double> sample_diameters(const SizeDistribution& d, int count, std::mt19937_64& rng, SizeDraws* so_far) {
  std::vector<double> out;
  out.reserve(count);
  std::function<double()> draw;
  std::uniform_real_distribution<double> unit(0, 1);
  switch (d.kind) {
    case SizeKind::One:
      draw = [&] { return d.mean; };
      break;
    case SizeKind::Two:
      draw = [&] { return unit(rng) < d.small_fraction ? d.d_min : d.d_max; };
      break;
    case SizeKind::Uniform:
      draw = [&] { return d.d_min + (d.d_max - d.d_min) * unit(rng); };
      break;
    case SizeKind::Normal: {
      auto normal = std::make_shared<std::normal_distribution<double>>(d.mean, d.spread);
      draw = [&, normal] { return (*normal)(rng); };
      break;
    }
    case SizeKind::Lognormal: {
      // mean m and standard deviation s of D: sigma^2 = ln(1 + s^2/m^2), mu = ln m - sigma^2 / 2
      const double s2 = std::log(1 + d.spread * d.spread / (d.mean * d.mean));
      auto lognormal = std::make_shared<std::lognormal_distribution<double>>(std::log(d.mean) - s2 / 2, std::sqrt(s2));
      draw = [&, lognormal] { return (*lognormal)(rng); };
      break;
    }
  }
  const bool bounded = d.kind == SizeKind::Normal || d.kind == SizeKind::Lognormal;
  // A spread so wide that hardly a draw falls between the bounds (or that overflows to NaN: a
  // fuzzed lognormal spread of 6.7e209 made every draw NaN, which passed as inside) must end.
  SizeDraws alone;
  SizeDraws& draws = so_far ? *so_far : alone;
  const double budget = 100.0 * (draws.kept + count) + 100000;
  while (static_cast<int>(out.size()) < count) {
    const double x = draw();
    if (++draws.made > budget)
      throw std::runtime_error("hardly any size drawn from this distribution falls between dMin and dMax (" +
                               std::to_string(static_cast<long long>(draws.kept) + static_cast<long long>(out.size())) +
                               " kept in " + std::to_string(static_cast<long long>(budget)) +
                               " draws): narrow the spread");
    if (!std::isfinite(x) || (bounded && !(x >= d.d_min && x <= d.d_max))) continue;  // truncated: drawn again
    out.push_back(x);
  }
  draws.kept += count;
  return out;
}

}  // namespace dem
