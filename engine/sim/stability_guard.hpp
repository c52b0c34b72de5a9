// Stops a run that has gone unstable, with a message a user can act on: a NaN, an overlap beyond a
// fraction of the radius, or mechanical energy growing with nothing to feed it.
#pragma once

#include "sim/simulation.hpp"

namespace dem {

class StabilityGuard {
 public:
  explicit StabilityGuard(const Simulation& sim);
  // Throws InstabilityError naming the step, the particle (its scene id, 1-based as in the files)
  // and the likely cause.
  void check(const Simulation& sim) const;
  // Every step (cheap): a blow-up the last step started, named where and when it started.
  void check_finite(const Simulation& sim) const;
  // Before anything is written (a frame, a saved state): every number the files take from the
  // state is finite; a blow-up never reaches them.
  void check_writable(const Simulation& sim) const;

 private:
  double mechanical_energy(const Simulation& sim, const ContactSummary& contacts) const;

  double initial_energy_ = 0;
  double energy_scale_ = 0;
  EnergyLedger input_at_start_;
  // The lowest the energy less the work its sources fed in has been at a check: energy made after
  // much was lost is made all the same.
  mutable double lowest_balance_ = 0;
};

}  // namespace dem
