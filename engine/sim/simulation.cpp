#include "sim/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <tuple>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/errors.hpp"
#include "core/parallel.hpp"
#include "core/rotation.hpp"

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
  const Grain grain = scene.grain();
  for (std::size_t i = 0; i < n; ++i) {
    const ParticleInit& in = scene.particles[i];
    const double r = in.radius;
    const double m = grain.mass(scene.materials[in.material].density, r);
    p.x[i] = in.position;
    p.v[i] = in.fixed ? Vec3::Zero() : in.velocity;
    p.w[i] = in.fixed ? Vec3::Zero() : in.angular_velocity;
    p.radius[i] = r;
    p.mass[i] = m;
    p.inv_mass[i] = in.fixed ? 0 : 1 / m;
    p.inv_inertia[i] = in.fixed ? 0 : 1 / grain.inertia(m, r);
    p.material[i] = in.material;
    p.id[i] = static_cast<int>(i);
    if (!in.force.isZero(0)) {
      if (p.external.empty()) p.external.assign(n, Vec3::Zero());
      p.external[i] = in.force;
    }
  }
  return p;
}

double mean_diameter(const std::vector<double>& radius) {
  double sum = 0;
  for (double r : radius) sum += 2 * r;
  return radius.empty() ? 0 : sum / static_cast<double>(radius.size());
}

}  // namespace

Simulation::Simulation(Scene scene, KernelSelector select) : scene_(std::move(scene)), select_(select) {
#ifdef _OPENMP
  if (scene_.numerics.threads > 0) omp_set_num_threads(scene_.numerics.threads);
#endif
  kernel_ = select(scene_, !scene_.walls.empty());
  state_.particles = make_particles(scene_);
  state_.bodies = make_bodies(scene_);
  mark_members(scene_, state_.bodies, state_.particles);
  state_.f_next.assign(state_.particles.size(), Vec3::Zero());
  state_.half_kick.assign(state_.particles.size(), Vec3::Zero());
  state_.spin_kick.assign(state_.particles.size(), Vec3::Zero());
  state_.gravity = scene_.gravity;
  state_.overlap_limit = scene_.numerics.max_overlap_fraction;
  state_.local_damping = scene_.numerics.local_damping;
  given_particles_ = scene_.particles.size();
  // A source's particles count as given for the step, the skin and the walls' reach before they
  // exist: its smallest and largest, at its region's corners, stand in for them until the step is chosen.
  std::vector<ParticleInit> source_extremes_all;
  for (const ParticleSource& source : scene_.sources)
    for (const ParticleInit& p : source_extremes(scene_, source)) source_extremes_all.push_back(p);
  scene_.particles.insert(scene_.particles.end(), source_extremes_all.begin(), source_extremes_all.end());
  for (const ParticleInit& init : scene_.particles)
    largest_given_radius_ = std::max(largest_given_radius_, init.radius);
  smallest_given_radius_ = largest_given_radius_;
  for (const ParticleInit& init : scene_.particles)
    smallest_given_radius_ = std::min(smallest_given_radius_, init.radius);
  refuse_positions_past_precision();
  if (scene_.plane) refuse_motion_off_the_plane();
  boundaries_.build(scene_, scene_.particles, state_.walls, state_.meshes);
  boundary_loads_.assign(scene_.walls.size(), BoundaryLoad{});
  if (scene_.growth && scene_.growth->steps > 0)
    growth_plan_ = GrowthPlan{1, scene_.growth->factor, 0, scene_.growth->steps};
  if (!scene_.stages.empty()) apply_stage_settings(0, /*restore=*/false);
  boundaries_.note_variation(scene_);
  // of the sources' extremes when the run starts empty
  std::vector<double> radii_for_skin = state_.particles.radius;
  if (radii_for_skin.empty())
    for (const ParticleInit& p : source_extremes_all) radii_for_skin.push_back(p.radius);
  skin_ = scene_.numerics.skin_fraction * mean_diameter(radii_for_skin);
  move_walls(0, 0);
  build_neighbors();
  refuse_coincident_particles();
  // bonds are glued now, or at the start of the stage that glues them (then from the stage's contacts)
  const int bonding_stage = std::max(0, scene_.bonding_stage());  // 0: at t = 0
  if (scene_.bonds) {
    state_.particles.q.assign(state_.particles.size(), Quat::Identity());  // the bonds measure turns from here
    if (bonding_stage == 0) glue_bonds();
  }
  // Forces at t = 0 for the first half kick: a zero step leaves history and velocities unchanged.
  // They come first so that the step knows the initial contacts (the speed their stored energy gives).
  state_.dt = 0;
  compute_forces_and_kick();
  settle_walls(0, 0);
  // the step knows whether any bond was made (a bonds block that glued nothing does not shorten it)
  // (a stage that glues bonds later needs a step that resolves them from the start)
  time_step_ = choose_time_step(scene_, *kernel_, !state_.bonds.empty() || bonding_stage > 0,
                                kernel_->summarize(state_).release_speed);
  // A stage's interactions and loads hold the step to their limits too (restitution shortens a
  // damped contact; a light loaded wall needs a short step): the shortest of them all is taken.
  for (std::size_t k = 0; k < scene_.stages.size(); ++k) {
    const Stage& stage = scene_.stages[k];
    const bool loads = std::any_of(stage.wall_changes.begin(), stage.wall_changes.end(),
                                   [](const WallChange& change) { return change.load.has_value(); });
    if (!stage.interactions && !loads) continue;
    const std::vector<Interaction> own = scene_.interactions;
    std::vector<std::pair<std::optional<PrescribedMotion>, std::optional<LoadControl>>> own_drives;
    for (const WallInit& w : scene_.walls) own_drives.emplace_back(w.motion, w.load);
    if (stage.interactions) scene_.interactions = *stage.interactions;
    for (const WallChange& change : stage.wall_changes) {
      scene_.walls[change.wall].motion = change.motion;
      scene_.walls[change.wall].load = change.load;
    }
    auto restore = [&] {
      scene_.interactions = own;
      for (std::size_t w = 0; w < scene_.walls.size(); ++w)
        std::tie(scene_.walls[w].motion, scene_.walls[w].load) = own_drives[w];
    };
    TimeStepReport staged;
    try {
      const std::unique_ptr<ForceKernel> kernel = select_(scene_, !scene_.walls.empty());
      staged = choose_time_step(scene_, *kernel, !state_.bonds.empty() || bonding_stage > 0,
                                kernel_->summarize(state_).release_speed);
    } catch (const SceneError& e) {
      restore();
      throw SceneError("stages[" + std::to_string(k) + "] (" + stage.name + "): " + e.what());
    }
    restore();
    if (staged.dt < time_step_.dt) time_step_ = staged;
  }
  state_.dt = time_step_.dt;
  // A prescribed motion must not carry a wall through a particle between two force evaluations.
  const double wall_reach = 0.5 * scene_.numerics.max_overlap_fraction * smallest_given_radius_;
  auto check_motion = [&](const WallInit& wall, const std::string& where) {
    if (!wall.motion || scene_.particles.empty()) return;
    const double move = fastest_wall_speed(scene_, wall) * state_.dt;
    if (move <= wall_reach) return;
    char buf[480];
    std::snprintf(
        buf, sizeof buf,
        "%s (%s): its motion moves it up to %.3e m in one step of %.6e s, more than %.3g of the smallest "
        "particle radius (%.3e m): it would pass through particles unseen; make it slower, or the step smaller "
        "(time.dt or time.dtFraction)",
        where.c_str(), wall.name.c_str(), move, state_.dt, 0.5 * scene_.numerics.max_overlap_fraction,
        smallest_given_radius_);
    throw SceneError(buf);
  };
  for (int k = 0; k < boundaries_.size(); ++k) check_motion(scene_.walls[k], scene_.walls[k].where(k));
  for (std::size_t s = 0; s < scene_.stages.size(); ++s)
    for (std::size_t c = 0; c < scene_.stages[s].wall_changes.size(); ++c) {
      WallInit changed = scene_.walls[scene_.stages[s].wall_changes[c].wall];
      changed.motion = scene_.stages[s].wall_changes[c].motion;
      check_motion(changed, "stages[" + std::to_string(s) + "].wallChanges[" + std::to_string(c) + "]");
    }
  scene_.particles.resize(given_particles_);  // the sources' stand-ins are gone
  source_progress_.assign(scene_.sources.size(), SourceProgress{});
  next_source_radius_.assign(scene_.sources.size(), {-1, 0.0});
  // Step counts are int64 and times step * dt: past 2^53 steps neither is exact any more.
  constexpr double kMaxSteps = 9007199254740992.0;  // 2^53
  if (!scene_.stages.empty()) {
    double steps = 0;
    for (std::size_t k = 0; k < scene_.stages.size(); ++k) {
      const Stage& stage = scene_.stages[k];
      const double n =
          stage.steps > 0 ? static_cast<double>(stage.steps) : std::ceil(stage.duration / state_.dt - 1e-9);
      steps += std::max(1.0, n);
      if (stage.min_duration > 0 && stage.min_duration > std::max(1.0, n) * state_.dt * (1 + 1e-12)) {
        char buf[300];
        std::snprintf(buf, sizeof buf,
                      "stages[%zu].minDuration: %.6g s is longer than the stage itself (%.0f steps of %.6e s): its "
                      "end condition could never end it",
                      k, stage.min_duration, std::max(1.0, n), state_.dt);
        throw SceneError(buf);
      }
      if (!(steps <= kMaxSteps)) {
        char buf[400];
        std::snprintf(buf, sizeof buf,
                      "stages[%zu]: the stages up to this one would take %.3g steps of %.6e s, more than a run can "
                      "count (at most 2^53 = 9.0e15); shorten them, or make the contacts softer or the particles "
                      "heavier",
                      k, steps, state_.dt);
        throw SceneError(buf);
      }
    }
    stage_end_step_ = stage_steps(0);
    plan_stage_growth(0);
    recount_total_steps();
  } else if (scene_.time.steps > 0) {
    if (scene_.time.steps > (std::int64_t{1} << 53))
      throw SceneError("time.steps: " + std::to_string(scene_.time.steps) +
                       " is more than a run can count (at most 2^53)");
    total_steps_ = scene_.time.steps;
  } else {
    // at least one step for any positive duration (5e-324 s once ran none)
    const double steps = std::max(1.0, std::ceil(scene_.time.duration / state_.dt - 1e-9));
    if (!(steps <= kMaxSteps)) {
      char buf[400];
      std::snprintf(buf, sizeof buf,
                    "time.duration: %.6g s at a step of %.6e s (%s) would take %.3g steps, more than a run can count "
                    "(at most 2^53 = 9.0e15); shorten the run, or make the contacts softer or the particles heavier",
                    scene_.time.duration, state_.dt, time_step_.automatic ? "automatic" : "given", steps);
      throw SceneError(buf);
    }
    total_steps_ = static_cast<std::int64_t>(steps);
  }
  if (scene_.stages.empty()) stage_end_step_ = total_steps_;
  if (scene_.outputs.every_steps == 0 && scene_.outputs.interval_seconds > 0) {
    // an interval longer than the run gives its first and last frames only
    const double every = scene_.outputs.interval_seconds / state_.dt;
    scene_.outputs.every_steps = every >= static_cast<double>(total_steps_)
                                     ? std::max<std::int64_t>(1, total_steps_)
                                     : std::max<std::int64_t>(1, std::llround(every));
  }
  ledger_.initial_energy = mechanical_energy();
}

