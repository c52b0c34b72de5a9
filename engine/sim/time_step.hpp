// The time step: chosen from the scene's stiffest, lightest contact unless given, and checked.
#pragma once

#include <string>

#include "core/scene.hpp"
#include "sim/force_kernel.hpp"

namespace dem {

struct TimeStepReport {
  double dt = 0;
  bool automatic = true;
  double contact_time = 0;     // shortest binary contact time (the normal model's: linear eq. 7, Hertz at v_ref)
  double rayleigh_time = 0;    // the normal model's wave time when it has one (Hertz: the Rayleigh time), else 0
  double reference_speed = 0;  // impact speed the contact time is taken at (a law whose time depends on it)
  double bond_time = 0;        // bonded scenes: shortest half-period of a bond's springs (0 without bonds)
  double stable_limit = 0;     // largest dt accepted without allow_unstable_dt
  std::string describe() const;
};

// Throws SceneError when a given dt exceeds the stable limit and the scene does not allow it.
// The contact times come from the scene's normal model, through its force kernel; the bonds' periods
// count when `bonded` (some bond was made). `release_speed`: the fastest the initial contacts' stored
// energy would part their bodies (ContactSummary::release_speed), an impact speed like the others.
TimeStepReport choose_time_step(const Scene& scene, const ForceKernel& kernel, bool bonded = true,
                                double release_speed = 0);

// The fastest a wall's prescribed motion (or servo load) moves a point of it, or the point where it
// meets a particle: its centre's speed plus its spin times the farthest of its corners, vertices
// and the particles from its rotation centre; at least a servo's speed limit.
double fastest_wall_speed(const Scene& scene, const WallInit& wall);

}  // namespace dem
