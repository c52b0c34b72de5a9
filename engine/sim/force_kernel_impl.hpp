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
    if (!s.bonds.empty()) s.bonds.step(s.particles, s.dt, s.time, s.f_next, s.particles.t);
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
        const MeshContacts& mc = s.mesh_contacts;
        for (int k = 0, used = mc.count(i); k < used; ++k) {
          const MeshSlot& slot = mc.slot(i, k);
          note(i, slot.delta, p.radius[i],
               Law::NormalLaw::elastic_energy(s.table(p.material[i], s.meshes[slot.mesh].material), slot.delta,
                                              p.radius[i]));
        }
      }
    }
    return sum;
  }

 private:
  // kRecord: keep each pair's forces for observers (force chains, contact counts) this step.
  template <bool kRecord>
  static void evaluate_pairs(SimState& s) {
    const int n = static_cast<int>(s.particles.size());
    const int size = s.blocks.block_size;
    const int blocks = (n + size - 1) / size;
    const int lanes = pair_lanes();
#pragma omp parallel for schedule(dynamic, 1) if (blocks > 1)
    for (int b = 0; b < blocks; ++b) {
      const int begin = b * size, end = std::min(n, begin + size);
      for (int i = begin; i < end; ++i) {
        s.f_next[i].setZero();
        s.particles.t[i].setZero();
      }
#if DEM_HAS_AVX2_LANES
      if (lanes == 4) {
        pairs_of_block_avx2<kRecord>(s, begin, end);
        continue;
      }
#endif
      pairs_of_block<1, kRecord>(s, begin, end);
    }
  }

#if DEM_HAS_AVX2_LANES
  // The same loop four contacts at a time. Only this function is compiled for AVX2 (the OpenMP
  // region stays outside it), and it runs only where the CPU has AVX2 (pair_lanes()).
  template <bool kRecord>
  [[gnu::target("avx2"), gnu::noinline]] static void pairs_of_block_avx2(SimState& s, int begin, int end) {
    pairs_of_block<4, kRecord>(s, begin, end);
  }
