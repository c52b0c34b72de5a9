// The force loop for one contact law. Pairs are evaluated in parallel into per-pair results, then
// each particle gathers its pairs in ascending pair order, adds its wall contacts and gravity and
// takes its second half kick. No particle is written by two threads and every sum has a fixed
// order, so results are bit-identical for any number of threads.
#pragma once

#include <algorithm>
#include <limits>

#include "contact/contact_law.hpp"
#include "sim/force_kernel.hpp"

namespace dem {

template <class Law, bool kWalls>
class ForceKernelImpl final : public ForceKernel {
 public:
  void compute_and_kick(SimState& s) override {
    evaluate_pairs(s);
    gather_and_kick(s);
  }

  bool has_rolling_spring() const override { return Law::kRollingSpring; }

  ContactSummary summarize(const SimState& s) const override {
    const Particles& p = s.particles;
    ContactSummary sum;
    auto note = [&](int i, double delta, double r_min, double elastic) {
      ++sum.contacts;
      sum.elastic_energy += elastic;
      if (delta / r_min > sum.max_overlap_fraction) {
        sum.max_overlap_fraction = delta / r_min;
        sum.worst_particle = i;
      }
    };
    const int n = static_cast<int>(p.size());
    for (int i = 0; i < n; ++i) {
      for (int k = s.neighbors.row_start[i]; k < s.neighbors.row_start[i + 1]; ++k) {
        const int j = s.neighbors.partner[k];
        const double rs = p.radius[i] + p.radius[j];
        const double dist = (p.x[i] - p.x[j]).norm();
        if (dist >= rs) continue;
        const double r_eff = p.radius[i] * p.radius[j] / rs;
        note(i, rs - dist, std::min(p.radius[i], p.radius[j]),
             Law::NormalLaw::elastic_energy(s.table(p.material[i], p.material[j]), rs - dist, r_eff));
      }
      if constexpr (kWalls) {
        for (int e = s.wall_contacts.row_start[i]; e < s.wall_contacts.row_start[i + 1]; ++e) {
          const Wall& wall = s.walls[s.wall_contacts.wall[e]];
          Vec3 normal;
          double delta;
          if (!wall.contact(p.x[i], p.radius[i], normal, delta)) continue;
          note(i, delta, p.radius[i],
               Law::NormalLaw::elastic_energy(s.table(p.material[i], wall.material), delta, p.radius[i]));
        }
      }
    }
    return sum;
  }

 private:
  static double reduced(double inv_a, double inv_b, double a, double b) {
    // two held bodies: fall back to the plain reduced value so the damping stays finite
    return inv_a + inv_b > 0 ? 1 / (inv_a + inv_b) : a * b / (a + b);
  }

  static void evaluate_pairs(SimState& s) {
    const Particles& p = s.particles;
    NeighborList& nl = s.neighbors;
    PairResults& out = s.pairs;
    const int n = static_cast<int>(p.size());
    const double dt = s.dt, half_dt = 0.5 * dt;
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) {
      const Vec3 xi = p.x[i], vi = p.v[i], wi = p.w[i];
      const Vec3 ai = p.inv_mass[i] * p.f[i];  // acceleration of the last step, for the prediction
      const double ri = p.radius[i];
      for (int k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
        const int j = nl.partner[k];
        const Vec3 d = xi - p.x[j];
        const double rs = ri + p.radius[j];
        const double d2 = d.squaredNorm();
        if (d2 >= rs * rs) {
          out.touching[k] = 0;
          if (!nl.shear[k].isZero(0)) nl.shear[k].setZero();
          if constexpr (Law::kRollingSpring) nl.roll[k].setZero();
          continue;
        }
        const double rj = p.radius[j];
        const double dist = std::sqrt(d2);
        ContactInput c;
        c.n = d / dist;
        c.delta = rs - dist;
        c.v_rel = vi - p.v[j] - (ri * wi + rj * p.w[j]).cross(c.n);
        const double vn = c.v_rel.dot(c.n);
        c.vn_now = vn + half_dt * (ai - p.inv_mass[j] * p.f[j]).dot(c.n);
        c.onset = boundary_share(c.delta, vn, dt);
        c.w_rel = wi - p.w[j];
        c.m_eff = reduced(p.inv_mass[i], p.inv_mass[j], p.mass[i], p.mass[j]);
        c.r_eff = ri * rj / rs;
        if constexpr (Law::kRolling) {
          // I + m r^2 = 7/5 m r^2 for a solid sphere (Ai et al. 2011, eq. 13)
          const double ii = 1.4 * p.mass[i] * ri * ri, ij = 1.4 * p.mass[j] * rj * rj;
          c.i_roll = reduced(p.inv_mass[i] > 0 ? 1 / ii : 0, p.inv_mass[j] > 0 ? 1 / ij : 0, ii, ij);
        }
        c.dt = dt;
        ContactHistory h{&nl.shear[k], Law::kRollingSpring ? &nl.roll[k] : nullptr};
        const ContactOutput r = Law::evaluate(s.table(p.material[i], p.material[j]), c, h);
        out.force[k] = r.force;
        out.lever[k] = c.n.cross(r.shear_force);
        if constexpr (Law::kRolling) out.roll_moment[k] = r.roll_moment;
        out.fn[k] = r.fn;
        out.touching[k] = 1;
      }
    }
  }

