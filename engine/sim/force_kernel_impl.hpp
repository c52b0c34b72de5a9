// The force loop for one contact law, over the fixed particle blocks of BlockPlan (sim/state.hpp):
// phase 1 evaluates every pair once, adding it to both bodies when they share a block and leaving
// j's share for later when they do not; phase 2 adds those shares, the walls and gravity to each
// particle and takes its second half kick. Each block and each particle is written by one thread,
// and the order of every sum is fixed by the blocks alone: bit-identical for any number of threads.
#pragma once

#include <algorithm>
#include <chrono>

#include "contact/contact_law.hpp"
#include "core/local_damping.hpp"
#include "core/parallel.hpp"
#include "contact/pair_table.hpp"
#include "sim/force_kernel.hpp"

namespace dem {

// `walls`: the scene has walls or meshes (at some stage). A run-time flag, not a template parameter: a
// predictable branch a particle, where a second instantiation of every law doubled the kernels' compile time.
template <class Law>
class ForceKernelImpl final : public ForceKernel {
 public:
  using Pair = typename Law::Pair;
  using Normal = typename Law::NormalModel;

  ForceKernelImpl(const Scene& scene, bool walls) : table_(scene, &Law::mix), walls_(walls) {}

  void compute_and_kick(SimState& s) override {
    s.deep_overlap.store(false, std::memory_order_relaxed);
    {
      const PhaseTimer timer(s.profile, Phase::pairs);
      if (s.record_contacts)
        evaluate_pairs<true>(s, table_);
      else
        evaluate_pairs<false>(s, table_);
    }
    const bool bonded = !s.bonds.empty();
    if (bonded) {  // bonds add to f_next and particles.t; the kick adds those to the pairs' sums
      const PhaseTimer timer(s.profile, Phase::bonds);
      std::fill(s.f_next.begin(), s.f_next.end(), Vec3::Zero());
      std::fill(s.particles.t.begin(), s.particles.t.end(), Vec3::Zero());
      s.bonds.step(s.particles, s.time, s.f_next, s.particles.t);
    }
    if (s.profile == nullptr) {
      gather_and_kick<false>(s, table_, bonded, walls_);
      return;
    }
    // The walls and meshes are timed inside the gather, per particle that has any, by each thread, in
    // one gather of PhaseProfile::kGatherSample (their clock reads cost more than a wall contact); the
    // others' time is shared among walls, meshes and kick as the sampled ones' (PhaseProfile::close).
    const auto start = PhaseProfile::Clock::now();
    if (s.profile->sample_gather()) {
      const GatherTimes times = gather_and_kick<true>(s, table_, bonded, walls_);
      s.profile->add_gather(std::chrono::duration<double>(PhaseProfile::Clock::now() - start).count(), times);
    } else {
      gather_and_kick<false>(s, table_, bonded, walls_);
      s.profile->add_unsampled_gather(std::chrono::duration<double>(PhaseProfile::Clock::now() - start).count());
    }
  }

  bool has_rolling_spring() const override { return Law::kRollingSpring; }

  double contact_time(int a, int b, double m_eff, double r_eff, double speed) const override {
    return Normal::contact_time(table_(a, b).normal, m_eff, r_eff, speed);
  }
  bool contact_time_needs_speed() const override { return Normal::kContactTimeNeedsSpeed; }
  double wave_time(const Material& m, double r_min) const override { return Normal::wave_time(m, r_min); }

  ContactSummary summarize(const SimState& s) const override { return survey(s, s.particles.radius); }

  double elastic_energy(const SimState& s, const std::vector<double>& radius) const override {
    return survey(s, radius).elastic_energy;
  }

