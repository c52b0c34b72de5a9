#include "neighbor/neighbor_list.hpp"

#include <algorithm>
#include <cmath>

#include "neighbor/cell_grid.hpp"

namespace dem {
namespace {

// I + m r^2 about the contact point: 7/5 m r^2 for a solid sphere
double rolling_inertia(const Particles& p, int i) { return 1.4 * p.mass[i] * p.radius[i] * p.radius[i]; }

struct SizeLevel {
  double r_max = 0;
  std::vector<int> members;
};

// Radii within a factor 2 share a level.
std::vector<SizeLevel> size_levels(const std::vector<double>& radius) {
  const double r_min = *std::min_element(radius.begin(), radius.end());
  std::vector<SizeLevel> levels;
  for (std::size_t i = 0; i < radius.size(); ++i) {
    const int level = r_min > 0 ? std::max(0, static_cast<int>(std::floor(std::log2(radius[i] / r_min)))) : 0;
    if (level >= static_cast<int>(levels.size())) levels.resize(level + 1);
    levels[level].members.push_back(static_cast<int>(i));
    levels[level].r_max = std::max(levels[level].r_max, radius[i]);
  }
  levels.erase(std::remove_if(levels.begin(), levels.end(), [](const SizeLevel& l) { return l.members.empty(); }),
               levels.end());
  return levels;
}

void bounding_box(const std::vector<Vec3>& x, Vec3& lo, Vec3& hi) {
  lo = hi = x[0];
  for (const Vec3& p : x) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
}

// Index of `j` in the sorted row of `i` of `list`, or -1.
int find_pair(const NeighborList& list, int i, int j) {
  if (i < 0 || i + 1 >= static_cast<int>(list.row_start.size())) return -1;
  const auto begin = list.partner.begin() + list.row_start[i];
  const auto end = list.partner.begin() + list.row_start[i + 1];
  const auto it = std::lower_bound(begin, end, j);
  return (it != end && *it == j) ? static_cast<int>(it - list.partner.begin()) : -1;
}

}  // namespace

PairConstants pair_constants(const Particles& p, int i, int j) {
  const double ri = p.radius[i], rj = p.radius[j];
  const double ii = rolling_inertia(p, i), ij = rolling_inertia(p, j);
  return {std::sqrt(reduced(p.inv_mass[i], p.inv_mass[j], p.mass[i], p.mass[j])), ri * rj / (ri + rj),
          reduced(p.inv_mass[i] > 0 ? 1 / ii : 0, p.inv_mass[j] > 0 ? 1 / ij : 0, ii, ij)};
}

PairConstants wall_constants(const Particles& p, int i) {
  return {std::sqrt(p.mass[i]), p.radius[i], rolling_inertia(p, i)};
}

void build_neighbor_list(const Particles& p, const NeighborBuildOptions& options, const NeighborList& previous,
                         const std::vector<int>& new_to_old, NeighborList& next) {
  const int n = static_cast<int>(p.size());
  next.row_start.assign(n + 1, 0);
  next.partner.clear();
  if (n == 0) return;

  Vec3 lo, hi;
  bounding_box(p.x, lo, hi);
  std::vector<SizeLevel> levels = size_levels(p.radius);
  std::vector<CellGrid> grids;
  for (const SizeLevel& level : levels) {
    grids.emplace_back(lo, hi, 2 * level.r_max + options.skin, 4 * level.members.size() + 64);
    grids.back().fill(p.x, level.members);
  }

  // Each pair is found once, from its smaller sphere: a particle scans only its own level and the
  // coarser ones (a large sphere never scans the fine grids, whose cells are small for its reach).
  // Within a level, the pair belongs to the lower index. Pairs are found in fixed blocks
  // (independent of the thread count), then put into rows and each row sorted.
  std::vector<int> level_of(n);
  for (std::size_t l = 0; l < levels.size(); ++l)
    for (int i : levels[l].members) level_of[i] = static_cast<int>(l);
  constexpr int kBlock = 512;
  const int blocks = (n + kBlock - 1) / kBlock;
  std::vector<std::vector<std::pair<int, int>>> block_pairs(blocks);
  // Packed spheres have a dozen neighbours within reach, a few dozen with a wide skin: a block with
  // kMostPairsPerParticle on average holds particles that overlap far past contact (20,000 at one
  // point once asked for 2e8 pairs and the memory to hold them). The search stops there.
  constexpr std::size_t kMostPairsPerParticle = 256;
  std::vector<int> crowded(blocks, -1);
#pragma omp parallel for schedule(dynamic) if (n >= kParallelMinParticles)
  for (int b = 0; b < blocks; ++b) {
    std::vector<std::pair<int, int>>& out = block_pairs[b];
    for (int i = b * kBlock; i < std::min(n, (b + 1) * kBlock) && crowded[b] < 0; ++i) {
      if (out.size() > kMostPairsPerParticle * kBlock) {
        crowded[b] = i;
        break;
      }
      const Vec3 xi = p.x[i];
      const double ri = p.radius[i];
      for (std::size_t l = level_of[i]; l < grids.size(); ++l) {
        const bool same_level = static_cast<int>(l) == level_of[i];
        grids[l].for_each_near(xi, ri + levels[l].r_max + options.skin, [&](int j) {
          if (same_level ? j <= i : false) return;
          if (!p.body.empty() && p.body[i] >= 0 && p.body[i] == p.body[j]) return;  // one rigid body
          const double cut = ri + p.radius[j] + options.skin;
          if ((p.x[j] - xi).squaredNorm() < cut * cut && out.size() <= kMostPairsPerParticle * kBlock)
            out.emplace_back(std::min(i, j), std::max(i, j));
        });
      }
    }
  }
  for (int b = 0; b < blocks; ++b)
    if (crowded[b] >= 0) {
      const int i = crowded[b];
      throw CrowdedError("more than " + std::to_string(kMostPairsPerParticle) +
                         " neighbours within reach of each particle around particle " + std::to_string(p.id[i] + 1) +
                         " (at " + std::to_string(p.x[i].x()) + ", " + std::to_string(p.x[i].y()) + ", " +
                         std::to_string(p.x[i].z()) +
                         "): particles there overlap far past contact, or lie on top of "
                         "each other");
    }
  for (const auto& found : block_pairs)
    for (const auto& [a, b] : found) ++next.row_start[a + 1];
  for (int i = 0; i < n; ++i) next.row_start[i + 1] += next.row_start[i];
  next.partner.resize(next.row_start[n]);
  {
    std::vector<int> fill(next.row_start.begin(), next.row_start.end() - 1);
    for (const auto& found : block_pairs)
      for (const auto& [a, b] : found) next.partner[fill[a]++] = b;
  }
#pragma omp parallel for schedule(static) if (n >= kParallelMinParticles)
  for (int i = 0; i < n; ++i)
    std::sort(next.partner.begin() + next.row_start[i], next.partner.begin() + next.row_start[i + 1]);

  const std::size_t pairs = next.partner.size();
  next.sqrt_m_eff.resize(pairs);
  next.r_eff.resize(pairs);
  next.i_roll.resize(pairs);
#pragma omp parallel for schedule(static) if (n >= kParallelMinParticles)
  for (int i = 0; i < n; ++i)
    for (int k = next.row_start[i]; k < next.row_start[i + 1]; ++k) {
      const PairConstants c = pair_constants(p, i, next.partner[k]);
      next.sqrt_m_eff[k] = c.sqrt_m_eff;
      next.r_eff[k] = c.r_eff;
      next.i_roll[k] = c.i_roll;
    }

  // Carry the history of pairs that were already listed.
  next.shear.assign(pairs, Vec3::Zero());
  next.touched.assign(pairs, 0);
  if (options.keep_rolling_history)
    next.roll.assign(pairs, Vec3::Zero());
  else
    next.roll.clear();
  if (previous.partner.empty()) return;
  const bool keep_roll = options.keep_rolling_history && !previous.roll.empty();
#pragma omp parallel for schedule(static) if (n >= kParallelMinParticles)
  for (int i = 0; i < n; ++i) {
    const int oi = new_to_old.empty() ? i : new_to_old[i];
    for (int k = next.row_start[i]; k < next.row_start[i + 1]; ++k) {
      const int oj = new_to_old.empty() ? next.partner[k] : new_to_old[next.partner[k]];
      const int old = oi < oj ? find_pair(previous, oi, oj) : find_pair(previous, oj, oi);
      if (old < 0) continue;
      const double sign = oi < oj ? 1.0 : -1.0;
      next.shear[k] = sign * previous.shear[old];
      if (!previous.touched.empty()) next.touched[k] = previous.touched[old];
      if (keep_roll) next.roll[k] = sign * previous.roll[old];
    }
  }
}

std::vector<int> spatial_order(const Particles& p, double cell_size) {
  const int n = static_cast<int>(p.size());
  std::vector<int> order(n);
  if (n == 0) return order;
  Vec3 lo, hi;
  bounding_box(p.x, lo, hi);
  CellGrid grid(lo, hi, cell_size, static_cast<std::size_t>(n) + 64);
  std::vector<int> cell(n);
  for (int i = 0; i < n; ++i) {
    const auto c = grid.cell_of(p.x[i]);
    cell[i] = grid.linear(c[0], c[1], c[2]);
    order[i] = i;
  }
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return cell[a] < cell[b]; });
  return order;
}

}  // namespace dem
