// Cundall's local damping (Cundall 1987, "Distinct element models of rock and soil structure"; PFC's
// local damping): each component of a force loses alpha times its size against the same component of
// the velocity, and nothing where that component is 0.
#pragma once

#include <cmath>

#include "core/vec.hpp"

namespace dem {

// Without a branch: the velocities' signs are as good as random, and the six branches a sphere took
// (force and torque) were mispredicted about half the time. For a finite force the bits are those of
// `if (v != 0) f -= alpha |f| sign(v)`: a zero direction subtracts +0, which leaves any f as it was.
inline void damp_locally(Vec3& force, const Vec3& velocity, double alpha) {
  for (int d = 0; d < 3; ++d) {
    const double direction = static_cast<double>((velocity[d] > 0) - (velocity[d] < 0));
    force[d] -= alpha * std::abs(force[d]) * direction;
  }
}

}  // namespace dem