 private:
  // The contacts the particles at their positions make with these radii, and the energy they hold.
  ContactSummary survey(const SimState& s, const std::vector<double>& radius) const {
    const Particles& p = s.particles;
    static const Vec3 kNone = Vec3::Zero();  // the rolling spring of a law without one
    ContactSummary sum;
    auto note = [&](int i, int j, double delta, double r_min, double elastic, double sqrt_m_eff) {
      ++sum.contacts;
      sum.elastic_energy += elastic;
      if (sqrt_m_eff > 0) sum.release_speed = std::max(sum.release_speed, std::sqrt(2 * elastic) / sqrt_m_eff);
      if (delta / r_min > sum.max_overlap_fraction) {
        sum.max_overlap_fraction = delta / r_min;
        sum.worst_particle = i;
        sum.worst_partner = j;
      }
    };
    const int n = static_cast<int>(p.size());
    for (int i = 0; i < n; ++i) {
      const double ri = radius[i];
      for (int k = s.neighbors.row_start[i]; k < s.neighbors.row_start[i + 1]; ++k) {
        const int j = s.neighbors.partner[k];
        const double rj = radius[j], rs = ri + rj;
        const double dist = (p.x[i] - p.x[j]).norm();
        if (dist >= rs) continue;
        note(i, j, rs - dist, std::min(ri, rj),
             Law::stored_energy(table_(p.material[i], p.material[j]), rs - dist, ri * rj / rs, s.neighbors.shear[k],
                                Law::kRollingSpring ? s.neighbors.roll[k] : kNone),
             s.neighbors.sqrt_m_eff[k]);
      }
      if (walls_) {
        for (int e = s.wall_contacts.row_start[i]; e < s.wall_contacts.row_start[i + 1]; ++e) {
          const Wall& wall = s.walls[s.wall_contacts.wall[e]];
          Vec3 normal;
          double delta;
          if (!wall.contact(p.x[i], ri, normal, delta)) continue;
          note(i, -1, delta, ri,
               Law::stored_energy(table_(p.material[i], wall.material), delta, ri, s.wall_contacts.shear[e],
                                  Law::kRollingSpring ? s.wall_contacts.roll[e] : kNone),
               s.wall_contacts.constants[e].sqrt_m_eff);
        }
        const MeshContacts& mc = s.mesh_contacts;
        for (int k = 0, used = mc.count(i); k < used; ++k) {
          const MeshSlot& slot = mc.slot(i, k);
          const double delta = slot.delta + (ri - p.radius[i]);
          if (delta <= 0) continue;
          note(i, -1, delta, ri,
               slot.weight * Law::stored_energy(table_(p.material[i], s.meshes[slot.mesh].material), delta, ri,
                                                slot.shear, slot.roll),
               mc.constants[i].sqrt_m_eff);
        }
      }
    }
    return sum;
  }

  // A listed pair parted since the last sample: the spring's impulse that sample could not see
  // (spring_boundary_correction), along the line of the centres so that both momenta stay. Rare:
  // kept out of the force loop.
  [[gnu::noinline]] static void add_parting_push(SimState& s, const PairTable<Pair>& table, int k, int i, int j,
                                                 int to) {
    const Particles& p = s.particles;
    const Vec3 d = p.x[i] - p.x[j];
    const double rs = p.radius[i] + p.radius[j], dist = d.norm();
    const Vec3 vc = p.v[i] - p.v[j];
    const double before = rs - (d - s.dt * vc).norm();  // the overlap at the last sample
    const double lost = before - (rs - dist);
    if (!(before > 0 && lost > 0 && dist > 0)) return;
    const Vec3 n = d / dist;
    const NeighborList& nl = s.neighbors;
    const double f = Law::parting_correction(table(p.material[i], p.material[j]), before, lost, nl.r_eff[k], vc.dot(n),
                                             nl.sqrt_m_eff[k]);
    if (f == 0) return;
    const Lanes4 push{f * n.x(), f * n.y(), f * n.z(), 0.0};
    BodySums* sums = s.blocks.sums.data();
    sums[i].f = sums[i].f + push;
    sums[to].f = sums[to].f - push;
  }

  // kRecord: keep each pair's forces for observers (force chains, contact counts) this step.
  template <bool kRecord>
  static void evaluate_pairs(SimState& s, const PairTable<Pair>& table) {
    const int n = static_cast<int>(s.particles.size());
    const int size = s.blocks.block_size;
    const int blocks = (n + size - 1) / size;
    const int lanes = pair_lanes();
    auto block = [&](int b) {
      const int begin = b * size, end = std::min(n, begin + size);
#if DEM_HAS_AVX2_LANES
      if (lanes == 4) {
        pairs_of_block_avx2<kRecord>(s, table, begin, end);
        return;
      }
#endif
      pairs_of_block<1, kRecord>(s, table, begin, end);
    };
    if (blocks <= 1) {  // no OpenMP region: even a team of one costs a malloc and futex calls (core/parallel.hpp)
      if (blocks == 1) block(0);  // none: a scene with no particle yet (a source's, before its first)
      return;
    }
    // each thread its static share of whole blocks, as every particle loop (core/parallel.hpp, kParticleBlock)
#pragma omp parallel
    {
      const auto [first, last] = static_range(blocks, omp_get_num_threads(), omp_get_thread_num());
      for (int b = first; b < last; ++b) block(b);
    }
  }

#if DEM_HAS_AVX2_LANES
  // The same loop four contacts at a time. Only this function is compiled for AVX2 (the OpenMP
  // region stays outside it), and it runs only where the CPU has AVX2 (pair_lanes()).
  template <bool kRecord>
  [[gnu::target("avx2"), gnu::noinline]] static void pairs_of_block_avx2(SimState& s, const PairTable<Pair>& table,
                                                                         int begin, int end) {
    pairs_of_block<4, kRecord>(s, table, begin, end);
  }
#endif