#endif

  // The rows begin..end, each W pairs at a time (a row's last group padded by repeating its last
  // pair, whose extra lanes are then left out). Body i is the same in every lane. Its force and
  // torque are summed in four running sums, the m-th pair of the row going to sum m mod 4, which are
  // added at the end of the row as ((s0 + s1) + (s2 + s3)); j's shares are written lane by lane in
  // pair order after all reads of the group. Every sum is thus made in the same order for W = 1
  // and W = 4, and the results are bit-identical.
  template <int W, bool kRecord>
  DEM_HOT static void pairs_of_block(SimState& s, int begin, int end) {
    using T = Lanes<W>;
    // Raw restrict pointers: the loop writes forces and springs, and without them the compiler must
    // assume every write may change the positions, radii or the vectors themselves and reload them.
    const Particles& p = s.particles;
    NeighborList& nl = s.neighbors;
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
    const int materials = table.material_count();
    const T dt = splat<T>(s.dt);

    auto part = [&](int k) {  // a listed pair that does not touch: its history and its share end
      if (!shear[k].isZero(0)) shear[k].setZero();
      if constexpr (Law::kRollingSpring) roll[k].setZero();
      if (slot[k] >= 0) {
        deferred_force[slot[k]].setZero();
        deferred_torque[slot[k]].setZero();
      }
      if constexpr (kRecord) out_touching[k] = 0;
    };

    LawParams<T> params{};
    int params_of = -1;  // material pair whose coefficients fill every lane of params, -1 if mixed
    for (int i = begin; i < end; ++i) {
      const int row_begin = row_start[i], row_end = row_start[i + 1];
      if (row_begin == row_end) continue;
      const V3<T> xi = broadcast<T>(x[i]), vi = broadcast<T>(v[i]), wi = broadcast<T>(w[i]),
                  kick_i = broadcast<T>(kick[i]);
      const T ri = splat<T>(radius[i]);
      const int mi = material[i];
      constexpr int kSums = 4 / W;  // running sums of each kind: 4 lanes of one, or 4 of W = 1
      V3<T> sum_f[kSums], sum_t[kSums];
      for (int m = 0; m < kSums; ++m) sum_f[m] = sum_t[m] = V3<T>::zero();
      for (int k0 = row_begin; k0 < row_end; k0 += W) {
        const int used = std::min(W, row_end - k0);
        const int m = ((k0 - row_begin) / W) % kSums;
        int kv[W], jv[W];
        for (int l = 0; l < W; ++l) {
          kv[l] = k0 + std::min(l, used - 1);
          jv[l] = partner[kv[l]];
        }
        const V3<T> xj = gather<T>(x, jv);
        const T rj = gather<T>(radius, jv);
        const V3<T> d = xi - xj;
        const T dist = lane_sqrt(squared_norm(d));
        const T rs = ri + rj;
        const auto touching = dist < rs;
        if (!any_lane(touching)) {
          for (int l = 0; l < used; ++l) part(kv[l]);
          continue;
        }

        int pair_of[W];
        bool same = true;
        for (int l = 0; l < W; ++l) {
          pair_of[l] = mi * materials + material[jv[l]];
          same = same && pair_of[l] == params_of;
        }
        if (!same) {
          bool uniform = true;
          for (int l = 0; l < W; ++l) {
            params.set(l, table(mi, material[jv[l]]));
            uniform = uniform && pair_of[l] == pair_of[0];
          }
          params_of = uniform ? pair_of[0] : -1;
        }

        const V3<T> wj = gather<T>(w, jv);
        ContactInput<T> c;
        c.n = d * (1.0 / dist);
        c.delta = rs - dist;
        c.v_rel = vi - gather<T>(v, jv) - cross(ri * wi + rj * wj, c.n);
        const T vn = dot(c.v_rel, c.n);
        // full-step prediction: v(n+1) ~ v(n+1/2) + (the first half kick again)
        c.vn_now = vn + dot(kick_i - gather<T>(kick, jv), c.n);
        c.onset = boundary_share(c.delta, vn, dt);
        c.w_rel = wi - wj;
        c.sqrt_m_eff = gather<T>(sqrt_m_eff, kv);
        c.r_eff = Law::kNeedsEffectiveRadius ? gather<T>(r_eff, kv) : T{};
        c.i_roll = Law::kRolling ? gather<T>(i_roll, kv) : T{};
        c.dt = dt;
        V3<T> spring = gather<T>(shear, kv);
        V3<T> roll_spring = Law::kRollingSpring ? gather<T>(roll, kv) : V3<T>::zero();
        const ContactOutput<T> r = Law::evaluate(params, c, spring, roll_spring);
        const V3<T> lever = cross(c.n, r.shear_force);
        V3<T> torque_i = -(ri * lever), torque_j = -(rj * lever);
        if constexpr (Law::kRolling) {
          torque_i = torque_i + r.roll_moment;
          torque_j = torque_j - r.roll_moment;
        }
        T ft2{};
        if constexpr (kRecord) ft2 = squared_norm(r.shear_force);
        const auto counted = touching & lanes_below<T>(used);
        sum_f[m] = sum_f[m] + select(counted, r.force, V3<T>::zero());
        sum_t[m] = sum_t[m] + select(counted, torque_i, V3<T>::zero());

        for (int l = 0; l < used; ++l) {
          const int k = kv[l], j = jv[l];
          if (!lane_on(touching, l)) {
            part(k);
            continue;
          }
          const Vec3 force = r.force.get(l);
          if (slot[k] < 0) {
            f_next[j] -= force;
            torque[j] += torque_j.get(l);
          } else {
            deferred_force[slot[k]] = -force;
            deferred_torque[slot[k]] = torque_j.get(l);
          }
          shear[k] = spring.get(l);
          if constexpr (Law::kRollingSpring) roll[k] = roll_spring.get(l);
          if constexpr (kRecord) {
            out_fn[k] = lane(r.fn, l);
            out_ft2[k] = lane(ft2, l);
            out_touching[k] = 1;
          }
        }
      }
      f_next[i] += four_sums(sum_f);
      torque[i] += four_sums(sum_t);
    }
  }

  // ((s0 + s1) + (s2 + s3)) of the four running sums, held as 4 lanes of one or 4 scalars.
  template <class T, int kSums>
  DEM_HOT static Vec3 four_sums(const V3<T> (&sums)[kSums]) {
    Vec3 s[4];
    for (int l = 0; l < 4; ++l) {
      if constexpr (kSums == 1) s[l] = sums[0].get(l);
      else s[l] = sums[l].get(0);
    }
    return (s[0] + s[1]) + (s[2] + s[3]);
  }

  static void gather_and_kick(SimState& s) {
    Particles& p = s.particles;
    const BlockPlan& plan = s.blocks;
    const int n = static_cast<int>(p.size());
    const double half_dt = 0.5 * s.dt;
    const Vec3 g = s.gravity;
    const double alpha = s.local_damping;
    // Raw pointers: through the std::vectors the compiler reloaded their data pointers after every
    // store and called Eigen's assignment loops out of line.
    const Vec3* __restrict f_next = s.f_next.data();
    const Vec3* __restrict deferred_force = plan.deferred_force.data();
    const Vec3* __restrict deferred_torque = plan.deferred_torque.data();
    const int* __restrict deferred_start = plan.deferred_start.data();
    const double* __restrict mass = p.mass.data();
    const double* __restrict inv_mass = p.inv_mass.data();
    const double* __restrict inv_inertia = p.inv_inertia.data();
    Vec3* __restrict force = p.f.data();
    Vec3* __restrict torque = p.t.data();
    Vec3* __restrict v = p.v.data();
    Vec3* __restrict w = p.w.data();
#pragma omp parallel for schedule(static) if (n >= kParallelMinParticles)
    for (int i = 0; i < n; ++i) {
      Vec3 f = f_next[i], t = torque[i];
      for (int a = deferred_start[i]; a < deferred_start[i + 1]; ++a) {
        f = f + deferred_force[a];
        t = t + deferred_torque[a];
      }
      if constexpr (kWalls) {
        if (s.wall_contacts.row_start[i] != s.wall_contacts.row_start[i + 1]) add_wall_forces(s, i, f, t);
        if (!s.meshes.empty()) add_mesh_forces(s, i, f, t);
      }
      f = f + mass[i] * g;
      if (!p.external.empty()) f = f + p.external[i];
      if (alpha > 0) {  // local damping: each component loses alpha |F| against its velocity
        for (int d = 0; d < 3; ++d) {
          if (v[i][d] != 0) f[d] -= alpha * std::abs(f[d]) * (v[i][d] > 0 ? 1 : -1);
          if (w[i][d] != 0) t[d] -= alpha * std::abs(t[d]) * (w[i][d] > 0 ? 1 : -1);
        }
      }
      force[i] = f;
      torque[i] = t;
      v[i] = v[i] + (half_dt * inv_mass[i]) * f;
      w[i] = w[i] + (half_dt * inv_inertia[i]) * t;
    }
  }

  // One sphere against a boundary (plane, plate or mesh) that moves with `pose`: the law with the
  // wall's velocity at the contact point; returns the force on the sphere and adds it and its
  // torque to f and t. shear and roll are the contact's springs, updated in place.
  DEM_HOT static ContactOutput<double> wall_contact(const SimState& s, int i, const Vec3& normal, double delta,
                                                    const Vec3& point, const WallPose& pose, int wall_material,
                                                    const PairConstants& pc, Vec3& shear, Vec3& roll, Vec3& f,
                                                    Vec3& t) {
    const Particles& p = s.particles;
    const double ri = p.radius[i];
    ContactInput<double> c;
    c.n = to_v3(normal);
    c.delta = delta;
    c.v_rel = to_v3(p.v[i]) - ri * cross(to_v3(p.w[i]), c.n);
    if (pose.moving()) c.v_rel = c.v_rel - to_v3(pose.velocity_at(point));
    const double vn = dot(c.v_rel, c.n);
    c.vn_now = vn + dot(to_v3(s.half_kick[i]), c.n);
    c.onset = boundary_share(c.delta, vn, s.dt);
    c.w_rel = to_v3(p.w[i] - pose.angular_velocity);
    c.sqrt_m_eff = pc.sqrt_m_eff;
    c.r_eff = pc.r_eff;
    c.i_roll = pc.i_roll;
    c.dt = s.dt;
    V3<double> spring = to_v3(shear), roll_spring = V3<double>::zero();
    if constexpr (Law::kRollingSpring) roll_spring = to_v3(roll);
    const auto params = LawParams<double>::all(s.table(p.material[i], wall_material));
    const ContactOutput<double> r = Law::evaluate(params, c, spring, roll_spring);
    shear = spring.get(0);
    if constexpr (Law::kRollingSpring) roll = roll_spring.get(0);
    f += r.force.get(0);
    t -= ri * cross(c.n, r.shear_force).get(0);
    if constexpr (Law::kRolling) t += r.roll_moment.get(0);
    return r;
  }

  static void add_wall_forces(SimState& s, int i, Vec3& f, Vec3& t) {
    const Particles& p = s.particles;
    WallContacts& wc = s.wall_contacts;
    const double ri = p.radius[i];
    for (int e = wc.row_start[i]; e < wc.row_start[i + 1]; ++e) {
      const Wall& wall = s.walls[wc.wall[e]];
      Vec3 normal;
      double delta;
      if (p.inv_mass[i] == 0 || !wall.contact(p.x[i], ri, normal, delta)) {
        wc.touching[e] = 0;
        wc.fn[e] = wc.ft[e] = 0;
        wc.force[e].setZero();
        wc.shear[e].setZero();
        if constexpr (Law::kRollingSpring) wc.roll[e].setZero();
        continue;
      }
      Vec3 unused_roll = Vec3::Zero();
      Vec3& roll = Law::kRollingSpring ? wc.roll[e] : unused_roll;
      const Vec3 point = p.x[i] - (ri - delta) * normal;
      const ContactOutput<double> r =
          wall_contact(s, i, normal, delta, point, wall.pose, wall.material, wc.constants[e], wc.shear[e], roll, f, t);
      wc.fn[e] = r.fn;
      if (s.record_contacts) wc.ft[e] = std::sqrt(squared_norm(r.shear_force));
      wc.force[e] = r.force.get(0);
      wc.point[e] = point;
      wc.touching[e] = 1;
    }
  }

  // Mesh contacts: the touches of mesh_touches, each taking the history of the last step's slot
  // with the same mesh and the closest normal (at most 60 degrees away): the spring carries over
  // as the sphere crosses from triangle to triangle.
  static void add_mesh_forces(SimState& s, int i, Vec3& f, Vec3& t) {
    const Particles& p = s.particles;
    MeshContacts& mc = s.mesh_contacts;
    constexpr int kSlots = MeshContacts::kSlots;
    // Slots in use come first; the first unused one (if any) has mesh = -1.
    MeshSlot* now = &mc.slots[static_cast<std::size_t>(i) * kSlots];
    if (mc.row_start[i] == mc.row_start[i + 1] || p.inv_mass[i] == 0) {  // nothing within reach (most particles)
      if (mc.used[i]) {  // the slots are touched only when they hold something: they are large
        now[0].mesh = -1;
        mc.used[i] = 0;
      }
      return;
    }
    struct History {
      int mesh;
      Vec3 normal, shear, roll;
    } before[kSlots];
    bool taken[kSlots] = {};
    int had = 0;
    for (; mc.used[i] && had < kSlots && now[had].mesh >= 0; ++had) before[had] = {now[had].mesh, now[had].normal, now[had].shear, now[had].roll};
    const double ri = p.radius[i];
    const PairConstants& pc = mc.constants[i];
    int filled = 0;
    const int end = mc.row_start[i + 1];
    for (int a = mc.row_start[i]; a < end;) {
      const int m = mc.mesh[a];
      int b = a;
      while (b < end && mc.mesh[b] == m) ++b;
      constexpr int kTouches = 8;
      MeshTouch touches[kTouches];
      const int count = mesh_touches(s.meshes[m], &mc.triangle[a], b - a, p.x[i], ri, touches, kTouches);
      for (int k = 0; k < count; ++k) {
        const MeshTouch& touch = touches[k];
        int best = -1;
        double best_dot = 0.5;
        for (int o = 0; o < had; ++o) {
          if (taken[o] || before[o].mesh != m) continue;
          const double alignment = before[o].normal.dot(touch.normal);
          if (alignment > best_dot) {
            best_dot = alignment;
            best = o;
          }
        }
        MeshSlot slot;
        slot.mesh = m;
        if (best >= 0) {
          taken[best] = true;
          slot.shear = before[best].shear;
          slot.roll = before[best].roll;
        }
        const ContactOutput<double> r = wall_contact(s, i, touch.normal, touch.delta, touch.point, s.meshes[m].pose,
                                                     s.meshes[m].material, pc, slot.shear, slot.roll, f, t);
        slot.normal = touch.normal;
        slot.force = r.force.get(0);
        slot.point = touch.point;
        slot.fn = r.fn;
        if (s.record_contacts) slot.ft = std::sqrt(squared_norm(r.shear_force));
        slot.delta = touch.delta;
        if (filled < kSlots) now[filled++] = slot;
      }
      a = b;
    }
    if (filled < kSlots && (filled > 0 || mc.used[i])) now[filled].mesh = -1;
    mc.used[i] = filled > 0;
  }
};

}  // namespace dem