double Simulation::mechanical_energy() const {
  return kinetic_energy() + gravitational_energy() + contact_summary().elastic_energy + state_.bonds.elastic_energy();
}

Vec3 Simulation::linear_momentum() const {
  const Particles& p = state_.particles;
  const ClumpBodies& b = state_.bodies;
  Vec3 total = Vec3::Zero();
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.inv_mass[i] > 0 && (p.body.empty() || p.body[i] < 0)) total += p.mass[i] * p.v[i];
  for (std::size_t k = 0; k < b.size(); ++k) total += b.mass[k] * b.v[k];
  return total;
}

Vec3 Simulation::angular_momentum() const {
  const Particles& p = state_.particles;
  const ClumpBodies& b = state_.bodies;
  Vec3 total = Vec3::Zero();
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.inv_mass[i] > 0 && (p.body.empty() || p.body[i] < 0))
      total += p.x[i].cross(p.mass[i] * p.v[i]) + p.w[i] / p.inv_inertia[i];
  for (std::size_t k = 0; k < b.size(); ++k) total += b.x[k].cross(b.mass[k] * b.v[k]) + b.rotation[k].angular_momentum;
  return total;
}

void Simulation::move_walls(double t_new, double dt) { boundaries_.begin_step(t_new, dt, state_.walls, state_.meshes); }

void Simulation::settle_walls(double t_new, double dt) {
  // Sums over particles in index order: the same totals for any number of threads.
  for (BoundaryLoad& load : boundary_loads_) load = BoundaryLoad{};
  const Particles& p = state_.particles;
  const WallContacts& wc = state_.wall_contacts;
  const int n = static_cast<int>(p.size());
  // is_contact: false for the push of the step after a parting (the spring's missed impulse)
  auto add = [&](int k, const Vec3& force_on_particle, const Vec3& point, bool is_contact = true) {
    BoundaryLoad& load = boundary_loads_[k];
    const WallPose& pose = boundaries_.driver(k).pose();
    const Vec3 centre = pose.center0 + pose.displacement;
    load.force -= force_on_particle;
    load.torque -= (point - centre).cross(force_on_particle);
    if (is_contact) ++load.contacts;
  };
  // Summed whatever the contact's normal: along the load's direction each counts at most that much,
  // so the servo's cap is on the safe side.
  auto respond = [&](int k, double kn, double cn) {
    boundary_loads_[k].response.stiffness += kn;
    boundary_loads_[k].response.damping += cn;
  };
  // the contacts are stored in particle order: one pass over them, not over every particle's row
  const int wall_entries = wc.row_start.empty() ? 0 : wc.row_start[n];
  for (int e = 0; e < wall_entries; ++e)
    if (wc.touching[e] || !wc.force[e].isZero(0)) {
      add(boundaries_.of_plane(wc.wall[e]), wc.force[e], wc.point[e], wc.touching[e] != 0);
      respond(boundaries_.of_plane(wc.wall[e]), wc.kn[e], wc.cn[e]);
    }
  MeshContacts& mc = state_.mesh_contacts;
  for (int i = 0; i < n && !mc.used.empty() && !mc.none_near(); ++i) {
    // only a particle with a face within reach has slots in use or a parting (add_mesh_forces): the
    // others (most, and all of them for a mesh far away) cost one comparison here
    if (mc.row_start[i] == mc.row_start[i + 1]) continue;
    for (int k = 0, used = mc.count(i); k < used; ++k) {
      // a valley weight's pull acts through the centre: at the contact point its torque on a
      // turning mesh was wrong, and so was the mesh's work (a sphere in a spinning pit: 21% of it)
      const MeshSlot& slot = mc.slot(i, k);
      const int boundary = state_.meshes[slot.mesh].boundary;
      add(boundary, slot.force - slot.pull, slot.point);
      respond(boundary, slot.kn, slot.cn);
      if (!slot.pull.isZero(0)) add(boundary, slot.pull, p.x[i], /*is_contact=*/false);
    }
    if (MeshParting& parting = mc.parted[i]; parting.mesh >= 0) {
      add(state_.meshes[parting.mesh].boundary, parting.force, parting.point, /*is_contact=*/false);
      parting = MeshParting{};
    }
  }
  boundaries_.end_step(t_new, dt, boundary_loads_, state_.walls, state_.meshes);
}