  // The pairs of rows begin..end taken as one stream, W consecutive pairs at a time whatever rows
  // they belong to: a row of the half list holds ~6 pairs, and filling the lanes row by row left a
  // quarter of them idle. Each lane has its own i and j; the block's last group repeats its last pair
  // in the spare lanes, whose results are dropped. The shares are then added lane by lane in pair
  // order to the padded sums of the block plan (i's, then j's or j's deferred slot), so every sum is
  // made in pair order for W = 1 and W = 4 alike: the results are bit-identical.
  template <int W, bool kRecord>
  DEM_HOT static void pairs_of_block(SimState& s, const PairTable<Pair>& table, int begin, int end) {
    using T = Lanes<W>;
    // Raw restrict pointers: the loop writes sums and springs, and without them the compiler must
    // assume every write may change the positions, radii or the vectors themselves and reload them.
    const Particles& p = s.particles;
    NeighborList& nl = s.neighbors;
    const Vec3* __restrict x = p.x.data();
    const Vec3* __restrict v = p.v.data();
    const Vec3* __restrict w = p.w.data();
    const Vec3* __restrict kick = s.half_kick.data();
    const Vec3* __restrict spin_kick = s.spin_kick.data();
    const double* __restrict radius = p.radius.data();
    const int* __restrict material = p.material.data();
    const int* __restrict partner = nl.partner.data();
    const int* __restrict owner = s.blocks.owner.data();
    const int* __restrict target = s.blocks.target.data();
    const double* __restrict sqrt_m_eff = nl.sqrt_m_eff.data();
    const double* __restrict r_eff = nl.r_eff.data();
    const double* __restrict i_roll = nl.i_roll.data();
    Vec3* __restrict shear = nl.shear.data();
    Vec3* __restrict roll = nl.roll.data();
    std::uint8_t* __restrict touched = nl.touched.data();
    BodySums* __restrict sums = s.blocks.sums.data();
    double* __restrict out_fn = s.pairs.fn.data();
    double* __restrict out_ft2 = s.pairs.ft_squared.data();
    std::uint8_t* __restrict out_touching = s.pairs.touching.data();
    const int materials = table.material_count();
    const T dt = splat<T>(s.dt);

    auto part = [&](int k, int i, int j, int to) {  // a listed pair that does not touch: its history ends
      if (!shear[k].isZero(0)) shear[k].setZero();
      if constexpr (Law::kRollingSpring) roll[k].setZero();
      if constexpr (kRecord) out_touching[k] = 0;
      if (!touched[k]) return;
      touched[k] = 0;
      add_parting_push(s, table, k, i, j, to);
    };

    typename Law::template Lanes<T> params{};
    int params_of = -1;  // material pair whose coefficients fill every lane of params, -1 if mixed
    // The stream goes in chunks of kGroups groups, each in two passes. The first finds every group's
    // distance, overlap and normal: its square roots and divisions are independent from group to
    // group and overlap in the pipeline, where inside one pass they held up everything after them.
    // It also asks for the cache lines of j that the second pass reads and writes: j is often the
    // sphere of the next layer, not yet in L1, and the second pass needs it at its very end.
    constexpr int kGroups = 16;
    using Mask = decltype(T{} < T{});
    struct Geometry {
      int k[W], i[W], j[W], to[W];  // pair, i, j, where j's share goes
      int used;
      Mask touching;
      V3<T> n;
      T delta, ri, rj;
    } geometry[kGroups];
    const T overlap_limit = splat<T>(s.overlap_limit);
    bool deep = false;  // a contact past the guard's overlap limit
    const int k_end = nl.row_start[end];
    for (int chunk = nl.row_start[begin]; chunk < k_end; chunk += kGroups * W) {
      const int groups = std::min(kGroups, (k_end - chunk + W - 1) / W);
      for (int g = 0; g < groups; ++g) {
        Geometry& geo = geometry[g];
        const int k0 = chunk + g * W;
        geo.used = std::min(W, k_end - k0);
        for (int l = 0; l < W; ++l) {
          geo.k[l] = k0 + std::min(l, geo.used - 1);
          geo.i[l] = owner[geo.k[l]];
          geo.j[l] = partner[geo.k[l]];
          geo.to[l] = target[geo.k[l]];
          __builtin_prefetch(&sums[geo.to[l]], 1);
          __builtin_prefetch(&v[geo.j[l]]);
          __builtin_prefetch(&w[geo.j[l]]);
          __builtin_prefetch(&kick[geo.j[l]]);
        }
        const V3<T> d = gather<T>(x, geo.i) - gather<T>(x, geo.j);
        geo.ri = gather<T>(radius, geo.i);
        geo.rj = gather<T>(radius, geo.j);
        const T dist = lane_sqrt(squared_norm(d));
        const T rs = geo.ri + geo.rj;
        geo.touching = dist < rs;
        if (!any_lane(geo.touching)) continue;
        geo.n = d * (1.0 / dist);
        geo.delta = rs - dist;
        deep = deep || any_lane(lane_and(geo.touching, geo.delta > overlap_limit * lane_min(geo.ri, geo.rj)));
      }
      for (int g = 0; g < groups; ++g) {
        const Geometry& geo = geometry[g];
        const int *kv = geo.k, *iv = geo.i, *jv = geo.j;
        if (!any_lane(geo.touching)) {
          for (int l = 0; l < geo.used; ++l) part(kv[l], iv[l], jv[l], geo.to[l]);
          continue;
        }
        int pair_of[W];
        bool same = true;
        for (int l = 0; l < W; ++l) {
          pair_of[l] = material[iv[l]] * materials + material[jv[l]];
          same = same && pair_of[l] == params_of;
        }
        if (!same) {
          bool uniform = true;
          for (int l = 0; l < W; ++l) {
            params.set(l, table(material[iv[l]], material[jv[l]]));
            uniform = uniform && pair_of[l] == pair_of[0];
          }
          params_of = uniform ? pair_of[0] : -1;
        }

        const V3<T> wi = gather<T>(w, iv), wj = gather<T>(w, jv);
        ContactInput<T> c;
        c.n = geo.n;
        c.delta = geo.delta;
        // The contact point: the middle of the overlap, at r - delta/2 from each centre (YADE's), so
        // that the two levers add up to the distance of the centres and the tangential force keeps
        // the total angular momentum (through the full radii it leaked delta / R of it).
        const T li = geo.ri - 0.5 * geo.delta, lj = geo.rj - 0.5 * geo.delta;
        const V3<T> v_centres = gather<T>(v, iv) - gather<T>(v, jv);
        c.v_rel = v_centres - cross(li * wi + lj * wj, c.n);
        const T vn = dot(c.v_rel, c.n);
        // full-step prediction: v(n+1) ~ v(n+1/2) + (the first half kick again)
        const V3<T> kicks = gather<T>(kick, iv) - gather<T>(kick, jv);
        c.vn_now = vn + dot(kicks, c.n);
        if constexpr (Law::kFriction) {
          // (the spins' kicks move the contact point in the plane only: vn_now is v_now's normal part)
          const V3<T> spins = li * gather<T>(spin_kick, iv) + lj * gather<T>(spin_kick, jv);
          c.vt_now = c.v_rel + kicks - cross(spins, c.n) - c.vn_now * c.n;
        }
        c.onset = boundary_share(c.delta, vn, dt);
        c.travel = lane_abs(vn) * dt;
        c.first_touch = T{};
        // Only an overlap smaller than the drift's relative travel can be new since the last sample
        // (the overlap changes by at most |v_i - v_j| dt a step): there, and only there, the flag of
        // the last sample is read and set. An older contact keeps its flag, which it set on the way in
        // (or, touching from the start, sets on its way out before it parts).
        const T reach2 = squared_norm(v_centres) * (1.0001 * s.dt * s.dt);
        const auto near_boundary = lane_and(geo.touching, geo.delta * geo.delta < reach2);
        bool near_any = false;
        if (any_lane(near_boundary)) {
          near_any = true;
          T was{};
          for (int l = 0; l < W; ++l) set_lane(was, l, touched[kv[l]] ? 1.0 : 0.0);
          const auto unseen = lane_and(near_boundary, was == T{});
          if (any_lane(unseen)) {
            // New where apart at the start of the drift (a contact of the first step, overlapping
            // from the start, is not): the overlap it gained over the drift.
            const T dist = geo.ri + geo.rj - geo.delta;
            const T dist_before = lane_sqrt(squared_norm(dist * geo.n - dt * v_centres));
            const auto fresh = lane_and(unseen, dist_before >= geo.ri + geo.rj);
            c.first_touch = select(fresh, dist_before - dist, T{});
          }
        }
        c.w_rel = wi - wj;
        c.sqrt_m_eff = gather<T>(sqrt_m_eff, kv);
        c.r_eff = Law::kNeedsEffectiveRadius ? gather<T>(r_eff, kv) : T{};
        c.i_roll = Law::kRolling ? gather<T>(i_roll, kv) : T{};
        c.dt = dt;
        V3<T> spring = gather<T>(shear, kv);
        V3<T> roll_spring = Law::kRollingSpring ? gather<T>(roll, kv) : V3<T>::zero();
        const ContactOutput<T> r = Law::evaluate(params, c, spring, roll_spring);
        const V3<T> lever = cross(c.n, r.shear_force);
        V3<T> torque_i = -(li * lever), torque_j = -(lj * lever);
        if constexpr (Law::kRolling) {
          torque_i = torque_i + r.roll_moment;
          torque_j = torque_j - r.roll_moment;
        }
        T ft2{};
        if constexpr (kRecord) ft2 = squared_norm(r.shear_force);
        Lanes4 force_of[W], torque_i_of[W], torque_j_of[W];
        lane_quads(r.force, force_of);
        lane_quads(torque_i, torque_i_of);
        lane_quads(torque_j, torque_j_of);

        for (int l = 0; l < geo.used; ++l) {
          const int k = kv[l];
          if (!lane_on(geo.touching, l)) {
            part(k, iv[l], jv[l], geo.to[l]);
            continue;
          }
          if (near_any && lane_on(near_boundary, l)) touched[k] = 1;
          BodySums& on_i = sums[iv[l]];
          BodySums& on_j = sums[geo.to[l]];
          on_i.f = on_i.f + force_of[l];
          on_i.t = on_i.t + torque_i_of[l];
          on_j.f = on_j.f - force_of[l];
          on_j.t = on_j.t + torque_j_of[l];
          shear[k] = spring.get(l);
          if constexpr (Law::kRollingSpring) roll[k] = roll_spring.get(l);
          if constexpr (kRecord) {
            out_fn[k] = lane(r.fn, l);
            out_ft2[k] = lane(ft2, l);
            out_touching[k] = 1;
          }
        }
      }
    }
    if (deep) s.deep_overlap.store(true, std::memory_order_relaxed);
  }

