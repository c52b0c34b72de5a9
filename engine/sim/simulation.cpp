#include "sim/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/errors.hpp"

namespace dem {
namespace {

Particles make_particles(const Scene& scene) {
  Particles p;
  const std::size_t n = scene.particles.size();
  p.x.resize(n);
  p.v.resize(n);
  p.w.resize(n);
  p.f.assign(n, Vec3::Zero());
  p.t.assign(n, Vec3::Zero());
  p.radius.resize(n);
  p.mass.resize(n);
  p.inv_mass.resize(n);
  p.inv_inertia.resize(n);
  p.material.resize(n);
  p.id.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const ParticleInit& in = scene.particles[i];
    const double r = in.radius;
    const double m = scene.materials[in.material].density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
    p.x[i] = in.position;
    p.v[i] = in.fixed ? Vec3::Zero() : in.velocity;
    p.w[i] = in.fixed ? Vec3::Zero() : in.angular_velocity;
    p.radius[i] = r;
    p.mass[i] = m;
    p.inv_mass[i] = in.fixed ? 0 : 1 / m;
    p.inv_inertia[i] = in.fixed ? 0 : 1 / (0.4 * m * r * r);  // solid sphere
    p.material[i] = in.material;
    p.id[i] = static_cast<int>(i);
  }
  return p;
}

double mean_diameter(const std::vector<double>& radius) {
  double sum = 0;
  for (double r : radius) sum += 2 * r;
  return radius.empty() ? 0 : sum / static_cast<double>(radius.size());
}

}  // namespace

Simulation::Simulation(Scene scene) : scene_(std::move(scene)) {
#ifdef _OPENMP
  if (scene_.numerics.threads > 0) omp_set_num_threads(scene_.numerics.threads);
#endif
  state_.table = PairTable(scene_);
  time_step_ = choose_time_step(scene_, state_.table);
  state_.dt = time_step_.dt;
  total_steps_ = scene_.time.steps > 0 ? scene_.time.steps
                                       : static_cast<std::int64_t>(std::ceil(scene_.time.duration / state_.dt - 1e-9));
  if (scene_.outputs.every_steps == 0 && scene_.outputs.interval_seconds > 0)
    scene_.outputs.every_steps =
        std::max<std::int64_t>(1, std::llround(scene_.outputs.interval_seconds / state_.dt));
  state_.particles = make_particles(scene_);
  state_.f_next.assign(state_.particles.size(), Vec3::Zero());
  state_.half_kick.assign(state_.particles.size(), Vec3::Zero());
  state_.gravity = scene_.gravity;
  for (const WallInit& w : scene_.walls) state_.walls.push_back(Wall::from(w));
  skin_ = scene_.numerics.skin_fraction * mean_diameter(state_.particles.radius);
  kernel_ = select_kernel(scene_, !state_.walls.empty());
  build_neighbors();
  // Forces at t = 0 for the first half kick: a zero step leaves history and velocities unchanged.
  state_.dt = 0;
  kernel_->compute_and_kick(state_);
  state_.dt = time_step_.dt;
}

void Simulation::step() {
  const double moved2 = half_kick_and_drift();
  const double half_skin = 0.5 * skin_;
  const int interval = scene_.numerics.search_interval;
  if (moved2 > half_skin * half_skin || (interval > 0 && step_ + 1 - last_build_step_ >= interval)) build_neighbors();
  kernel_->compute_and_kick(state_);
  contacts_recorded_ = state_.record_contacts;
  ++step_;
}

double Simulation::half_kick_and_drift() {
  Particles& p = state_.particles;
  const int n = static_cast<int>(p.size());
  const double dt = state_.dt, half_dt = 0.5 * dt;
  double moved2 = 0;
  // Raw pointers and whole-vector expressions: through the std::vectors the compiler kept
  // reloading their data pointers and called Eigen's assignment loops out of line (9% of a step).
  Vec3* __restrict kick = state_.half_kick.data();
  Vec3* __restrict x = p.x.data();
  Vec3* __restrict v = p.v.data();
  Vec3* __restrict w = p.w.data();
  const Vec3* __restrict f = p.f.data();
  const Vec3* __restrict t = p.t.data();
  const Vec3* __restrict x0 = x_at_build_.data();
  const double* __restrict inv_mass = p.inv_mass.data();
  const double* __restrict inv_inertia = p.inv_inertia.data();
#pragma omp parallel for schedule(static) reduction(max : moved2) if (n >= kParallelMinParticles)
  for (int i = 0; i < n; ++i) {
    const Vec3 k = (half_dt * inv_mass[i]) * f[i];
    kick[i] = k;
    const Vec3 vi = v[i] + k;
    v[i] = vi;
    w[i] = w[i] + (half_dt * inv_inertia[i]) * t[i];
    const Vec3 xi = x[i] + dt * vi;
    x[i] = xi;
    moved2 = std::max(moved2, (xi - x0[i]).squaredNorm());
  }
  return moved2;
}

