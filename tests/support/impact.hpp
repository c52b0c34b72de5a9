// Measures one impact: peak overlap, peak normal force, contact duration and rebound velocities.
#pragma once

#include <algorithm>

#include "support/scenes.hpp"

namespace dem::test {

struct ImpactRecord {
  double max_overlap = 0;
  double max_force = 0;
  double contact_time = 0;  // from touch to separation, interpolated between steps
  Simulation* sim = nullptr;
};

// Overlap of the first contact in the scene: particle 0 with particle 1, or with wall 0.
inline double first_overlap(const Simulation& sim) {
  const Particles& p = sim.particles();
  if (p.size() >= 2) return p.radius[0] + p.radius[1] - (p.x[0] - p.x[1]).norm();
  Vec3 n;
  double delta = 0;
  return sim.state().walls[0].contact(p.x[0], p.radius[0], n, delta)
             ? delta
             : -sim.state().walls[0].distance(p.x[0]) + p.radius[0];
}

inline double first_normal_force(const Simulation& sim) {
  const auto pairs = sim.pair_contacts();
  if (!pairs.empty()) return pairs[0].fn;
  const WallContacts& wc = sim.state().wall_contacts;
  return wc.fn.empty() ? 0 : *std::max_element(wc.fn.begin(), wc.fn.end());
}

// Steps until the bodies have touched and parted again (or max_steps).
inline ImpactRecord record_impact(Simulation& sim, std::int64_t max_steps) {
  ImpactRecord r;
  r.sim = &sim;
  double prev = first_overlap(sim);
  double t_start = -1;
  for (std::int64_t k = 0; k < max_steps; ++k) {
    const double t0 = sim.time();
    sim.step();
    const double d = first_overlap(sim);
    r.max_overlap = std::max(r.max_overlap, d);
    r.max_force = std::max(r.max_force, first_normal_force(sim));
    if (prev <= 0 && d > 0) t_start = t0 + sim.dt() * (-prev) / (d - prev);
    if (prev > 0 && d <= 0 && t_start >= 0) {
      r.contact_time = t0 + sim.dt() * prev / (prev - d) - t_start;
      return r;
    }
    prev = d;
  }
  return r;
}

}  // namespace dem::test