  // bonded: bond forces and torques wait in f_next and particles.t. kTimed: time the walls and meshes
  // (PhaseProfile), whose clock is read only around the particles that touch or near one.
  template <bool kTimed>
  static GatherTimes gather_and_kick(SimState& s, const PairTable<Pair>& table, bool bonded, bool walls) {
    using Clock = PhaseProfile::Clock;
    auto seconds_since = [](Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); };
    struct RangeOut {
      bool bad = false;  // some particle's end-of-step state may not be finite (Simulation::step checks which)
      GatherTimes times;
    };
    Particles& p = s.particles;
    const BlockPlan& plan = s.blocks;
    const int n = static_cast<int>(p.size());
    const double half_dt = 0.5 * s.dt;
    const Vec3 g = s.gravity;
    const double alpha = s.local_damping;
    auto kick_range = [&](int begin, int end) {
      // The scene's constants as locals: captured by reference, they were reloaded from memory at
      // every particle.
      const bool add_bonds = bonded, any_walls = walls;
      const double h = half_dt, damping = alpha;
      const Vec3 weight_per_mass = g;
      RangeOut out;
      Clock::time_point range_start;
      if constexpr (kTimed) range_start = Clock::now();
      // Raw pointers: through the std::vectors the compiler reloaded their data pointers after every
      // store and called Eigen's assignment loops out of line.
      const Vec3* __restrict f_next = s.f_next.data();
      BodySums* __restrict sums = s.blocks.sums.data();  // the particles', then the deferred slots
      BodySums* __restrict deferred = sums + n;
      const int* __restrict deferred_start = plan.deferred_start.data();
      const double* __restrict mass = p.mass.data();
      const double* __restrict inv_mass = p.inv_mass.data();
      const double* __restrict inv_inertia = p.inv_inertia.data();
      Vec3* __restrict force = p.f.data();
      Vec3* __restrict torque = p.t.data();
      Vec3* __restrict v = p.v.data();
      Vec3* __restrict w = p.w.data();
      const Vec3* __restrict x = p.x.data();
      const int* __restrict body = p.body.empty() ? nullptr : p.body.data();
      const Vec3* __restrict external = p.external.empty() ? nullptr : p.external.data();
      const int* __restrict wall_rows = s.wall_contacts.row_start.data();
      const MeshContacts& mc = s.mesh_contacts;
      const bool meshes_near = !s.meshes.empty() && !mc.none_near();
      // Every particle's squared position, and speeds and spins weighted by mass, summed component by
      // component: the terms are >= 0, so the sum is finite exactly when each is, but for a sum that
      // overflows where no particle does, which Simulation::step's particle by particle check then
      // clears. Three vertical sums instead of three squared norms and tests a particle.
      Vec3 magnitudes = Vec3::Zero();
      for (int i = begin; i < end; ++i) {
        Vec3 f = as_vec3(sums[i].f), t = as_vec3(sums[i].t);
        sums[i] = BodySums{};  // zero for the next step's pair loop (while the line is in cache)
        if (add_bonds) {
          f = f + f_next[i];
          t = t + torque[i];
        }
        for (int a = deferred_start[i]; a < deferred_start[i + 1]; ++a) {
          f = f + as_vec3(deferred[a].f);
          t = t + as_vec3(deferred[a].t);
          deferred[a] = BodySums{};  // zero for the next step's pair loop
        }
        if (any_walls) {
          if (wall_rows[i] != wall_rows[i + 1]) {
            Clock::time_point t0;
            if constexpr (kTimed) t0 = Clock::now();
            add_wall_forces(s, table, i, f, t);
            if constexpr (kTimed) {
              out.times.walls += seconds_since(t0);
              ++out.times.wall_intervals;
            }
          }
          // a particle with no face within reach and no slot to clear is passed without a call; one
          // with only a slot to clear is not timed
          if (meshes_near && (mc.row_start[i] != mc.row_start[i + 1] || mc.used[i])) {
            const bool timed = kTimed && mc.row_start[i] != mc.row_start[i + 1];
            Clock::time_point t0;
            if (timed) t0 = Clock::now();
            add_mesh_forces(s, table, i, f, t);
            if (timed) {
              out.times.meshes += seconds_since(t0);
              ++out.times.mesh_intervals;
            }
          }
        }
        f = f + mass[i] * weight_per_mass;
        if (external) f = f + external[i];
        // local damping: each component loses alpha |F| against its velocity. A clump member's is
        // its body's, on the body's force and torque (kick_bodies): here it would take alpha of the
        // body's weight once per member (a stone of four spheres at alpha 0.3 floated).
        if (damping > 0 && (body == nullptr || body[i] < 0)) {
          damp_locally(f, v[i], damping);
          damp_locally(t, w[i], damping);
        }
        force[i] = f;
        torque[i] = t;
        const Vec3 vi = v[i] + (h * inv_mass[i]) * f, wi = w[i] + (h * inv_inertia[i]) * t;
        v[i] = vi;
        w[i] = wi;
        // the end-of-step state, checked every step so that a blow-up is caught where it starts
        const Vec3 xi = x[i];
        magnitudes = magnitudes + (xi.cwiseProduct(xi) + mass[i] * (vi.cwiseProduct(vi) + wi.cwiseProduct(wi)));
      }
      out.bad = !std::isfinite(magnitudes.sum());
      if constexpr (kTimed) out.times.range = seconds_since(range_start);
      return out;
    };
    const RangeOut all = reduce_ranges(
        n, kParallelMinParticles, RangeOut{}, kick_range,
        [](RangeOut a, const RangeOut& b) {
          a.bad = a.bad || b.bad;
          a.times.range += b.times.range;
          a.times.walls += b.times.walls;
          a.times.meshes += b.times.meshes;
          a.times.wall_intervals += b.times.wall_intervals;
          a.times.mesh_intervals += b.times.mesh_intervals;
          return a;
        },
        kParticleBlock);
    s.non_finite = all.bad;
    return all.times;
  }

