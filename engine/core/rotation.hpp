// Rotations as rotation vectors (axis times angle) and back: a particle's orientation follows its
// spin, q(n+1) = exp(w dt) q(n), and a bond measures the relative rotation of its two particles.
#pragma once

#include <cmath>

#include "core/vec.hpp"

namespace dem {

// The rotation by |v| about v / |v| (exact for any angle; the identity for v = 0).
inline Quat rotation_by(const Vec3& v) {
  const double angle = v.norm();
  if (angle == 0) return Quat::Identity();
  const double half = 0.5 * angle;
  const Vec3 axis = (std::sin(half) / angle) * v;
  return Quat(std::cos(half), axis.x(), axis.y(), axis.z());
}

// The rotation vector of q, with its angle in [0, pi].
inline Vec3 rotation_vector(const Quat& q) {
  const double sign = q.w() < 0 ? -1.0 : 1.0;  // q and -q are the same rotation: take the shorter way
  const Vec3 v = sign * q.vec();
  const double s = v.norm(), c = sign * q.w();
  if (s == 0) return Vec3::Zero();
  return (2 * std::atan2(s, c) / s) * v;
}

}  // namespace dem
