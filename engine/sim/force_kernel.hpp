// The force loop, written once and instantiated per contact law (sim/kernel_select.hpp picks one).
#pragma once

#include <memory>

#include "core/scene.hpp"
#include "sim/state.hpp"

namespace dem {

struct ContactSummary {
  double max_overlap_fraction = 0;  // overlap / smaller radius
  int worst_particle = -1;          // index of the particle with that overlap
  int worst_partner = -1;           // index of the other particle of that contact (-1: a wall)
  double elastic_energy = 0;        // stored in the normal springs
  std::size_t contacts = 0;
  // The fastest the bodies of one contact would part if its stored energy all went into their
  // relative motion, sqrt(2 U / m*): the speed a release from an initial overlap reaches.
  double release_speed = 0;
};

class ForceKernel {
 public:
  virtual ~ForceKernel() = default;
  // Computes forces and torques of every particle from the current positions and velocities,
  // updating the contact history, then completes the velocity update (the second half kick).
  virtual void compute_and_kick(SimState& state) = 0;
  // Overlaps and stored elastic energy of the current contacts, for the stability guard.
  virtual ContactSummary summarize(const SimState& state) const = 0;
  // The elastic energy the contacts would store at the current positions with these radii (one per
  // particle; a mesh contact's overlap, kept from the last force loop, changes by the radius's
  // change): what growing the radii puts in.
  virtual double elastic_energy(const SimState& state, const std::vector<double>& radius) const = 0;
  virtual bool has_rolling_spring() const = 0;

  // What the time step needs of the normal model (sim/time_step.cpp), for materials a and b: the
  // contact time of a pair of reduced mass m_eff and radius r_eff meeting at `speed` (used only
  // when contact_time_needs_speed()), and a material's own time limit for its smallest sphere
  // (Hertz: the Rayleigh time; infinite for a law without one).
  virtual double contact_time(int a, int b, double m_eff, double r_eff, double speed) const = 0;
  virtual bool contact_time_needs_speed() const = 0;
  virtual double wave_time(const Material& m, double r_min) const = 0;
};

// Sphere pairs are evaluated four at a time with AVX2 where the CPU has it (x86-64), else one at a
// time; both give identical bits. set_pair_lanes(1) forces the one-at-a-time loop (for tests and
// comparisons); asking for 4 where AVX2 is missing throws.
#if defined(__x86_64__) && defined(__GNUC__)
#define DEM_HAS_AVX2_LANES 1
#else
#define DEM_HAS_AVX2_LANES 0
#endif
int pair_lanes();
void set_pair_lanes(int lanes);

}  // namespace dem