  // One sphere against a boundary (plane, plate or mesh) that moves with `pose`: the law with the
  // wall's velocity at the contact point; returns the force on the sphere and adds it and its
  // torque to f and t. shear and roll are the contact's springs, updated in place. `weight` (a mesh
  // face's share at a valley, mesh/mesh_wall.hpp) scales what the contact applies, not its springs.
  DEM_HOT static ContactOutput<double> wall_contact(SimState& s, const PairTable<Pair>& table, int i,
                                                    const Vec3& normal, double delta, const Vec3& point,
                                                    const WallPose& pose, int wall_material, const PairConstants& pc,
                                                    Vec3& shear, Vec3& roll, Vec3& f, Vec3& t, bool first_sample,
                                                    double weight = 1) {
    const Particles& p = s.particles;
    if (delta > s.overlap_limit * p.radius[i]) s.deep_overlap.store(true, std::memory_order_relaxed);
    const double li = p.radius[i] - 0.5 * delta;  // to the contact point, as for a pair
    ContactInput<double> c;
    c.n = to_v3(normal);
    c.delta = delta;
    c.v_rel = to_v3(p.v[i]) - li * cross(to_v3(p.w[i]), c.n);
    if (pose.moving()) c.v_rel = c.v_rel - to_v3(pose.velocity_at(point));
    const double vn = dot(c.v_rel, c.n);
    c.vn_now = vn + dot(to_v3(s.half_kick[i]), c.n);
    if constexpr (Law::kFriction) {  // the wall's own acceleration is left out, as in vn_now
      const V3<double> v_now = c.v_rel + to_v3(s.half_kick[i]) - li * cross(to_v3(s.spin_kick[i]), c.n);
      c.vt_now = v_now - dot(v_now, c.n) * c.n;
    }
    c.onset = boundary_share(c.delta, vn, s.dt);
    c.travel = std::abs(vn) * s.dt;
    // the overlap gained since the last sample (a sphere moves straight relative to a plane)
    c.first_touch = first_sample && vn < 0 && delta <= c.travel ? c.travel : 0.0;
    c.w_rel = to_v3(p.w[i] - pose.angular_velocity);
    c.sqrt_m_eff = pc.sqrt_m_eff;
    c.r_eff = pc.r_eff;
    c.i_roll = pc.i_roll;
    c.dt = s.dt;
    V3<double> spring = to_v3(shear), roll_spring = V3<double>::zero();
    if constexpr (Law::kRollingSpring) roll_spring = to_v3(roll);
    const auto params = Law::template Lanes<double>::all(table(p.material[i], wall_material));
    ContactOutput<double> r = Law::evaluate(params, c, spring, roll_spring);
    shear = spring.get(0);
    if constexpr (Law::kRollingSpring) roll = roll_spring.get(0);
    if (weight != 1) {
      r.force = weight * r.force;
      r.shear_force = weight * r.shear_force;
      r.fn *= weight;
      r.kn *= weight;
      r.cn *= weight;
      if constexpr (Law::kRolling) r.roll_moment = weight * r.roll_moment;
    }
    f += r.force.get(0);
    t -= li * cross(c.n, r.shear_force).get(0);
    if constexpr (Law::kRolling) t += r.roll_moment.get(0);
    return r;
  }

