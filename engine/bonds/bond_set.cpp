#include "bonds/bond_set.hpp"

#include <algorithm>
#include <numeric>
#include <random>

namespace dem {

BondSet::BondSet(const BondSettings& settings, const Particles& p, const NeighborList& pairs, const std::vector<int>& stone)
    : moments_(settings.parallel) {
  std::mt19937_64 rng(settings.seed);
  std::normal_distribution<double> spread(1.0, settings.strength_spread);
  const int n = static_cast<int>(p.size());
  for (int i = 0; i < n; ++i) {
    for (int k = pairs.row_start[i]; k < pairs.row_start[i + 1]; ++k) {
      const int j = pairs.partner[k];
      if (stone[p.id[i]] != stone[p.id[j]]) continue;  // two stones touching: not one body
      const double r_min = std::min(p.radius[i], p.radius[j]);
      const double gap = (p.x[i] - p.x[j]).norm() - p.radius[i] - p.radius[j];
      if (gap > settings.gap_tolerance * r_min) continue;
      if (settings.region && !(settings.region->contains(p.x[i]) && settings.region->contains(p.x[j]))) continue;
      Bond b;
      b.i = i;
      b.j = j;
      b.geometry = BondGeometry::of(settings.radius_multiplier * r_min);
      b.kn = settings.youngs_modulus / (p.radius[i] + p.radius[j]);
      b.ks = settings.shear_stiffness_ratio * b.kn;
      double ratio = 1;
      const Vec3 centre = 0.5 * (p.x[i] + p.x[j]);
      for (const BondSettings::Zone& zone : settings.zones)
        if (zone.box.contains(centre)) ratio = zone.strength_ratio;
      // a spread strength is drawn once per bond, from the seed: the same bonds whatever the threads;
      // the normal distribution is cut at 5% of the mean (no bond is born broken)
      const double draw = settings.strength_spread > 0 ? std::max(0.05, spread(rng)) : 1.0;
      b.tensile_strength = settings.tensile_strength * ratio * draw;
      b.shear_strength = settings.shear_strength * ratio * draw;
      b.moments = settings.parallel;
      b.normal = (p.x[i] - p.x[j]).normalized();
      bonds_.push_back(b);
    }
  }
}

void BondSet::step(const Particles& p, double dt, double time, std::vector<Vec3>& f, std::vector<Vec3>& t) {
  for (Bond& b : bonds_) {
    if (b.state != BondBreak::Intact) continue;
    const Vec3 d = p.x[b.i] - p.x[b.j];
    const double dist = d.norm();
    const Vec3 n = d / dist;
    // the bond centre: the middle of the gap (or overlap) between the two surfaces
    const double gap = dist - p.radius[b.i] - p.radius[b.j];
    const Vec3 lever_i = -(p.radius[b.i] + 0.5 * gap) * n, lever_j = (p.radius[b.j] + 0.5 * gap) * n;
    BondMotion m;
    m.normal = n;
    m.velocity = (p.v[b.i] + p.w[b.i].cross(lever_i)) - (p.v[b.j] + p.w[b.j].cross(lever_j));
    m.spin = p.w[b.i] - p.w[b.j];
    const BondLoad load = bond_step(b, m, lever_i, lever_j, dt, time);
    f[b.i] += load.force;
    f[b.j] -= load.force;
    t[b.i] += load.moment_i;
    t[b.j] += load.moment_j;
  }
}

void BondSet::renumber(const std::vector<int>& new_to_old) {
  if (new_to_old.empty()) return;
  std::vector<int> old_to_new(new_to_old.size());
  for (std::size_t k = 0; k < new_to_old.size(); ++k) old_to_new[new_to_old[k]] = static_cast<int>(k);
  for (Bond& b : bonds_) {
    int i = old_to_new[b.i], j = old_to_new[b.j];
    if (i > j) {  // keep i < j: the bond's vectors are i's, so they change sign with the roles
      std::swap(i, j);
      b.shear_force = -b.shear_force;
      b.twist = -b.twist;
      b.bending = -b.bending;
      b.normal = -b.normal;
    }
    b.i = i;
    b.j = j;
  }
  // bond order decides the order of the force sums: keep it a function of the particle order
  std::stable_sort(bonds_.begin(), bonds_.end(), [](const Bond& a, const Bond& b) { return a.i != b.i ? a.i < b.i : a.j < b.j; });
}

double BondSet::elastic_energy() const {
  double e = 0;
  for (const Bond& b : bonds_) {
    if (b.state != BondBreak::Intact || b.kn <= 0) continue;
    const BondGeometry& g = b.geometry;
    e += b.normal_force * b.normal_force / (2 * b.kn * g.area) + b.shear_force.squaredNorm() / (2 * b.ks * g.area);
    if (b.moments) e += b.twist.squaredNorm() / (2 * b.ks * g.polar) + b.bending.squaredNorm() / (2 * b.kn * g.inertia);
  }
  return e;
}

BondCounts BondSet::counts() const {
  BondCounts c;
  for (const Bond& b : bonds_) {
    if (b.state == BondBreak::Intact) ++c.intact;
    else if (b.state == BondBreak::Tension) ++c.tension;
    else ++c.shear;
  }
  return c;
}

std::vector<int> BondSet::fragments(const std::vector<int>& id) const {
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