// A wall (a load drives it; a prescribed motion was checked at the set-up) that moved so far in
// this step that it could pass through a particle unseen: the first such step is kept (TooFast).
void Simulation::check_wall_moves(const std::vector<WallPose>& before) {
  if (first_too_fast_) return;
  const double reach = 0.5 * scene_.numerics.max_overlap_fraction * smallest_given_radius_;
  if (const auto past = boundaries_.moved_past(before, reach))
    first_too_fast_ = TooFast{
        step_ + 1, static_cast<double>(step_ + 1) * state_.dt, -1, past->second, smallest_given_radius_, past->first};
}

// A double resolves a coordinate to 1.1e-16 of its size: 1e9 radii from the origin an overlap is
// resolved to 1e-7 of the radius, past that contacts go wrong (two 1 mm spheres at 9.9e8 m, 1e12
// radii out, rebounded with e = 0.844 for 0.8).
void Simulation::refuse_positions_past_precision() const {
  constexpr double kMostRadii = 1e9;
  double farthest = 0;
  int which = -1;
  for (std::size_t i = 0; i < scene_.particles.size(); ++i) {
    const double far = scene_.particles[i].position.cwiseAbs().maxCoeff();
    if (far > farthest) {
      farthest = far;
      which = static_cast<int>(i);
    }
  }
  if (which < 0 || farthest <= kMostRadii * smallest_given_radius_) return;
  char buf[460];
  std::snprintf(buf, sizeof buf,
                "particles: particle %d is %.3e m from the origin, %.3g times the smallest radius (%.3e m): a double "
                "resolves a coordinate there to %.1e m, too coarse for contacts of spheres that small; move the "
                "scene nearer the origin (at most 1e9 smallest radii out)",
                which + 1, farthest, farthest / smallest_given_radius_, smallest_given_radius_,
                farthest * std::numeric_limits<double>::epsilon());
  throw SceneError(buf);
}

// A 2D run's discs start in the plane, moving in it and turning about y (the spec loader says which field is off).
void Simulation::refuse_motion_off_the_plane() const {
  for (std::size_t i = 0; i < scene_.particles.size(); ++i) {
    const ParticleInit& p = scene_.particles[i];
    if (p.position.y() == 0 && p.velocity.y() == 0 && p.angular_velocity.x() == 0 && p.angular_velocity.z() == 0 &&
        p.force.y() == 0 && p.clump < 0)
      continue;
    throw SceneError("particles: particle " + std::to_string(i + 1) +
                     " leaves the plane of a 2D run: its y, velocity y, spin x and z and force y must be 0, and it "
                     "cannot belong to a clump");
  }
  if (scene_.gravity.y() != 0) throw SceneError("gravity: a 2D run's gravity lies in the x-z plane (its y must be 0)");
}

// The forces at the particles' positions now and the step's second half kick (state_.dt: 0 for the forces alone, at
// the start and at a stage's start), the plane's reaction in a 2D run, and the clumps' bodies' kick.
void Simulation::compute_forces_and_kick() {
  kernel_->compute_and_kick(state_);  // times its pairs, bonds, walls, meshes and kick itself
  if (scene_.plane) {
    const PhaseTimer timer(state_.profile, Phase::kick);
    hold_in_plane();
  }
  if (!state_.bodies.empty()) {
    const PhaseTimer timer(state_.profile, Phase::clumps);
    kick_bodies(state_.bodies, state_.particles, state_.gravity, state_.dt, state_.local_damping);
  }
}

// The plane's reaction (a 2D run): the discs keep y = 0 and turn only about y. The kick has just added dt/2 f/m, so
// clearing the out-of-plane velocity and spin is clearing those forces' and torques' part of it; the forces and
// torques are cleared too for the next step's first half kick. The constraint does no work: it removes only
// velocity components that were 0 before the kick.
void Simulation::hold_in_plane() {
  Particles& p = state_.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.f[i].y() = 0;
    p.v[i].y() = 0;
    p.t[i].x() = p.t[i].z() = 0;
    p.w[i].x() = p.w[i].z() = 0;
  }
}

// Two particles with one centre: the contact between them has no direction (its normal is 0/0).
void Simulation::refuse_coincident_particles() const {
  const Particles& p = state_.particles;
  const NeighborList& nl = state_.neighbors;
  for (int i = 0; i < static_cast<int>(p.size()); ++i)
    for (int k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
      const int j = nl.partner[k];
      const double close = 1e-9 * (p.radius[i] + p.radius[j]);
      if ((p.x[i] - p.x[j]).squaredNorm() > close * close) continue;
      const int a = std::min(p.id[i], p.id[j]) + 1, b = std::max(p.id[i], p.id[j]) + 1;
      char buf[300];
      std::snprintf(
          buf, sizeof buf,
          "particles: particles %d and %d are at the same place (centres %.3e m apart, radii %.3e and %.3e m): "
          "a contact between them has no direction; move one of them",
          a, b, (p.x[i] - p.x[j]).norm(), p.radius[i], p.radius[j]);
      throw SceneError(buf);
    }
}

void Simulation::add_work(double& account, double work) {
  account += work;
  ledger_.magnitude += std::abs(work);
}

// The work of each moving wall on the particles over the step: minus the force and torque the
// particles put on it (trapezoid of the step's start and end) times its displacement and turn.
void Simulation::add_wall_work(const std::vector<WallPose>& before, const std::vector<BoundaryLoad>& loads_before) {
  double work = 0;
  for (int k = 0; k < boundaries_.size(); ++k) {
    if (!boundaries_.present(k) || !boundaries_.driver(k).moves()) continue;
    const WallPose& now = boundaries_.driver(k).pose();
    const Vec3 shift = now.displacement - before[k].displacement;
    const Eigen::AngleAxisd turn(Eigen::Matrix3d(now.rotation * before[k].rotation.transpose()));
    const Vec3 force = 0.5 * (loads_before[k].force + boundary_loads_[k].force);
    const Vec3 torque = 0.5 * (loads_before[k].torque + boundary_loads_[k].torque);
    work -= force.dot(shift) + torque.dot(turn.angle() * turn.axis());
  }
  add_work(ledger_.walls, work);
}

