#include "spec/packing.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace dem::spec {

std::vector<Vec3> random_packing(const Vec3& box_lo, const Vec3& box_hi, std::vector<double>& diameters,
                                 std::mt19937_64& rng, const std::function<bool(const Vec3&, double)>& accept,
                                 const std::vector<Sphere>& obstacles, bool planar) {
  Vec3 lo = box_lo, hi = box_hi;
  if (planar) lo.y() = hi.y() = 0;
  std::sort(diameters.begin(), diameters.end(), std::greater<>());
  const int n = static_cast<int>(diameters.size());
  std::vector<Vec3> placed;
  placed.reserve(n);
  if (n == 0) return placed;
  // The spheres already there that a new one could touch, then the new ones, in one hash grid of
  // cell = the largest diameter: a new sphere checks the 27 cells around it.
  std::vector<Vec3> centre;
  std::vector<double> radius;
  double cell = diameters[0];
  for (const Sphere& o : obstacles) {
    const Vec3 reach = Vec3::Constant(o.radius);
    if (((o.centre + reach).array() < lo.array()).any() || ((o.centre - reach).array() > hi.array()).any()) continue;
    centre.push_back(o.centre);
    radius.push_back(o.radius);
    cell = std::max(cell, 2 * o.radius);
  }
  const int given = static_cast<int>(centre.size());
  auto key = [&](const Vec3& x) {
    const auto c = ((x - lo) / cell).array().floor().cast<long long>();
    return (c[0] * 73856093LL) ^ (c[1] * 19349663LL) ^ (c[2] * 83492791LL);
  };
  std::unordered_multimap<long long, int> grid;
  for (int o = 0; o < given; ++o) grid.emplace(key(centre[o]), o);
  constexpr int kAttempts = 2000;
  for (int k = 0; k < n; ++k) {
    const double r = diameters[k] / 2;
    Vec3 a = lo + Vec3::Constant(r), b = hi - Vec3::Constant(r);
    if (planar) a.y() = b.y() = 0;
    if ((b.array() < a.array()).any())
      throw std::runtime_error("a sphere of diameter " + std::to_string(diameters[k]) + " does not fit in the box");
    bool ok = false;
    for (int attempt = 0; attempt < kAttempts && !ok; ++attempt) {
      Vec3 x;
      for (int d = 0; d < 3; ++d)
        x[d] = planar && d == 1 ? 0.0 : std::uniform_real_distribution<double>(a[d], b[d])(rng);
      ok = !accept || accept(x, r);
      for (int dz = -1; dz <= 1 && ok; ++dz)
        for (int dy = -1; dy <= 1 && ok; ++dy)
          for (int dx = -1; dx <= 1 && ok; ++dx) {
            const auto range = grid.equal_range(key(x + cell * Vec3(dx, dy, dz)));
            for (auto it = range.first; it != range.second && ok; ++it) {
              const int o = it->second;
              const double reach = r + radius[o];
              ok = (centre[o] - x).squaredNorm() >= reach * reach;
            }
          }
      if (ok) {
        grid.emplace(key(x), given + k);
        centre.push_back(x);
        radius.push_back(r);
        placed.push_back(x);
      }
    }
    if (!ok)
      throw std::runtime_error(
          "placed only " + std::to_string(k) + " of " + std::to_string(n) +
          (planar ? " discs: the region is too full for random placement (in 2D it stalls near an area fraction of 0.5)"
                  : " spheres: the region is too full for random placement (it stalls near a solid fraction of 0.35)"));
  }
  return placed;
}

}  // namespace dem::spec