  // The speed at which particle i's centre leaves a boundary moving with `pose`, along its normal n
  // (wall -> particle): after a parting, to count the step the contact left (parting_correction).
  static double leaving_speed(const SimState& s, int i, const Vec3& n, const WallPose& pose) {
    Vec3 v = s.particles.v[i];
    if (pose.moving()) v -= pose.velocity_at(s.particles.x[i] - s.particles.radius[i] * n);
    return v.dot(n);
  }

  static void add_wall_forces(SimState& s, const PairTable<Pair>& table, int i, Vec3& f, Vec3& t) {
    const Particles& p = s.particles;
    WallContacts& wc = s.wall_contacts;
    const double ri = p.radius[i];
    for (int e = wc.row_start[i]; e < wc.row_start[i + 1]; ++e) {
      const Wall& wall = s.walls[wc.wall[e]];
      Vec3 normal;
      double delta;
      // a held particle and a wall at rest cannot change each other; a moving wall pushing on a held
      // particle must be stopped by it (its reaction goes to the wall, BoundaryLoad)
      const bool held_against_still_wall = p.inv_mass[i] == 0 && !wall.pose.moving();
      if (held_against_still_wall || !wall.contact(p.x[i], ri, normal, delta)) {
        const bool parted = wc.touching[e] && p.inv_mass[i] != 0;
        wc.touching[e] = 0;
        wc.fn[e] = wc.ft[e] = wc.kn[e] = wc.cn[e] = 0;
        wc.force[e].setZero();
        if (parted) {  // since the last sample: the spring's impulse it could not see (spring_boundary_correction)
          const Vec3 n = wall.normal_towards(p.x[i]);
          const double vn = leaving_speed(s, i, n, wall.pose);
          const double before = ri - wall.distance(p.x[i]) + vn * s.dt;
          if (before > 0 && vn > 0) {
            const double push = Law::parting_correction(table(p.material[i], wall.material), before, vn * s.dt,
                                                        wc.constants[e].r_eff, vn, wc.constants[e].sqrt_m_eff);
            wc.force[e] = push * n;
            wc.point[e] = p.x[i] - ri * n;
            f += wc.force[e];
          }
        }
        wc.shear[e].setZero();
        if constexpr (Law::kRollingSpring) wc.roll[e].setZero();
        continue;
      }
      Vec3 unused_roll = Vec3::Zero();
      Vec3& roll = Law::kRollingSpring ? wc.roll[e] : unused_roll;
      const Vec3 point = p.x[i] - (ri - 0.5 * delta) * normal;  // the middle of the overlap
      const ContactOutput<double> r = wall_contact(s, table, i, normal, delta, point, wall.pose, wall.material,
                                                   wc.constants[e], wc.shear[e], roll, f, t, !wc.touching[e]);
      wc.fn[e] = r.fn;
      wc.kn[e] = r.kn;
      wc.cn[e] = r.cn;
      if (s.record_contacts) wc.ft[e] = std::sqrt(squared_norm(r.shear_force));
      wc.force[e] = r.force.get(0);
      wc.point[e] = point;
      wc.touching[e] = 1;
    }
  }