void Simulation::step() {
  update_stage();
  const double t_new = static_cast<double>(step_ + 1) * state_.dt;
  const bool walls_move = boundaries_.any_moving();
  PhaseProfile* const profile = state_.profile;
  std::vector<WallPose> poses_before;
  std::vector<BoundaryLoad> loads_before;
  // a scene without walls has no wall motion to time (its calls return at once)
  PhaseProfile* const walls_profile = scene_.walls.empty() ? nullptr : profile;
  {
    const PhaseTimer timer(walls_profile, Phase::wall_motion);
    if (walls_move) {
      poses_before = boundaries_.poses();
      loads_before = boundary_loads_;
    }
    move_walls(t_new, state_.dt);
  }
  // growth's work on the contacts at the step's start positions; grow() adds that at its end
  PhaseProfile* const growth_profile = growth_plan_ ? profile : nullptr;  // likewise without growth
  double growth_at_start = 0;
  {
    const PhaseTimer timer(growth_profile, Phase::growth);
    growth_at_start = growth_energy_at_positions_now();
  }
  state_.time = t_new;
  double moved2 = 0;
  {
    const PhaseTimer timer(profile, Phase::drift);
    moved2 = half_kick_and_drift();
  }
  if (!state_.bodies.empty()) {  // the members move with their bodies, not as the drift above moved them
    const PhaseTimer timer(profile, Phase::clumps);
    moved2 = std::max(moved2, drift_bodies(state_.bodies, state_.particles, x_at_build_, state_.dt, state_.half_kick,
                                           state_.spin_kick));
  }
  // The particle that moved farthest for its size in this drift, with the velocity that moved it: after
  // the step's second half kick its speed can be anything (at a step of 1e200 s a sphere resting on a
  // plane was reported to have moved 0 m, and one whose speed overflowed -8e-3 m).
  if (moved_too_far_ && !first_too_fast_) {
    const Particles& p = state_.particles;
    std::size_t worst = 0;
    double worst_ratio = -1;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double ratio = state_.dt * p.v[i].norm() / p.radius[i];
      const double key = std::isnan(ratio) ? std::numeric_limits<double>::infinity() : ratio;  // NaN: the worst
      if (key > worst_ratio) {
        worst_ratio = key;
        worst = i;
      }
    }
    first_too_fast_ = TooFast{step_ + 1, static_cast<double>(step_ + 1) * state_.dt, p.id[worst],
                              state_.dt * p.v[worst].norm(), p.radius[worst]};
  }
  double grown = 0;
  {
    const PhaseTimer timer(growth_profile, Phase::growth);
    grown = grow(growth_at_start);
  }
  bool inserted = false;
  if (!scene_.sources.empty()) {
    const PhaseTimer timer(profile, Phase::sources);
    inserted = feed_sources();
  }
  const double half_skin = 0.5 * skin_;
  const int interval = scene_.numerics.search_interval;
  // a pair closes by at most twice (the largest move + the largest growth) since the build
  if (inserted || std::sqrt(moved2) + grown > half_skin || boundaries_.shift_since_build() > half_skin ||
      (interval > 0 && step_ + 1 - last_build_step_ >= interval))
    build_neighbors();
  compute_forces_and_kick();
  {
    const PhaseTimer timer(walls_profile, Phase::wall_motion);
    settle_walls(t_new, state_.dt);
    if (walls_move) {
      add_wall_work(poses_before, loads_before);
      check_wall_moves(poses_before);
    }
  }
  contacts_recorded_ = state_.record_contacts;
  ++step_;
  if (state_.non_finite && !first_non_finite_) {  // the kick's sum of magnitudes is not finite: which particles?
    const Particles& p = state_.particles;
    NonFinite bad{step_, time(), -1, 0};
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (state_is_finite(p.x[i], p.v[i], p.w[i], p.mass[i])) continue;
      ++bad.particles;
      if (bad.particle_id < 0 || p.id[i] < bad.particle_id) bad.particle_id = p.id[i];
    }
    if (bad.particles > 0) first_non_finite_ = bad;  // none: only the sum overflowed
  }
}

// The radii's scale (Scene::growth, or a stage's) after this step: reached linearly over its steps.
double Simulation::grown_scale() const {
  const GrowthPlan& g = *growth_plan_;
  const double share = std::min(1.0, static_cast<double>(step_ + 1 - g.start) / static_cast<double>(g.steps));
  return g.from + (g.to - g.from) * share;
}

std::vector<double> Simulation::grown_radii() const {
  const double scale = grown_scale();
  const Particles& p = state_.particles;
  std::vector<double> radius(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) radius[i] = scene_.particles[p.id[i]].radius * scale;
  return radius;
}

bool Simulation::growing() const {
  return growth_plan_ && growth_plan_->steps > 0 && step_ >= growth_plan_->start &&
         step_ < growth_plan_->start + growth_plan_->steps;
}

double Simulation::growth_energy_at_positions_now() const {
  if (!growing()) return 0;
  return kernel_->elastic_energy(state_, grown_radii()) - kernel_->elastic_energy(state_, state_.particles.radius);
}

double Simulation::grow(double contacts_work_at_start) {
  if (!growing()) return largest_given_radius_ * (growth_scale_ - growth_at_build_);
  Particles& p = state_.particles;
  // The work of this step's growth: what the larger radii add to the energy stored in the contacts
  // (the elastic energy the ledger counts) at the positions of the step's start and of its end,
  // averaged (the step moves the particles with the forces of the old radii, then of the new: either
  // end alone is off by half the change of force times the move; in a packing grown without damping
  // the energy then missed the work by 3e-3 of it, with the average by 4e-5); and each free particle's energies
  // changing with its mass at its speed, spin and height (1/2 dm v^2 + 1/2 dI w^2 - dm g.x). Not the contact forces
  // times the overlaps' growth: their dashpots pull while grown spheres push apart, and counting that pull made damped
  // contacts look like sources (the guard stopped the PDEM-EGD manual's set-up at eps 0.2).
  const std::vector<double> radius = grown_radii();
  const double work_at_end = kernel_->elastic_energy(state_, radius) - kernel_->elastic_energy(state_, p.radius);
  double work = 0.5 * (contacts_work_at_start + work_at_end);
  const Grain grain = scene_.grain();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = radius[i];
    const double m = grain.mass(scene_.materials[scene_.particles[p.id[i]].material].density, r);
    if (p.inv_mass[i] > 0) {
      const double dm = m - p.mass[i], di = grain.inertia(m, r) - grain.inertia(p.mass[i], p.radius[i]);
      work += 0.5 * dm * p.v[i].squaredNorm() + 0.5 * di * p.w[i].squaredNorm() - dm * state_.gravity.dot(p.x[i]);
    }
    p.radius[i] = r;
    p.mass[i] = m;
    if (p.inv_mass[i] > 0) {
      p.inv_mass[i] = 1 / m;
      p.inv_inertia[i] = 1 / grain.inertia(m, r);
    }
  }
  refresh_contact_constants();
  add_work(ledger_.growth, work);
  growth_scale_ = grown_scale();
  return largest_given_radius_ * (growth_scale_ - growth_at_build_);
}

