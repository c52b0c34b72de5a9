#include "sim/stability_guard.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "core/errors.hpp"

namespace dem {
namespace {

std::string where(const Simulation& sim, int index) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "at step %lld (t = %.6e s), particle %d", static_cast<long long>(sim.step_count()),
                sim.time(), sim.particles().id[index] + 1);
  return buf;
}

}  // namespace

StabilityGuard::StabilityGuard(const Simulation& sim) {
  const ContactSummary contacts = sim.contact_summary();
  initial_energy_ = mechanical_energy(sim, contacts);
  lowest_balance_ = initial_energy_;
  // What could legitimately move around: the kinetic and elastic energy now, and the potential
  // energy of a fall across the whole particle cloud.
  const Particles& p = sim.particles();
  double mass = 0;
  Vec3 lo = Vec3::Constant(1e300), hi = -lo;
  for (std::size_t i = 0; i < p.size(); ++i) {
    mass += p.mass[i];
    lo = lo.cwiseMin(p.x[i]);
    hi = hi.cwiseMax(p.x[i]);
  }
  const double height = p.size() > 0 ? (hi - lo).norm() + 2 * p.radius[0] : 0;
  energy_scale_ = sim.kinetic_energy() + contacts.elastic_energy + sim.bonds().elastic_energy() +
                  mass * sim.state().gravity.norm() * height;
  input_at_start_ = sim.energy_input();
}

double StabilityGuard::mechanical_energy(const Simulation& sim, const ContactSummary& contacts) const {
  // Simulation::mechanical_energy, with the contact summary the other checks already made
  return sim.kinetic_energy() + sim.gravitational_energy() + contacts.elastic_energy + sim.bonds().elastic_energy();
}

void StabilityGuard::check_finite(const Simulation& sim) const {
  if (const std::optional<TooFast>& fast = sim.first_too_fast(); fast && fast->wall >= 0) {
    char buf[480];
    std::snprintf(
        buf, sizeof buf,
        "unstable: wall %d (%s) moved %.3e m in one step at step %lld (t = %.6e s), more than %.3g of the "
        "smallest particle radius (%.3e m): it could pass through particles unseen; likely cause: its load "
        "drives it faster than the time step resolves (a servo's maxSpeed, or a cyclic load on a light wall; ",
        fast->wall + 1, sim.scene().walls[fast->wall].name.c_str(), fast->distance, static_cast<long long>(fast->step),
        fast->time, 0.5 * sim.scene().numerics.max_overlap_fraction, fast->radius);
    throw InstabilityError(buf + sim.time_step().describe() + ")");
  }
  if (const std::optional<TooFast>& fast = sim.first_too_fast()) {
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "unstable: particle %d moved %.3e m in one step at step %lld (t = %.6e s), more than %.3g of its "
                  "radius (%.3e m): it could pass through another particle or press into it past the overlap limit "
                  "unseen; likely cause: a speed far beyond what the time step resolves (",
                  fast->particle_id + 1, fast->distance, static_cast<long long>(fast->step), fast->time,
                  0.5 * sim.scene().numerics.max_overlap_fraction, fast->radius);
    throw InstabilityError(buf + sim.time_step().describe() + ")");
  }
  const std::optional<NonFinite>& bad = sim.first_non_finite();
  if (!bad) return;
  char buf[260];
  std::snprintf(buf, sizeof buf,
                "unstable: position or velocity is not a finite number (or overflows its energy) at step %lld "
                "(t = %.6e s), particle %d, "
                "where it started (%d particle%s went bad in that step)",
                static_cast<long long>(bad->step), bad->time, bad->particle_id + 1, bad->particles,
                bad->particles == 1 ? "" : "s");
  throw InstabilityError(buf + std::string("; likely cause: the time step is too large for the contact stiffness (") +
                         sim.time_step().describe() + ")");
}

void StabilityGuard::check_writable(const Simulation& sim) const {
  check_finite(sim);
  const Particles& p = sim.particles();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!state_is_finite(p.x[i], p.v[i], p.w[i], p.mass[i])) {
      throw InstabilityError("unstable: position or velocity is not a finite number (or overflows its energy) " +
                             where(sim, static_cast<int>(i)) +
                             "; likely cause: the time step is too large for the contact stiffness (" +
                             sim.time_step().describe() + ")");
    }
  }
  // finite states whose energies or wall loads overflow: the files would hold inf
  bool walls_finite = true;
  for (const BoundaryLoad& load : sim.boundary_loads())
    walls_finite = walls_finite && load.force.allFinite() && load.torque.allFinite();
  for (std::size_t k = 0; k < sim.scene().walls.size(); ++k) {
    const WallPose& pose = sim.wall_driver(static_cast<int>(k)).pose();
    walls_finite = walls_finite && pose.displacement.allFinite() && pose.rotation.allFinite();
  }
  // (Energy.dat holds the energies stored in the contacts and bonds too)
  const bool energies_finite = std::isfinite(sim.kinetic_energy()) && std::isfinite(sim.gravitational_energy()) &&
                               std::isfinite(sim.contact_summary().elastic_energy) &&
                               std::isfinite(sim.bonds().elastic_energy());
  if (!walls_finite || !energies_finite) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "unstable: %s overflowed at step %lld (t = %.6e s)",
                  walls_finite ? "the kinetic, potential or stored elastic energy" : "a wall's load or position",
                  static_cast<long long>(sim.step_count()), sim.time());
    throw InstabilityError(buf +
                           std::string("; likely cause: the time step is too large for the contact stiffness, "
                                       "or speeds or forces far beyond the scene's scale (") +
                           sim.time_step().describe() + ")");
  }
}

