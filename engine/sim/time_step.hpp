// The time step: chosen from the scene's stiffest, lightest contact unless given, and checked.
#pragma once

#include <string>

#include "contact/pair_params.hpp"
#include "core/scene.hpp"

namespace dem {

struct TimeStepReport {
  double dt = 0;
  bool automatic = true;
  double contact_time = 0;   // shortest binary contact time (linear: seeds' eq. 7; Hertz: at v_ref)
  double rayleigh_time = 0;  // Hertz only: pi R sqrt(rho/G) / (0.1631 nu + 0.8766)
  double reference_speed = 0;  // Hertz only: impact speed the contact time is taken at
  double bond_time = 0;      // bonded scenes: shortest half-period of a bond's springs (0 without bonds)
  double stable_limit = 0;   // largest dt accepted without allow_unstable_dt
  std::string describe() const;
};

// Throws SceneError when a given dt exceeds the stable limit and the scene does not allow it.
TimeStepReport choose_time_step(const Scene& scene, const PairTable& table);

}  // namespace dem