void Simulation::build_neighbors() {
  Particles& p = state_.particles;
  std::vector<int> order;
  const int reorder = scene_.numerics.reorder_interval;
  if (reorder > 0 && builds_ % reorder == 0 && p.size() > 0) {
    const double r_max = *std::max_element(p.radius.begin(), p.radius.end());
    order = spatial_order(p, 2 * r_max + skin_);
    bool identity = true;
    for (std::size_t k = 0; k < order.size() && identity; ++k) identity = order[k] == static_cast<int>(k);
    if (identity) {
      order.clear();
    } else {
      p.permute(order);
      permute_array(state_.half_kick, order);  // this step's kick, already taken, feeds the prediction
    }
  }
  ++builds_;
  NeighborList next;
  build_neighbor_list(p, {skin_, kernel_->has_rolling_spring()}, state_.neighbors, order, next);
  state_.neighbors = std::move(next);
  const std::size_t pairs = state_.neighbors.pair_count();
  PairResults& r = state_.pairs;
  r.fn.assign(pairs, 0.0);
  r.ft_squared.assign(pairs, 0.0);
  r.touching.assign(pairs, 0);
  plan_blocks();
  WallContacts previous = std::move(state_.wall_contacts);
  build_wall_contacts(previous, order);
  x_at_build_ = p.x;
  last_build_step_ = step_;
}

void Simulation::plan_blocks() {
  const NeighborList& nl = state_.neighbors;
  BlockPlan& b = state_.blocks;
  const int n = static_cast<int>(state_.particles.size());
  b.deferred_start.assign(n + 1, 0);
  auto crosses = [&](int i, int j) { return j / b.block_size != i / b.block_size; };
  for (int i = 0; i < n; ++i)
    for (int k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k)
      if (crosses(i, nl.partner[k])) ++b.deferred_start[nl.partner[k] + 1];
  for (int i = 0; i < n; ++i) b.deferred_start[i + 1] += b.deferred_start[i];
  b.slot.assign(nl.pair_count(), -1);
  std::vector<int> fill(b.deferred_start.begin(), b.deferred_start.end() - 1);
  for (int i = 0; i < n; ++i)
    for (int k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k)
      if (crosses(i, nl.partner[k])) b.slot[k] = fill[nl.partner[k]]++;
  b.deferred_force.assign(b.deferred_start[n], Vec3::Zero());
  b.deferred_torque.assign(b.deferred_start[n], Vec3::Zero());
}

void Simulation::build_wall_contacts(const WallContacts& previous, const std::vector<int>& new_to_old) {
  const Particles& p = state_.particles;
  WallContacts& wc = state_.wall_contacts;
  const int n = static_cast<int>(p.size());
  wc = WallContacts{};
  wc.row_start.assign(n + 1, 0);
  if (state_.walls.empty()) return;
  const bool keep_roll = kernel_->has_rolling_spring();
  for (int i = 0; i < n; ++i) {
    const int old = new_to_old.empty() ? i : new_to_old[i];
    for (int w = 0; w < static_cast<int>(state_.walls.size()); ++w) {
      if (state_.walls[w].distance(p.x[i]) >= p.radius[i] + skin_) continue;
      Vec3 shear = Vec3::Zero(), roll = Vec3::Zero();
      if (!previous.row_start.empty()) {
        for (int e = previous.row_start[old]; e < previous.row_start[old + 1]; ++e) {
          if (previous.wall[e] != w) continue;
          shear = previous.shear[e];
          if (keep_roll) roll = previous.roll[e];
        }
      }
      wc.wall.push_back(w);
      wc.constants.push_back(wall_constants(p, i));
      wc.shear.push_back(shear);
      if (keep_roll) wc.roll.push_back(roll);
    }
    wc.row_start[i + 1] = static_cast<int>(wc.wall.size());
  }
  wc.fn.assign(wc.wall.size(), 0.0);
  wc.ft.assign(wc.wall.size(), 0.0);
  wc.touching.assign(wc.wall.size(), 0);
}

double Simulation::kinetic_energy() const {
  const Particles& p = state_.particles;
  double e = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    e += 0.5 * p.mass[i] * (p.v[i].squaredNorm() + 0.4 * p.radius[i] * p.radius[i] * p.w[i].squaredNorm());
  return e;
}

double Simulation::gravitational_energy() const {
  const Particles& p = state_.particles;
  double e = 0;
  for (std::size_t i = 0; i < p.size(); ++i) e -= p.mass[i] * state_.gravity.dot(p.x[i]);
  return e;
}

namespace {
void require_recorded(bool recorded) {
  if (!recorded) throw std::logic_error("the last step did not record contact forces (Simulation::record_contacts)");
}
}  // namespace

std::vector<int> Simulation::contact_counts() const {
  require_recorded(contacts_recorded_);
  const Particles& p = state_.particles;
  const NeighborList& nl = state_.neighbors;
  std::vector<int> count(p.size(), 0);
  for (std::size_t i = 0; i < p.size(); ++i)
    for (int k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k)
      if (state_.pairs.touching[k]) {
        ++count[i];
        ++count[nl.partner[k]];
      }
  const WallContacts& wc = state_.wall_contacts;
  for (std::size_t i = 0; i + 1 < wc.row_start.size(); ++i)
    for (int e = wc.row_start[i]; e < wc.row_start[i + 1]; ++e) count[i] += wc.touching[e];
  return count;
}

std::vector<PairContact> Simulation::pair_contacts() const {
  require_recorded(contacts_recorded_);
  const NeighborList& nl = state_.neighbors;
  std::vector<PairContact> out;
  for (std::size_t i = 0; i < state_.particles.size(); ++i)
    for (int k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k)
      if (state_.pairs.touching[k])
        out.push_back({static_cast<int>(i), nl.partner[k], state_.pairs.fn[k], std::sqrt(state_.pairs.ft_squared[k])});
  return out;
}

}  // namespace dem
