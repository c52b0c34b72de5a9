// Neighbour-list build time for 100,000 spheres at a solid fraction of 0.35 in a box: one size,
// radii spread log-uniformly over 10:1, and a 10:1 bimodal mix with 0.1% large spheres by count.
// Each is also searched on a single cell grid sized for the largest sphere (counting pairs only),
// which is what the size levels of engine/neighbor replace.
//   build/bench_neighbor_search      (one thread: OMP_NUM_THREADS=1)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "neighbor/cell_grid.hpp"
#include "neighbor/neighbor_list.hpp"

namespace {

using dem::Particles;
using dem::Vec3;
using Clock = std::chrono::steady_clock;

Particles make_cloud(int n, double ratio, bool bimodal) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> r(n);
  double volume = 0;
  for (int i = 0; i < n; ++i) {
    r[i] = bimodal ? (i % 1000 == 999 ? 0.001 * ratio : 0.001) : 0.001 * std::pow(ratio, u(rng));
    volume += 4.0 / 3.0 * M_PI * r[i] * r[i] * r[i];
  }
  const double side = std::cbrt(volume / 0.35);
  Particles p;
  for (int i = 0; i < n; ++i) {
    p.x.push_back(Vec3(u(rng), u(rng), u(rng)) * side);
    p.radius.push_back(r[i]);
    p.mass.push_back(1);
    p.inv_mass.push_back(1);
    p.inv_inertia.push_back(1);
    p.material.push_back(0);
    p.id.push_back(i);
  }
  p.v.assign(n, Vec3::Zero());
  p.w = p.f = p.t = p.v;
  p.permute(dem::spatial_order(p, 0.002));
  return p;
}

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

void measure(const char* name, const Particles& p) {
  const int n = static_cast<int>(p.size()), reps = 5;
  double mean_d = 0;
  for (double r : p.radius) mean_d += 2 * r / n;
  const double skin = 0.1 * mean_d;
  dem::NeighborList previous, next;
  auto t0 = Clock::now();
  for (int k = 0; k < reps; ++k) dem::build_neighbor_list(p, {skin, false}, previous, {}, next);
  const double levels = seconds_since(t0) / reps;

  Vec3 lo = p.x[0], hi = p.x[0];
  for (const Vec3& x : p.x) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  const double r_max = *std::max_element(p.radius.begin(), p.radius.end());
  std::vector<int> all(n);
  for (int i = 0; i < n; ++i) all[i] = i;
  std::size_t pairs = 0;
  t0 = Clock::now();
  for (int k = 0; k < reps; ++k) {
    dem::CellGrid grid(lo, hi, 2 * r_max + skin, 4 * all.size() + 64);
    grid.fill(p.x, all);
    pairs = 0;
    for (int i = 0; i < n; ++i)
      grid.for_each_near(p.x[i], p.radius[i] + r_max + skin, [&](int j) {
        const double cut = p.radius[i] + p.radius[j] + skin;
        if (j > i && (p.x[j] - p.x[i]).squaredNorm() < cut * cut) ++pairs;
      });
  }
  const double single = seconds_since(t0) / reps;
  std::printf("%-28s %zu pairs (one grid: %zu); size levels %.3f s (%.2f us/particle), one grid %.3f s\n", name,
              next.pair_count(), pairs, levels, 1e6 * levels / n, single);
}

}  // namespace

int main() {
  const int n = 100000;
  measure("one size", make_cloud(n, 1, false));
  measure("10:1 log-uniform", make_cloud(n, 10, false));
  measure("10:1 bimodal, 0.1% large", make_cloud(n, 10, true));
}