void Simulation::refresh_contact_constants() {
  const Particles& p = state_.particles;
  NeighborList& nl = state_.neighbors;
  const int n = static_cast<int>(p.size());
  if (static_cast<int>(nl.row_start.size()) == n + 1)
    for (int i = 0; i < n; ++i)
      for (int k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
        const PairConstants c = pair_constants(p, i, nl.partner[k]);
        nl.sqrt_m_eff[k] = c.sqrt_m_eff;
        nl.r_eff[k] = c.r_eff;
        nl.i_roll[k] = c.i_roll;
      }
  WallContacts& wc = state_.wall_contacts;
  if (static_cast<int>(wc.row_start.size()) == n + 1)
    for (int i = 0; i < n; ++i)
      for (int e = wc.row_start[i]; e < wc.row_start[i + 1]; ++e) wc.constants[e] = wall_constants(p, i);
  MeshContacts& mc = state_.mesh_contacts;
  if (static_cast<int>(mc.constants.size()) == n)
    for (int i = 0; i < n; ++i) mc.constants[i] = wall_constants(p, i);
}

double Simulation::half_kick_and_drift() {
  Particles& p = state_.particles;
  const int n = static_cast<int>(p.size());
  const double dt = state_.dt, half_dt = 0.5 * dt;
  // a particle may move at most this share of its radius in a step (TooFast)
  const double reach = 0.5 * scene_.numerics.max_overlap_fraction;
  const double reach2_over_dt2 = reach * reach / (dt * dt);
  struct Drift {
    double moved2 = 0;  // the largest squared move since the neighbour build
    bool too_fast = false;
  };
  // The work of the constant external forces over this drift, summed block by block (kParticleBlock),
  // then the blocks in order: the same bits on any number of threads, whose ranges are whole blocks.
  // Summed per range, the ledger's external work (Energy.csv, results.json) changed in its last
  // digits with the thread count.
  double* __restrict work_of_block = nullptr;
  if (!p.external.empty()) {
    external_work_of_block_.assign((n + kParticleBlock - 1) / kParticleBlock, 0.0);
    work_of_block = external_work_of_block_.data();
  }
  const Drift d = reduce_ranges(
      n, kParallelMinParticles, Drift{},
      [&](int begin, int end) {
        // Raw pointers and whole-vector expressions: through the std::vectors the compiler kept
        // reloading their data pointers and called Eigen's assignment loops out of line (9% of a step).
        // The step's constants as locals: captured by reference, they were reloaded at every particle.
        const double step = dt, half_step = half_dt, too_fast2_over_r2 = reach2_over_dt2;
        double* __restrict external_work = work_of_block;
        Vec3* __restrict kick = state_.half_kick.data();
        Vec3* __restrict spin_kick = state_.spin_kick.data();
        Vec3* __restrict x = p.x.data();
        Vec3* __restrict v = p.v.data();
        Vec3* __restrict w = p.w.data();
        const Vec3* __restrict f = p.f.data();
        const Vec3* __restrict t = p.t.data();
        const Vec3* __restrict x0 = x_at_build_.data();
        const double* __restrict inv_mass = p.inv_mass.data();
        const double* __restrict inv_inertia = p.inv_inertia.data();
        Quat* __restrict q = p.q.empty() ? nullptr : p.q.data();
        const Vec3* __restrict external = p.external.empty() ? nullptr : p.external.data();
        const double* __restrict radius = p.radius.data();
        // the results in locals, not in `out` (returned in the caller's memory: stored at every particle)
        double moved2 = 0;
        bool too_fast = false;
        for (int i = begin; i < end; ++i) {
          const Vec3 k = (half_step * inv_mass[i]) * f[i];
          kick[i] = k;
          const Vec3 vi = v[i] + k;
          v[i] = vi;
          const Vec3 sk = (half_step * inv_inertia[i]) * t[i];
          spin_kick[i] = sk;
          const Vec3 wi = w[i] + sk;
          w[i] = wi;
          const Vec3 xi = x[i] + step * vi;
          x[i] = xi;
          // the orientation turns with the half-step spin, as the position moves with the half-step velocity
          if (q) q[i] = (rotation_by(step * wi) * q[i]).normalized();
          if (external && inv_mass[i] > 0) external_work[i / kParticleBlock] += step * external[i].dot(vi);
          moved2 = std::max(moved2, (xi - x0[i]).squaredNorm());
          const bool this_too_fast = vi.squaredNorm() > too_fast2_over_r2 * radius[i] * radius[i];
          too_fast = too_fast | this_too_fast;  // no branch
        }
        return Drift{moved2, too_fast};
      },
      [](const Drift& a, const Drift& b) {
        return Drift{std::max(a.moved2, b.moved2), a.too_fast || b.too_fast};
      },
      kParticleBlock);
  moved_too_far_ = d.too_fast;
  if (!p.external.empty()) {
    double external_work = 0;
    for (const double work : external_work_of_block_) external_work += work;
    add_work(ledger_.external, external_work);
  }
  return d.moved2;
}

void Simulation::build_neighbors() {
  Particles& p = state_.particles;
  std::vector<int> order;
  const int reorder = scene_.numerics.reorder_interval;
  if (reorder > 0 && builds_ % reorder == 0 && p.size() > 0) {
    const PhaseTimer timer(state_.profile, Phase::sort);
    const double r_max = *std::max_element(p.radius.begin(), p.radius.end());
    order = spatial_order(p, 2 * r_max + skin_);
    bool identity = true;
    for (std::size_t k = 0; k < order.size() && identity; ++k) identity = order[k] == static_cast<int>(k);
    if (identity) {
      order.clear();
    } else {
      p.permute(order);
      permute_array(state_.half_kick, order);  // this step's kicks, already taken, feed the prediction
      permute_array(state_.spin_kick, order);
      state_.bonds.renumber(order);
      if (!state_.bodies.empty()) index_members(state_.bodies, p);
    }
  }
  const PhaseTimer timer(state_.profile, Phase::rebuild);
  ++builds_;
  NeighborList next;
  try {
    build_neighbor_list(p, {skin_, kernel_->has_rolling_spring()}, state_.neighbors, order, next);
  } catch (const CrowdedError& e) {
    if (step_ == 0 && builds_ == 1) throw SceneError(std::string("particles: ") + e.what());  // the scene as given
    throw InstabilityError("unstable at step " + std::to_string(step_) + ": " + e.what() +
                           "; likely cause: the contact stiffness is too low for the load, or the time step too large");
  }
  state_.neighbors = std::move(next);
  const std::size_t pairs = state_.neighbors.pair_count();
  PairResults& r = state_.pairs;
  r.fn.assign(pairs, 0.0);
  r.ft_squared.assign(pairs, 0.0);
  r.touching.assign(pairs, 0);
  plan_blocks();
  WallContacts previous = std::move(state_.wall_contacts);
  build_wall_contacts(previous, order);
  build_mesh_contacts(order);
  growth_at_build_ = growth_scale_;
  boundaries_.mark_build();
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
  b.owner.resize(nl.pair_count());
  b.target.resize(nl.pair_count());
  std::vector<int> fill(b.deferred_start.begin(), b.deferred_start.end() - 1);
  for (int i = 0; i < n; ++i)
    for (int k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
      const int j = nl.partner[k];
      b.owner[k] = i;
      b.target[k] = crosses(i, j) ? n + fill[j]++ : j;
    }
  b.sums.assign(n + b.deferred_start[n], BodySums{});
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
      if (!boundaries_.present(boundaries_.of_plane(w)) || state_.walls[w].distance(p.x[i]) >= p.radius[i] + skin_)
        continue;
      Vec3 shear = Vec3::Zero(), roll = Vec3::Zero();
      std::uint8_t touching = 0;  // at the last force evaluation (the force loop's first and last steps)
      if (!previous.row_start.empty()) {
        for (int e = previous.row_start[old]; e < previous.row_start[old + 1]; ++e) {
          if (previous.wall[e] != w) continue;
          shear = previous.shear[e];
          if (keep_roll) roll = previous.roll[e];
          if (!previous.touching.empty()) touching = previous.touching[e];
        }
      }
      wc.wall.push_back(w);
      wc.constants.push_back(wall_constants(p, i));
      wc.shear.push_back(shear);
      wc.touching.push_back(touching);
      if (keep_roll) wc.roll.push_back(roll);
    }
    wc.row_start[i + 1] = static_cast<int>(wc.wall.size());
  }
  wc.fn.assign(wc.wall.size(), 0.0);
  wc.ft.assign(wc.wall.size(), 0.0);
  wc.kn.assign(wc.wall.size(), 0.0);
  wc.cn.assign(wc.wall.size(), 0.0);
  wc.force.assign(wc.wall.size(), Vec3::Zero());
  wc.point.assign(wc.wall.size(), Vec3::Zero());
}

