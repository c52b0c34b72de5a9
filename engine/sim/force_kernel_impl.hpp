// The force loop for one contact law, over the fixed particle blocks of BlockPlan (sim/state.hpp):
// phase 1 evaluates every pair once, adding it to both bodies when they share a block and leaving
// j's share for later when they do not; phase 2 adds those shares, the walls and gravity to each
// particle and takes its second half kick. Each block and each particle is written by one thread,
// and the order of every sum is fixed by the blocks alone: bit-identical for any number of threads.
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
        note(i, rs - dist, std::min(p.radius[i], p.radius[j]),
             Law::NormalLaw::elastic_energy(s.table(p.material[i], p.material[j]), rs - dist,
                                            s.neighbors.constants[k].r_eff));
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
  static void evaluate_pairs(SimState& s) {
    Particles& p = s.particles;
    NeighborList& nl = s.neighbors;
    PairResults& out = s.pairs;
    BlockPlan& plan = s.blocks;
    std::vector<Vec3>& f_next = s.f_next;
    const int n = static_cast<int>(p.size());
    const int size = plan.block_size;
    const int blocks = (n + size - 1) / size;
    const double dt = s.dt, half_dt = 0.5 * dt;
#pragma omp parallel for schedule(dynamic, 1) if (blocks > 1)
    for (int b = 0; b < blocks; ++b) {
      const int begin = b * size, end = std::min(n, begin + size);
      for (int i = begin; i < end; ++i) {
        f_next[i].setZero();
        p.t[i].setZero();
      }
      std::vector<double> row_dist, row_inv;  // per row: distance and its inverse, before the force pass
      for (int i = begin; i < end; ++i) {
        const Vec3 xi = p.x[i], vi = p.v[i], wi = p.w[i];
        const Vec3 ai = p.inv_mass[i] * p.f[i];  // acceleration of the last step, for the prediction
        const double ri = p.radius[i];
        Vec3 fi = f_next[i], ti = p.t[i];
        const int row_begin = nl.row_start[i], row_end = nl.row_start[i + 1];
        // Pass 1: the distances. Short independent iterations let the square roots of a whole row
        // overlap instead of each contact waiting for its own (measured: ~40 cycles per contact).
        const int row_length = row_end - row_begin;
        row_dist.resize(row_length);
        row_inv.resize(row_length);
        for (int k = row_begin; k < row_end; ++k) row_dist[k - row_begin] = (xi - p.x[nl.partner[k]]).squaredNorm();
        for (int m = 0; m < row_length; ++m) {
          row_dist[m] = std::sqrt(row_dist[m]);
          row_inv[m] = 1 / row_dist[m];
        }
        for (int k = row_begin; k < row_end; ++k) {
          const int j = nl.partner[k];
          const double rj = p.radius[j];
          const double rs = ri + rj;
          const double dist = row_dist[k - row_begin];
          if (dist >= rs) {
            out.touching[k] = 0;
            if (!nl.shear[k].isZero(0)) nl.shear[k].setZero();
            if constexpr (Law::kRollingSpring) nl.roll[k].setZero();
            if (j >= end) {
              plan.deferred_force[k].setZero();
              plan.deferred_torque[k].setZero();
            }
            continue;
          }
          const Vec3 d = xi - p.x[j];
          ContactInput c;
          c.n = d * row_inv[k - row_begin];
          c.delta = rs - dist;
          c.v_rel = vi - p.v[j] - (ri * wi + rj * p.w[j]).cross(c.n);
          const double vn = c.v_rel.dot(c.n);
          c.vn_now = vn + half_dt * (ai - p.inv_mass[j] * p.f[j]).dot(c.n);
          c.onset = boundary_share(c.delta, vn, dt);
          c.w_rel = wi - p.w[j];
          c.pair = &nl.constants[k];
          c.dt = dt;
          ContactHistory h{&nl.shear[k], Law::kRollingSpring ? &nl.roll[k] : nullptr};
          const ContactOutput r = Law::evaluate(s.table(p.material[i], p.material[j]), c, h);
          const Vec3 lever = c.n.cross(r.shear_force);
          Vec3 torque_j = -rj * lever;
          fi += r.force;
          ti -= ri * lever;
          if constexpr (Law::kRolling) {
            ti += r.roll_moment;
            torque_j -= r.roll_moment;
          }
          if (j < end) {
            f_next[j] -= r.force;
            p.t[j] += torque_j;
          } else {
            plan.deferred_force[k] = -r.force;
            plan.deferred_torque[k] = torque_j;
          }
          out.fn[k] = r.fn;
          out.ft_squared[k] = r.shear_force.squaredNorm();
          out.touching[k] = 1;
        }
        f_next[i] = fi;
        p.t[i] = ti;
      }
    }
  }

  static void gather_and_kick(SimState& s) {
    Particles& p = s.particles;
    const BlockPlan& plan = s.blocks;
    const int n = static_cast<int>(p.size());
    const double half_dt = 0.5 * s.dt;
    const Vec3 g = s.gravity;
#pragma omp parallel for schedule(static) if (n >= kParallelMinParticles)
    for (int i = 0; i < n; ++i) {
      Vec3 f = s.f_next[i], t = p.t[i];
      for (int a = plan.deferred_start[i]; a < plan.deferred_start[i + 1]; ++a) {
        const int k = plan.deferred_pair[a];
        f += plan.deferred_force[k];
        t += plan.deferred_torque[k];
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
      c.pair = &wc.constants[e];
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
