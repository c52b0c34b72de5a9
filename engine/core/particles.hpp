// Per-particle state, one contiguous array per quantity (the hot loops read a few of them at a time).
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "core/vec.hpp"

namespace dem {

// Below this many particles a step is too short to share between threads: the fork and join would
// cost more than they save (and oversubscribed machines make it far worse).
constexpr int kParallelMinParticles = 4096;

struct Particles {
  std::vector<Vec3> x;  // position
  std::vector<Vec3> v;  // velocity
  std::vector<Vec3> w;  // angular velocity
  std::vector<Vec3> f;  // force of the current step
  std::vector<Vec3> t;  // torque of the current step
  std::vector<double> radius;
  std::vector<double> mass;
  std::vector<double> inv_mass;     // 0 for a fixed particle
  std::vector<double> inv_inertia;  // 0 for a fixed particle
  std::vector<int> material;
  std::vector<int> id;         // index in the scene (files and observers use it)
  std::vector<Vec3> external;  // constant external force; empty when no particle has one
  // Members of rigid clumps (empty when the scene has none): the body, -1 for a free sphere, and
  // the member's centre in the body frame. A member's x, v and w are set from its body each step.
  std::vector<int> body;
  std::vector<Vec3> body_offset;
  // Orientation (body frame to space), integrated from the spin: only in scenes with bonds, which
  // measure their particles' relative rotation (empty otherwise).
  std::vector<Quat> q;

  std::size_t size() const { return x.size(); }

  // Reorders every array so that new index k holds old index new_to_old[k].
  void permute(const std::vector<int>& new_to_old);
};

// A solid sphere of radius r: its mass, and its moment of inertia about a diameter.
inline double sphere_mass(double density, double r) { return density * 4.0 / 3.0 * std::numbers::pi * r * r * r; }
inline double sphere_inertia(double m, double r) { return 0.4 * m * r * r; }

// What a particle is: a solid sphere, or in a 2D run (Scene::plane) a solid disc (a short cylinder) of
// the run's thickness lying in the x-z plane, which turns only about its axis (y).
struct Grain {
  double disc_thickness = 0;  // m; 0: spheres
  bool disc() const { return disc_thickness > 0; }
  double mass(double density, double r) const {
    return disc() ? density * std::numbers::pi * r * r * disc_thickness : sphere_mass(density, r);
  }
  // The moment of inertia over m r^2: about a diameter (a sphere, 2/5) or the disc's axis (1/2).
  double inertia_factor() const { return disc() ? 0.5 : 0.4; }
  double inertia(double m, double r) const { return inertia_factor() * m * r * r; }
};

// A particle's state is usable: its position, velocity and spin are finite and so are the squares
// the energies and files take of them (a speed past ~1e154 m/s overflows m v^2 before it overflows).
// The kick no longer asks it of every particle (it tests one sum a range, force_kernel_impl.hpp); the
// guard and Simulation::step ask it particle by particle when that sum or a frame needs it.
inline bool state_is_finite(const Vec3& x, const Vec3& v, const Vec3& w, double mass) {
  const bool x_finite = std::isfinite(x.squaredNorm());
  const bool v_finite = std::isfinite(mass * v.squaredNorm());
  const bool w_finite = std::isfinite(mass * w.squaredNorm());
  return x_finite & v_finite & w_finite;
}

// Applies new_to_old to one array (used for per-particle history kept outside Particles too).
template <class T>
void permute_array(std::vector<T>& values, const std::vector<int>& new_to_old) {
  std::vector<T> out(values.size());
  for (std::size_t k = 0; k < new_to_old.size(); ++k) out[k] = values[new_to_old[k]];
  values.swap(out);
}

inline void Particles::permute(const std::vector<int>& new_to_old) {
  permute_array(x, new_to_old);
  permute_array(v, new_to_old);
  permute_array(w, new_to_old);
  permute_array(f, new_to_old);
  permute_array(t, new_to_old);
  permute_array(radius, new_to_old);
  permute_array(mass, new_to_old);
  permute_array(inv_mass, new_to_old);
  permute_array(inv_inertia, new_to_old);
  permute_array(material, new_to_old);
  permute_array(id, new_to_old);
  if (!external.empty()) permute_array(external, new_to_old);
  if (!body.empty()) {
    permute_array(body, new_to_old);
    permute_array(body_offset, new_to_old);
  }
  if (!q.empty()) permute_array(q, new_to_old);
}

}  // namespace dem