void StabilityGuard::check(const Simulation& sim) const {
  check_writable(sim);
  const Particles& p = sim.particles();
  const ContactSummary contacts = sim.contact_summary();
  const double limit = sim.scene().numerics.max_overlap_fraction;
  if (contacts.max_overlap_fraction > limit) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "unstable: overlap of %.3g times the radius (limit %.3g) ",
                  contacts.max_overlap_fraction, limit);
    const std::string partner = contacts.worst_partner >= 0 ? " (its contact with particle " +
                                                                  std::to_string(p.id[contacts.worst_partner] + 1) + ")"
                                                            : " (its contact with a wall)";
    if (sim.step_count() == 0)  // before any step: the overlap is where the particles were put
      throw InstabilityError(buf + where(sim, contacts.worst_particle) + partner +
                             " as placed, before the first step; likely cause: the scene's initial positions (move "
                             "them apart or make them smaller, or let them grow into place with growth)");
    const std::optional<Scene::Growth>& growth = sim.scene().growth;
    if (growth && growth->factor > 1 && sim.step_count() <= growth->steps) {  // still growing
      char why[320];
      std::snprintf(why, sizeof why,
                    "; likely cause: the radii grow too fast for the contacts to push the particles apart "
                    "(growth.factor %.6g over growth.steps %lld, now at step %lld; grow over more steps)",
                    growth->factor, static_cast<long long>(growth->steps), static_cast<long long>(sim.step_count()));
      throw InstabilityError(buf + where(sim, contacts.worst_particle) + partner + why);
    }
    if (!sim.scene().stages.empty() && sim.scene().stages[sim.stage()].growth_factor > 1) {  // a stage grows them
      const Stage& stage = sim.scene().stages[sim.stage()];
      char why[320];
      std::snprintf(why, sizeof why,
                    "; likely cause: the radii grow too fast for the contacts to push the particles apart "
                    "(stage \"%s\" grows them by %.6g over %lld steps; make it longer)",
                    stage.name.c_str(), stage.growth_factor,
                    static_cast<long long>(sim.stage_end_step() - sim.stage_start_step()));
      throw InstabilityError(buf + where(sim, contacts.worst_particle) + partner + why);
    }
    if (sim.stage() > 0 && sim.step_count() - sim.stage_start_step() <= 2) {
      // a wall a stage adds where particles already are cuts into them at its first step
      std::string added;
      for (const WallInit& wall : sim.scene().walls)
        if (wall.first_stage == sim.stage()) added += (added.empty() ? "\"" : ", \"") + wall.name + "\"";
      if (!added.empty())
        throw InstabilityError(buf + where(sim, contacts.worst_particle) + partner + " at the first step of stage \"" +
                               sim.scene().stages[sim.stage()].name + "\"; likely cause: the wall it adds (" + added +
                               ") cuts into the particles where they are: place it clear of them");
    }
    throw InstabilityError(buf + where(sim, contacts.worst_particle) + partner +
                           "; likely cause: the contact stiffness is too low for the load, or the time step "
                           "too large (" +
                           sim.time_step().describe() + ")");
  }
  // Damping and friction only take energy out; what walls, external forces and growth put in is
  // counted (Simulation::energy_input). Allow for integration error and unseen springs: 5% of the
  // energy that could legitimately move around, and of every joule fed in or taken out by sources.
  const EnergyLedger& input = sim.energy_input();
  const double fed = input.total() - input_at_start_.total();
  const double slack = 0.05 * (energy_scale_ + input.magnitude - input_at_start_.magnitude);
  const double energy = mechanical_energy(sim, contacts);
  lowest_balance_ = std::min(lowest_balance_, energy - fed);
  if (energy - fed > lowest_balance_ + slack + 1e-300) {
    // name the particle with the most kinetic energy, of translation and rotation: that is where the
    // energy went (by speed alone, a still, fixed sphere was named beside one spinning up)
    std::size_t liveliest = 0;
    double most = sim.particle_kinetic_energy(0);
    for (std::size_t i = 1; i < p.size(); ++i)
      if (const double e = sim.particle_kinetic_energy(i); e > most) most = e, liveliest = i;
    char buf[300];
    std::snprintf(buf, sizeof buf,
                  "unstable: mechanical energy grew from %.6e J to %.6e J, more than the %.6e J its sources fed in "
                  "(less that work it rose from its lowest, %.6e J, to %.6e J), ",
                  initial_energy_, energy, fed, lowest_balance_, energy - fed);
    throw InstabilityError(buf + where(sim, static_cast<int>(liveliest)) +
                           " (the one with the most kinetic energy); likely cause: the time step is too large for the "
                           "contact stiffness (" +
                           sim.time_step().describe() + ")");
  }
}

}  // namespace dem