  static void gather_and_kick(SimState& s) {
    Particles& p = s.particles;
    const NeighborList& nl = s.neighbors;
    const PairResults& pr = s.pairs;
    const int n = static_cast<int>(p.size());
    const double half_dt = 0.5 * s.dt;
    const Vec3 g = s.gravity;
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) {
      const double ri = p.radius[i];
      Vec3 f = Vec3::Zero(), t = Vec3::Zero();
      // pairs where i is the partner come first: their indices are below i's own row
      for (int a = pr.as_partner_start[i]; a < pr.as_partner_start[i + 1]; ++a) {
        const int k = pr.as_partner[a];
        if (!pr.touching[k]) continue;
        f -= pr.force[k];
        t -= ri * pr.lever[k];
        if constexpr (Law::kRolling) t -= pr.roll_moment[k];
      }
      for (int k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
        if (!pr.touching[k]) continue;
        f += pr.force[k];
        t -= ri * pr.lever[k];
        if constexpr (Law::kRolling) t += pr.roll_moment[k];
      }
      if constexpr (kWalls) add_wall_forces(s, i, f, t);
      f += p.mass[i] * g;
      p.f[i] = f;
      p.t[i] = t;
      p.v[i] += half_dt * p.inv_mass[i] * f;
      p.w[i] += half_dt * p.inv_inertia[i] * t;
    }
  }

  static void add_wall_forces(SimState& s, int i, Vec3& f, Vec3& t) {
    const Particles& p = s.particles;
    WallContacts& wc = s.wall_contacts;
    const double ri = p.radius[i];
    for (int e = wc.row_start[i]; e < wc.row_start[i + 1]; ++e) {
      const Wall& wall = s.walls[wc.wall[e]];
      ContactInput c;
      if (p.inv_mass[i] == 0 || !wall.contact(p.x[i], ri, c.n, c.delta)) {
        wc.touching[e] = 0;
        wc.fn[e] = wc.ft[e] = 0;
        wc.shear[e].setZero();
        if constexpr (Law::kRollingSpring) wc.roll[e].setZero();
        continue;
      }
      c.v_rel = p.v[i] - ri * p.w[i].cross(c.n);
      const double vn = c.v_rel.dot(c.n);
      c.vn_now = vn + 0.5 * s.dt * p.inv_mass[i] * p.f[i].dot(c.n);
      c.onset = boundary_share(c.delta, vn, s.dt);
      c.w_rel = p.w[i];
      c.m_eff = p.mass[i];
      c.r_eff = ri;
      if constexpr (Law::kRolling) c.i_roll = 1.4 * p.mass[i] * ri * ri;
      c.dt = s.dt;
      ContactHistory h{&wc.shear[e], Law::kRollingSpring ? &wc.roll[e] : nullptr};
      const ContactOutput r = Law::evaluate(s.table(p.material[i], wall.material), c, h);
      f += r.force;
      t -= ri * c.n.cross(r.shear_force);
      if constexpr (Law::kRolling) t += r.roll_moment;
      wc.touching[e] = 1;
      wc.fn[e] = r.fn;
      wc.ft[e] = r.shear_force.norm();
    }
  }
};

}  // namespace dem