void Simulation::build_mesh_contacts(const std::vector<int>& new_to_old) {
  MeshContacts& mc = state_.mesh_contacts;
  const Particles& p = state_.particles;
  const int n = static_cast<int>(p.size());
  if (state_.meshes.empty()) return;
  constexpr int kSlots = MeshContacts::kSlots;
  if (!new_to_old.empty() && !mc.slots.empty()) {  // the slots follow their particles
    std::vector<MeshSlot> moved(mc.slots.size());
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < kSlots; ++k)
        moved[static_cast<std::size_t>(i) * kSlots + k] =
            mc.slots[static_cast<std::size_t>(new_to_old[i]) * kSlots + k];
    mc.slots.swap(moved);
    permute_array(mc.used, new_to_old);
  }
  mc.used.resize(n, 0);
  mc.parted.assign(n, MeshParting{});
  mc.slots.resize(static_cast<std::size_t>(n) * kSlots);  // new slots are empty (mesh = -1)
  mc.constants.resize(n);
  for (int i = 0; i < n; ++i) mc.constants[i] = wall_constants(p, i);
  // (a run that starts empty bins its meshes for the particles its sources will insert)
  const double r_max =
      std::max(largest_given_radius_, n > 0 ? *std::max_element(p.radius.begin(), p.radius.end()) : 0.0);
  for (MeshWall& mesh : state_.meshes) {
    if (!mesh.grid_stale || !boundaries_.present(mesh.boundary)) continue;
    mesh.grid.build(mesh.vertices, mesh.triangles, 2 * r_max + skin_);
    mesh.grid_stale = false;
  }
  // Candidates per particle in fixed blocks (any thread count gives the same rows), then joined.
  constexpr int kBlock = 512;
  const int blocks = (n + kBlock - 1) / kBlock;
  std::vector<std::vector<std::array<int, 3>>> found(blocks);  // (particle, mesh, triangle)
#pragma omp parallel for schedule(dynamic) if (n >= kParallelMinParticles)
  for (int b = 0; b < blocks; ++b) {
    std::vector<int> near;
    std::vector<std::pair<double, int>> within;  // (squared distance, triangle): nearest first
    for (int i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) {
      const double reach = p.radius[i] + skin_;
      const Vec3 lo = p.x[i] - Vec3::Constant(reach), hi = p.x[i] + Vec3::Constant(reach);
      for (int m = 0; m < static_cast<int>(state_.meshes.size()); ++m) {
        const MeshWall& mesh = state_.meshes[m];
        if (!boundaries_.present(mesh.boundary)) continue;
        near.clear();
        mesh.grid.for_each_in_box(lo, hi, [&](int t) { near.push_back(t); });
        std::sort(near.begin(), near.end());
        near.erase(std::unique(near.begin(), near.end()), near.end());
        within.clear();
        for (int t : near) {
          const auto& tri = mesh.triangles[t];
          const Vec3 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]], &c = mesh.vertices[tri[2]];
          // the cell held it, but its box may still miss the sphere's: cheaper than the closest point
          if ((a.cwiseMin(b).cwiseMin(c).array() > hi.array()).any() ||
              (a.cwiseMax(b).cwiseMax(c).array() < lo.array()).any())
            continue;
          const Vec3 q = closest_on_triangle(p.x[i], a, b, c).point;
          const double d2 = (p.x[i] - q).squaredNorm();
          if (d2 < reach * reach) within.emplace_back(d2, t);
        }
        std::sort(within.begin(), within.end());
        for (const auto& [d2, t] : within) found[b].push_back({i, m, t});
      }
    }
  }
  mc.row_start.assign(n + 1, 0);
  mc.mesh.clear();
  mc.triangle.clear();
  for (const auto& block : found)
    for (const auto& [i, m, t] : block) {
      ++mc.row_start[i + 1];
      mc.mesh.push_back(m);
      mc.triangle.push_back(t);
    }
  for (int i = 0; i < n; ++i) mc.row_start[i + 1] += mc.row_start[i];
  // Nothing within reach: the slots still in use are emptied now, as the force loop would empty them
  // (add_mesh_forces), which then passes every particle by.
  if (mc.none_near())
    for (int i = 0; i < n; ++i)
      if (mc.used[i]) {
        mc.slot(i, 0).mesh = -1;
        mc.used[i] = 0;
      }
}

double Simulation::kinetic_energy() const {
  const Particles& p = state_.particles;
  double e = bodies_kinetic_energy(state_.bodies);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.body.empty() && p.body[i] >= 0) continue;  // counted with its body
    e += particle_kinetic_energy(i);
  }
  return e;
}

double Simulation::particle_kinetic_energy(std::size_t i) const {
  const Particles& p = state_.particles;
  const double k = scene_.grain().inertia_factor();
  return 0.5 * p.mass[i] * (p.v[i].squaredNorm() + k * p.radius[i] * p.radius[i] * p.w[i].squaredNorm());
}

double Simulation::rotational_energy() const {
  const Particles& p = state_.particles;
  double e = bodies_rotational_energy(state_.bodies);
  const double k = scene_.grain().inertia_factor();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.body.empty() && p.body[i] >= 0) continue;  // counted with its body
    e += 0.5 * p.mass[i] * k * p.radius[i] * p.radius[i] * p.w[i].squaredNorm();
  }
  return e;
}

double Simulation::translational_energy() const {
  const Particles& p = state_.particles;
  double e = bodies_translational_energy(state_.bodies);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.body.empty() && p.body[i] >= 0) continue;  // counted with its body
    e += 0.5 * p.mass[i] * p.v[i].squaredNorm();
  }
  return e;
}

