#include "bonds/bond_set.hpp"

#include <algorithm>
#include <numeric>
#include <random>

#include "bonds/bond_models.hpp"
#include "core/parallel.hpp"

namespace dem {

namespace {

BondEnd end_of(const Particles& p, int i) { return {p.x[i], p.q[i], p.radius[i]}; }

// Loads the intact bonds of bonds[begin, end) kBondLanes at a time (bond_loads: the same bits as
// one at a time) and hands each bond's index and load to `done`, in bond order.
template <class Done>
void load_intact(std::vector<Bond>& bonds, const Particles& p, double time, int begin, int end, Done done) {
  Bond* group[kBondLanes];
  int index[kBondLanes];
  BondEnd ends_i[kBondLanes], ends_j[kBondLanes];
  BondLoad loads[kBondLanes];
  int m = 0;
  auto flush = [&] {
    bond_loads(group, ends_i, ends_j, m, time, loads);
    for (int g = 0; g < m; ++g) done(index[g], loads[g]);
    m = 0;
  };
  for (int k = begin; k < end; ++k) {
    Bond& b = bonds[k];
    if (b.state != BondBreak::Intact) continue;
    group[m] = &b, index[m] = k, ends_i[m] = end_of(p, b.i), ends_j[m] = end_of(p, b.j);
    if (++m == kBondLanes) flush();
  }
  if (m > 0) flush();
}

}  // namespace

BondSet::BondSet(const BondSettings& settings, const Particles& p, const NeighborList& pairs,
                 const std::vector<int>& stone) {
  std::mt19937_64 rng(settings.seed);
  std::normal_distribution<double> spread(1.0, settings.strength_spread);
  const int n = static_cast<int>(p.size());
  for (int i = 0; i < n; ++i) {
    for (int k = pairs.row_start[i]; k < pairs.row_start[i + 1]; ++k) {
      const int j = pairs.partner[k];
      if (stone[p.id[i]] != stone[p.id[j]]) continue;                       // two stones touching: not one body
      if (!p.body.empty() && (p.body[i] >= 0 || p.body[j] >= 0)) continue;  // a clump is rigid already
      const double r_min = std::min(p.radius[i], p.radius[j]);
      const double gap = (p.x[i] - p.x[j]).norm() - p.radius[i] - p.radius[j];
      if (gap > settings.gap_tolerance * r_min) continue;
      if (settings.region && !(settings.region->contains(p.x[i]) && settings.region->contains(p.x[j]))) continue;
      double ratio = 1;
      const Vec3 centre = 0.5 * (p.x[i] + p.x[j]);
      for (const BondSettings::Zone& zone : settings.zones)
        if (zone.box.contains(centre)) ratio = zone.strength_ratio;
      // a spread strength is drawn once per bond, from the seed: the same bonds whatever the threads;
      // the normal distribution is cut at 5% of the mean (no bond is born broken)
      const double draw = settings.strength_spread > 0 ? std::max(0.05, spread(rng)) : 1.0;
      Bond b = bond_between(settings, p.radius[i], p.radius[j], ratio * draw);
      b.i = i;
      b.j = j;
      glue(b, end_of(p, i), end_of(p, j));
      bonds_.push_back(b);
    }
  }
}

void BondSet::step(const Particles& p, double time, std::vector<Vec3>& f, std::vector<Vec3>& t) {
  const int n = static_cast<int>(bonds_.size());
  auto add = [&](const Bond& b, const BondLoad& load) {
    f[b.i] += load.force;
    f[b.j] -= load.force;
    t[b.i] += load.moment_i;
    t[b.j] += load.moment_j;
  };
  if (n < kParallelMinBonds || omp_get_max_threads() == 1) {
    load_intact(bonds_, p, time, 0, n, [&](int k, const BondLoad& load) { add(bonds_[k], load); });
    return;
  }
  // The loads on all threads (each bond's own state is all a load changes), then added in bond
  // order on this one: the same sums, bit for bit, as the loop above.
  loads_.resize(bonds_.size());
  loaded_.resize(bonds_.size());
  for_ranges(n, kParallelMinBonds, [&](int begin, int end) {
    for (int k = begin; k < end; ++k) loaded_[k] = bonds_[k].state == BondBreak::Intact;
    load_intact(bonds_, p, time, begin, end, [&](int k, const BondLoad& load) { loads_[k] = load; });
  });
  for (int k = 0; k < n; ++k)
    if (loaded_[k]) add(bonds_[k], loads_[k]);  // a bond that broke in this step adds its zeros, as above
}

void BondSet::renumber(const std::vector<int>& new_to_old) {
  if (new_to_old.empty()) return;
  std::vector<int> old_to_new(new_to_old.size());
  for (std::size_t k = 0; k < new_to_old.size(); ++k) old_to_new[new_to_old[k]] = static_cast<int>(k);
  for (Bond& b : bonds_) {
    b.i = old_to_new[b.i];
    b.j = old_to_new[b.j];
    if (b.i > b.j) swap_ends(b);  // keep i < j: the bond's state is i's
  }
  // bond order decides the order of the force sums: keep it a function of the particle order
  std::stable_sort(bonds_.begin(), bonds_.end(),
                   [](const Bond& a, const Bond& b) { return a.i != b.i ? a.i < b.i : a.j < b.j; });
}

double BondSet::elastic_energy() const {
  double e = 0;
  for (const Bond& b : bonds_) e += bond_energy(b);
  return e;
}

BondCounts BondSet::counts() const {
  BondCounts c;
  for (const Bond& b : bonds_) {
    if (b.state == BondBreak::Intact)
      ++c.intact;
    else if (b.state == BondBreak::Tension)
      ++c.tension;
    else
      ++c.shear;
  }
  return c;
}

std::vector<int> BondSet::fragments(const std::vector<int>& id, const std::vector<int>& body) const {
  const int n = static_cast<int>(id.size());
  std::vector<int> root(n);
  std::iota(root.begin(), root.end(), 0);
  auto find = [&](int a) {
    while (root[a] != a) a = root[a] = root[root[a]];
    return a;
  };
  for (const Bond& b : bonds_)
    if (b.state == BondBreak::Intact) {
      const int a = find(b.i), c = find(b.j);
      if (a != c) root[std::max(a, c)] = std::min(a, c);
    }
  // a rigid clump's members are one piece, whatever bonds say
  std::vector<int> first_of_body;
  for (int i = 0; i < static_cast<int>(body.size()) && i < n; ++i) {
    if (body[i] < 0) continue;
    if (static_cast<int>(first_of_body.size()) <= body[i]) first_of_body.resize(body[i] + 1, -1);
    int& first = first_of_body[body[i]];
    if (first < 0) {
      first = i;
      continue;
    }
    const int a = find(first), c = find(i);
    if (a != c) root[std::max(a, c)] = std::min(a, c);
  }
  // number the fragments by their lowest particle id, so that the numbers do not depend on the order
  std::vector<int> lowest(n, -1);
  for (int i = 0; i < n; ++i) {
    const int r = find(i);
    if (lowest[r] < 0 || id[i] < lowest[r]) lowest[r] = id[i];
  }
  std::vector<std::pair<int, int>> order;  // (lowest id, root)
  for (int i = 0; i < n; ++i)
    if (find(i) == i) order.emplace_back(lowest[i], i);
  std::sort(order.begin(), order.end());
  std::vector<int> number(n, 0);
  for (std::size_t k = 0; k < order.size(); ++k) number[order[k].second] = static_cast<int>(k) + 1;
  std::vector<int> out(n);
  for (int i = 0; i < n; ++i) out[i] = number[find(i)];
  return out;
}

}  // namespace dem
