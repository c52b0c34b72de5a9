// The force loop for one contact law, over the fixed particle blocks of BlockPlan (sim/state.hpp):
// phase 1 evaluates every pair once, adding it to both bodies when they share a block and leaving
// j's share for later when they do not; phase 2 adds those shares, the walls and gravity to each
// particle and takes its second half kick. Each block and each particle is written by one thread,
// and the order of every sum is fixed by the blocks alone: bit-identical for any number of threads.
#pragma once

#include <algorithm>

#include "contact/contact_law.hpp"
#include "sim/force_kernel.hpp"

namespace dem {

template <class Law, bool kWalls>
class ForceKernelImpl final : public ForceKernel {
 public:
  void compute_and_kick(SimState& s) override {
    if (s.record_contacts) evaluate_pairs<true>(s);
    else evaluate_pairs<false>(s);
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
                                            s.neighbors.r_eff[k]));
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
  // kRecord: keep each pair's forces for observers (force chains, contact counts) this step.
  template <bool kRecord>
  static void evaluate_pairs(SimState& s) {
    // Raw restrict pointers: the loop writes forces and springs, and without them the compiler must
    // assume every write may change the positions, radii or the vectors themselves and reload them.
    const Particles& p = s.particles;
    NeighborList& nl = s.neighbors;
    const int n = static_cast<int>(p.size());
    const int size = s.blocks.block_size;
    const int blocks = (n + size - 1) / size;
    const double dt = s.dt;
    const Vec3* __restrict x = p.x.data();
    const Vec3* __restrict v = p.v.data();
    const Vec3* __restrict w = p.w.data();
    const Vec3* __restrict kick = s.half_kick.data();
    const double* __restrict radius = p.radius.data();
    const int* __restrict material = p.material.data();
    const int* __restrict row_start = nl.row_start.data();
    const int* __restrict partner = nl.partner.data();
    const double* __restrict sqrt_m_eff = nl.sqrt_m_eff.data();
    const double* __restrict r_eff = nl.r_eff.data();
    const double* __restrict i_roll = nl.i_roll.data();
    Vec3* __restrict shear = nl.shear.data();
    Vec3* __restrict roll = nl.roll.data();
    Vec3* __restrict f_next = s.f_next.data();
    Vec3* __restrict torque = s.particles.t.data();
    const int* __restrict slot = s.blocks.slot.data();
    Vec3* __restrict deferred_force = s.blocks.deferred_force.data();
    Vec3* __restrict deferred_torque = s.blocks.deferred_torque.data();
    double* __restrict out_fn = s.pairs.fn.data();
    double* __restrict out_ft2 = s.pairs.ft_squared.data();
    std::uint8_t* __restrict out_touching = s.pairs.touching.data();
    const PairTable& table = s.table;
#pragma omp parallel for schedule(dynamic, 1) if (blocks > 1)
    for (int b = 0; b < blocks; ++b) {
      const int begin = b * size, end = std::min(n, begin + size);
      for (int i = begin; i < end; ++i) {
        f_next[i].setZero();
        torque[i].setZero();
      }
      std::vector<double> row_dist, row_inv;  // per row: distance and its inverse, before the force pass
      for (int i = begin; i < end; ++i) {
        const Vec3 xi = x[i], vi = v[i], wi = w[i], kick_i = kick[i];
        const double ri = radius[i];
        const int mi = material[i];
        Vec3 fi = f_next[i], ti = torque[i];
        const int row_begin = row_start[i], row_end = row_start[i + 1];
        // Pass 1: the distances. Short independent iterations let the square roots of a whole row
        // overlap instead of each contact waiting for its own.
        const int row_length = row_end - row_begin;
        row_dist.resize(row_length);
        row_inv.resize(row_length);
        for (int m = 0; m < row_length; ++m) row_dist[m] = (xi - x[partner[row_begin + m]]).squaredNorm();
        for (int m = 0; m < row_length; ++m) {
          row_dist[m] = std::sqrt(row_dist[m]);
          row_inv[m] = 1 / row_dist[m];
        }
        for (int k = row_begin; k < row_end; ++k) {
          const int j = partner[k];
          const double rj = radius[j];
          const double rs = ri + rj;
          const double dist = row_dist[k - row_begin];
          if (dist >= rs) {
            if constexpr (kRecord) out_touching[k] = 0;
            if (!shear[k].isZero(0)) shear[k].setZero();
            if constexpr (Law::kRollingSpring) roll[k].setZero();
            if (j >= end) {
              deferred_force[slot[k]].setZero();
              deferred_torque[slot[k]].setZero();
            }
            continue;
          }
          ContactInput c;
          c.n = (xi - x[j]) * row_inv[k - row_begin];
          c.delta = rs - dist;
          c.v_rel = vi - v[j] - (ri * wi + rj * w[j]).cross(c.n);
          const double vn = c.v_rel.dot(c.n);
          // full-step prediction: v(n+1) ~ v(n+1/2) + (the first half kick again)
          c.vn_now = vn + (kick_i - kick[j]).dot(c.n);
          c.onset = boundary_share(c.delta, vn, dt);
          c.w_rel = wi - w[j];
          c.pair.sqrt_m_eff = sqrt_m_eff[k];
          if constexpr (Law::kNeedsEffectiveRadius) c.pair.r_eff = r_eff[k];
          if constexpr (Law::kRolling) c.pair.i_roll = i_roll[k];
          c.dt = dt;
          ContactHistory h{&shear[k], Law::kRollingSpring ? &roll[k] : nullptr};
          const ContactOutput r = Law::evaluate(table(mi, material[j]), c, h);
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
            torque[j] += torque_j;
          } else {
            deferred_force[slot[k]] = -r.force;
            deferred_torque[slot[k]] = torque_j;
          }
          if constexpr (kRecord) {
            out_fn[k] = r.fn;
            out_ft2[k] = r.shear_force.squaredNorm();
            out_touching[k] = 1;
          }
        }
        f_next[i] = fi;
        torque[i] = ti;
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
        f += plan.deferred_force[a];
        t += plan.deferred_torque[a];
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
      c.vn_now = vn + s.half_kick[i].dot(c.n);
      c.onset = boundary_share(c.delta, vn, s.dt);
      c.w_rel = p.w[i];
      c.pair = wc.constants[e];
      c.dt = s.dt;
      ContactHistory h{&wc.shear[e], Law::kRollingSpring ? &wc.roll[e] : nullptr};
      const ContactOutput r = Law::evaluate(s.table(p.material[i], wall.material), c, h);
      f += r.force;
      t -= ri * c.n.cross(r.shear_force);
      if constexpr (Law::kRolling) t += r.roll_moment;
      wc.touching[e] = 1;
      wc.fn[e] = r.fn;
      if (s.record_contacts) wc.ft[e] = r.shear_force.norm();
    }
  }
};

}  // namespace dem