double Simulation::gravitational_energy() const {
  const Particles& p = state_.particles;
  double e = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.body.empty() || p.body[i] < 0) e -= p.mass[i] * state_.gravity.dot(p.x[i]);
  const ClumpBodies& b = state_.bodies;
  for (std::size_t k = 0; k < b.size(); ++k) e -= b.mass[k] * state_.gravity.dot(b.x[k]);
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
  const MeshContacts& mc = state_.mesh_contacts;
  for (std::size_t i = 0; i < p.size(); ++i) count[i] += mc.count(static_cast<int>(i));
  return count;
}

std::vector<int> Simulation::fragments() const {
  const Particles& p = state_.particles;
  if (!state_.bonds.empty()) return state_.bonds.fragments(p.id, p.body);  // a clump is one piece among them
  std::vector<int> part(p.size(), 0);
  if (!p.body.empty())  // a clump's members are its part: the clump's number from 1
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.body[i] >= 0) part[i] = p.body[i] + 1;
  return part;
}

std::vector<WallContact> Simulation::wall_contacts() const {
  std::vector<WallContact> out;
  const WallContacts& wc = state_.wall_contacts;
  const MeshContacts& mc = state_.mesh_contacts;
  for (int i = 0; i < static_cast<int>(state_.particles.size()); ++i) {
    std::vector<WallContact> mine;
    if (!wc.row_start.empty())
      for (int e = wc.row_start[i]; e < wc.row_start[i + 1]; ++e)
        if (wc.touching[e]) mine.push_back({i, boundaries_.of_plane(wc.wall[e]), wc.fn[e], wc.ft[e]});
    for (int k = 0, used = mc.count(i); k < used; ++k)
      mine.push_back({i, state_.meshes[mc.slot(i, k).mesh].boundary, mc.slot(i, k).fn, mc.slot(i, k).ft});
    std::stable_sort(mine.begin(), mine.end(),
                     [](const WallContact& a, const WallContact& b) { return a.wall < b.wall; });
    out.insert(out.end(), mine.begin(), mine.end());
  }
  return out;
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

// ---- stages (Scene::stages) ----

const std::string& Simulation::stage_name() const {
  static const std::string none;
  return scene_.stages.empty() ? none : scene_.stages[stage_].name;
}

std::int64_t Simulation::stage_steps(int k) const {
  const Stage& stage = scene_.stages[k];
  if (stage.steps > 0) return stage.steps;
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(stage.duration / state_.dt - 1e-9)));
}

void Simulation::recount_total_steps() {
  total_steps_ = stage_end_step_;
  for (int k = stage_ + 1; k < static_cast<int>(scene_.stages.size()); ++k) total_steps_ += stage_steps(k);
}

void Simulation::update_stage() {
  if (scene_.stages.empty()) return;
  if (step_ >= stage_end_step_ && stage_ + 1 < static_cast<int>(scene_.stages.size())) enter_stage(stage_ + 1);
  if (step_ + 1 < stage_end_step_ && stage_end_condition_holds()) {
    stage_end_step_ = step_ + 1;
    stage_ended_early_ = true;
    recount_total_steps();
  }
}

bool Simulation::stage_end_condition_holds() const {
  const Stage& stage = scene_.stages[stage_];
  if (!stage.ends_early()) return false;
  const std::int64_t wait =
      stage.min_duration >= 0 ? std::llround(stage.min_duration / state_.dt) : stage_steps(stage_) / 10;
  if (step_ - stage_start_step_ < wait) return false;
  if (stage.until_kinetic_energy > 0 && kinetic_energy() < stage.until_kinetic_energy) return true;
  return stage.until_wall >= 0 && boundary_loads_[stage.until_wall].force.norm() >= stage.until_wall_force;
}

void Simulation::plan_stage_growth(int k) {
  growth_plan_.reset();
  const Stage& stage = scene_.stages[k];
  if (stage.growth_factor == 1) return;
  double from = 1;  // the stages before grew to this (each runs its whole length: none ends early)
  for (int j = 0; j < k; ++j) from *= scene_.stages[j].growth_factor;
  growth_plan_ = GrowthPlan{from, from * stage.growth_factor, stage_start_step_, stage_end_step_ - stage_start_step_};
}

double Simulation::growth_scale_at(std::int64_t step) const {
  double scale = 1;
  for (int j = 0; j < stage_ && j < static_cast<int>(scene_.stages.size()); ++j)
    scale *= scene_.stages[j].growth_factor;
  if (!growth_plan_ || growth_plan_->steps <= 0) return scale;
  const GrowthPlan& g = *growth_plan_;
  if (step < g.start) return g.from;
  const double share = std::min(1.0, static_cast<double>(step - g.start) / static_cast<double>(g.steps));
  return g.from + (g.to - g.from) * share;
}

void Simulation::apply_stage_settings(int k, bool restore) {
  Vec3 gravity = scene_.gravity;
  double damping = scene_.numerics.local_damping;
  const std::vector<Interaction>* table = nullptr;  // nullptr: the scene's own
  for (int j = 0; j <= k; ++j) {
    const Stage& stage = scene_.stages[j];
    if (stage.gravity) gravity = *stage.gravity;
    if (stage.local_damping) damping = *stage.local_damping;
    if (stage.interactions) table = &*stage.interactions;
  }
  state_.gravity = gravity;
  state_.local_damping = damping;
  if (scene_.stages[k].interactions || (restore && table)) {
    // the force loop holds its own table of the pairs' coefficients (contact/pair_table.hpp)
    std::vector<Interaction> own = std::move(scene_.interactions);
    scene_.interactions = *table;
    kernel_ = select_(scene_, !scene_.walls.empty());
    scene_.interactions = std::move(own);
  }
  const double now = time();
  for (std::size_t w = 0; w < scene_.walls.size(); ++w) {
    const bool there = scene_.walls[w].present_at(k);
    if (there && !boundaries_.present(static_cast<int>(w)) && !restore)
      boundaries_.driver(static_cast<int>(w)).start_clock(now);  // a wall come now
    boundaries_.set_present(static_cast<int>(w), there);
  }
  for (int w = 0; w < boundaries_.size(); ++w) boundaries_.driver(w).set_gravity(gravity);
  if (!restore) {
    for (const WallChange& c : scene_.stages[k].wall_changes)
      boundaries_.driver(c.wall).change(c.motion, c.load, now, gravity);
    return;
  }
  // every wall's motion and load as stage k has them, for StateIO to compare with the saved ones
  for (std::size_t w = 0; w < scene_.walls.size(); ++w)
    for (int j = k; j >= 0; --j) {
      const auto& changes = scene_.stages[j].wall_changes;
      const auto c = std::find_if(changes.begin(), changes.end(),
                                  [&](const WallChange& change) { return change.wall == static_cast<int>(w); });
      if (c == changes.end()) continue;
      boundaries_.driver(static_cast<int>(w)).change(c->motion, c->load, 0, gravity);
      break;
    }
}

void Simulation::restore_stage(int k, std::int64_t start, std::int64_t end, bool ended_early) {
  stage_ = k;
  stage_start_step_ = start;
  stage_end_step_ = end;
  stage_ended_early_ = ended_early;
  apply_stage_settings(k, /*restore=*/true);
  plan_stage_growth(k);
  recount_total_steps();
}