  // Mesh contacts: the touches of mesh_touches, each taking the history of the last step's slot
  // with the same mesh and the closest normal (at most 60 degrees away): the spring carries over
  // as the sphere crosses from triangle to triangle.
  static void add_mesh_forces(SimState& s, const PairTable<Pair>& table, int i, Vec3& f, Vec3& t) {
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
      double delta, weight;
    } before[kSlots];
    bool taken[kSlots] = {};
    int had = 0;
    for (; mc.used[i] && had < kSlots && now[had].mesh >= 0; ++had)
      before[had] = {now[had].mesh, now[had].normal, now[had].shear, now[had].roll, now[had].delta, now[had].weight};
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
        const Vec3 point = p.x[i] - (ri - 0.5 * touch.delta) * touch.normal;  // the middle of the overlap
        const ContactOutput<double> r = wall_contact(s, table, i, touch.normal, touch.delta, point, s.meshes[m].pose,
                                                     s.meshes[m].material, pc, slot.shear, slot.roll, f, t,
                                                     /*first_sample=*/best < 0, touch.weight);
        slot.normal = touch.normal;
        slot.force = r.force.get(0);
        if (touch.weight != 1) {  // a face shared at a valley: the pull of its weight, through the centre
          const double stored =
              Normal::elastic_energy(table(p.material[i], s.meshes[m].material).normal, touch.delta, ri);
          const Vec3 pull = -stored * touch.weight_gradient;
          f += pull;
          slot.force += pull;
          slot.pull = pull;
        }
        slot.point = point;
        slot.fn = r.fn;
        slot.kn = r.kn;
        slot.cn = r.cn;
        if (s.record_contacts) slot.ft = std::sqrt(squared_norm(r.shear_force));
        slot.delta = touch.delta;
        slot.weight = touch.weight;
        if (filled < kSlots) now[filled++] = slot;
      }
      a = b;
    }
    // A face contact of the last sample found nowhere now, that the drift since has carried off its
    // plane: parted, with the spring's impulse the last sample could not see (spring_boundary_correction).
    // The push goes to the mesh's load too (mc.parted); a particle leaving faces of two meshes in
    // one step keeps the first mesh's push only, so that each wall's work stays its own.
    for (int o = 0; o < had; ++o) {
      if (taken[o] || before[o].delta <= 0) continue;
      const History& h = before[o];
      MeshParting& parting = mc.parted[i];
      if (parting.mesh >= 0 && parting.mesh != h.mesh) continue;
      const double vn = leaving_speed(s, i, h.normal, s.meshes[h.mesh].pose);
      if (!(vn > 0 && h.delta <= vn * s.dt)) continue;
      const double push = Law::parting_correction(table(p.material[i], s.meshes[h.mesh].material), h.delta, vn * s.dt,
                                                  pc.r_eff, vn, pc.sqrt_m_eff);
      const Vec3 force = (h.weight * push) * h.normal;
      f += force;
      parting.mesh = h.mesh;
      parting.force += force;
      parting.point = p.x[i] - ri * h.normal;
    }
    if (filled < kSlots && (filled > 0 || mc.used[i])) now[filled].mesh = -1;
    mc.used[i] = filled > 0;
  }

  PairTable<Pair> table_;
  bool walls_;  // the scene has walls or meshes: the survey and the gather visit their contacts
};

}  // namespace dem