void Simulation::glue_bonds() {
  std::vector<int> stone;  // breakable stones glue only inside themselves
  for (const ParticleInit& p : scene_.particles) stone.push_back(p.stone);
  state_.bonds = BondSet(*scene_.bonds, state_.particles, state_.neighbors, stone);
  // Only bonds read the orientations, and no later stage glues any (one stage at most does): a bonds
  // block that glued nothing no longer turns every sphere every step (a sincos each; bench/unused).
  if (state_.bonds.empty()) state_.particles.q.clear();
}

// A mesh gone at a stage's start leaves no contact behind: its slots are emptied, the others kept
// in order (the first slots in use, as MeshContacts wants them).
void Simulation::drop_slots_of_absent_meshes() {
  MeshContacts& mc = state_.mesh_contacts;
  constexpr int kSlots = MeshContacts::kSlots;
  for (std::size_t i = 0; i < mc.used.size(); ++i) {
    if (!mc.used[i]) continue;
    int kept = 0;
    for (int k = 0; k < kSlots; ++k) {
      const MeshSlot slot = mc.slots[i * kSlots + k];
      if (slot.mesh >= 0 && boundaries_.present(state_.meshes[slot.mesh].boundary))
        mc.slots[i * kSlots + kept++] = slot;
    }
    for (int k = kept; k < kSlots; ++k) mc.slots[i * kSlots + k] = MeshSlot{};
    mc.used[i] = kept > 0;
  }
}

void Simulation::enter_stage(int k) {
  const double before = mechanical_energy();
  stage_ = k;
  stage_start_step_ = step_;
  stage_end_step_ = step_ + stage_steps(k);
  stage_ended_early_ = false;
  apply_stage_settings(k, /*restore=*/false);
  plan_stage_growth(k);
  drop_slots_of_absent_meshes();
  build_neighbors();  // without the walls gone, with the walls come
  if (scene_.stages[k].glue_bonds && scene_.bonds) glue_bonds();
  // Forces anew, as at t = 0 (a zero step leaves history and velocities unchanged): a wall gone
  // pushes no more, a new gravity pulls from the stage's first half kick.
  // The last step's kicks are spent: the force loop's prediction of the velocities at the step's
  // end must not add them again (and a saved state does not hold the spin's).
  std::fill(state_.half_kick.begin(), state_.half_kick.end(), Vec3::Zero());
  std::fill(state_.spin_kick.begin(), state_.spin_kick.end(), Vec3::Zero());
  const double dt = state_.dt, now = time();  // time() is step * dt: taken before dt is set to 0
  state_.dt = 0;
  compute_forces_and_kick();
  settle_walls(now, 0);
  state_.dt = dt;
  add_work(ledger_.stages, mechanical_energy() - before);
  recount_total_steps();
}

double Simulation::source_active_time(int k) const {
  const ParticleSource& source = scene_.sources[k];
  const std::int64_t from = source.stage >= 0 ? stage_start_step_ : 0;
  return static_cast<double>(step_ + 1 - from) * state_.dt - source.start;
}

bool Simulation::feed_sources() {
  bool any = false;
  for (int k = 0; k < static_cast<int>(scene_.sources.size()); ++k) {
    const ParticleSource& source = scene_.sources[k];
    if (source.stage >= 0 && source.stage != stage_) continue;
    const double since = source_active_time(k);
    SourceProgress& progress = source_progress_[k];
    const std::int64_t every = std::max<std::int64_t>(1, source.every_steps);
    if (since <= 0 || (progress.last_attempt >= 0 && step_ + 1 - progress.last_attempt < every)) continue;
    progress.last_attempt = step_ + 1;
    // the next particle's size, drawn once (a generator seeded anew each time: most of what a step
    // with nothing due cost, a done source's included)
    auto& [index, radius] = next_source_radius_[k];
    if (index != progress.inserted) {
      index = progress.inserted;
      radius = source_radius(source, index);
    }
    const std::vector<ParticleInit> due = due_particles(
        scene_, source, progress, radius, std::min(since, source.end - source.start), state_.particles,
        [&] { return boundaries_.faces(source.face_wall, state_.walls, state_.meshes); },
        [this](const Vec3& x, double r) { return boundaries_.touches(x, r, state_.walls, state_.meshes); });
    double energy = 0;  // what the new particles bring: their kinetic and gravitational energy
    for (ParticleInit init : due) {
      init.source = k;
      append_particle(init);
      // It enters after the step's drift, and the step's second half kick is still to come: it takes
      // the first half kick back (it touches nothing, so its force is its weight), and so ends the
      // step at the source's velocity, with the energy counted here.
      const Vec3 half_kick = 0.5 * state_.dt * state_.gravity;
      state_.particles.v.back() -= half_kick;
      state_.half_kick.back() = half_kick;
      const double m = state_.particles.mass.back();
      energy += 0.5 * m * init.velocity.squaredNorm() - m * state_.gravity.dot(init.position);
    }
    if (!due.empty()) add_work(ledger_.sources, energy);
    any = any || !due.empty();
  }
  return any;
}

void Simulation::append_particle(const ParticleInit& init) {
  Particles& p = state_.particles;
  const double r = init.radius;
  const Grain grain = scene_.grain();
  const double m = grain.mass(scene_.materials[init.material].density, r);
  ParticleInit given = init;
  given.radius = r / growth_scale_;  // a growth scales the given sizes: this one is r now
  scene_.particles.push_back(given);
  p.x.push_back(init.position);
  p.v.push_back(init.velocity);
  p.w.push_back(init.angular_velocity);
  p.f.push_back(Vec3::Zero());
  p.t.push_back(Vec3::Zero());
  p.radius.push_back(r);
  p.mass.push_back(m);
  p.inv_mass.push_back(1 / m);
  p.inv_inertia.push_back(1 / grain.inertia(m, r));
  p.material.push_back(init.material);
  p.id.push_back(static_cast<int>(scene_.particles.size()) - 1);
  if (!p.external.empty()) p.external.push_back(Vec3::Zero());
  if (!p.body.empty()) {
    p.body.push_back(-1);
    p.body_offset.push_back(Vec3::Zero());
  }
  if (!p.q.empty()) p.q.push_back(Quat::Identity());
  state_.f_next.push_back(Vec3::Zero());
  state_.half_kick.push_back(Vec3::Zero());
  state_.spin_kick.push_back(Vec3::Zero());
  x_at_build_.push_back(init.position);
  // no history: the rows of the lists and slots end where they did (the next build fills them)
  NeighborList& nl = state_.neighbors;
  if (!nl.row_start.empty()) nl.row_start.push_back(nl.row_start.back());
  WallContacts& wc = state_.wall_contacts;
  if (!wc.row_start.empty()) wc.row_start.push_back(wc.row_start.back());
  MeshContacts& mc = state_.mesh_contacts;
  if (!state_.meshes.empty()) {
    mc.used.resize(p.size(), 0);
    mc.slots.resize(p.size() * MeshContacts::kSlots);
    if (!mc.row_start.empty()) mc.row_start.push_back(mc.row_start.back());
  }
}

}  // namespace dem
