// Small scenes built in code for the physics tests, with the materials of validation.md.
#pragma once

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "core/scene.hpp"
#include "contact/models.hpp"
#include "sim/simulation.hpp"

namespace dem::test {

inline double sphere_mass(double density, double radius) {
  return density * 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
}

// A scene with one particle material "p" (index 0) and one rigid wall material "wall" (index 1).
inline Scene base_scene(std::string_view model, double density, double youngs, double poisson, double restitution,
                        double friction, double kn = 0) {
  Scene s;
  s.materials.push_back({"p", density, youngs, poisson, kn, false});
  s.materials.push_back({"wall", 0, 0, 0, 0, true});
  const Interaction in{restitution, friction, 0};
  s.interactions.assign(4, in);
  s.contact.normal = model;
  s.time.steps = 1;
  s.outputs.animation = false;
  return s;
}

inline void set_rolling(Scene& s, std::string_view model, double mu_r) {
  s.contact.rolling = model;
  for (Interaction& in : s.interactions) in.rolling_friction = mu_r;
}

inline ParticleInit sphere(const Vec3& x, double r, const Vec3& v = Vec3::Zero(), const Vec3& w = Vec3::Zero()) {
  ParticleInit p;
  p.position = x;
  p.radius = r;
  p.velocity = v;
  p.angular_velocity = w;
  p.material = 0;
  return p;
}

inline WallInit plane(const Vec3& point, const Vec3& normal, const std::string& name = "plane") {
  return WallInit{name, 1, PlaneShape{point, normal.normalized()}, {}, {}};
}

// An elastic gas: `side`^3 spheres of radius r on a lattice in a cube of edge `box` closed by six
// planes, each with a random velocity of components in (-1, 1) m/s drawn from `seed`.
inline void fill_gas_box(Scene& s, int side, double r, double box, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> speed(-1.0, 1.0);
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (int k = 0; k < side; ++k)
        s.particles.push_back(
            sphere(Vec3(i + 0.5, j + 0.5, k + 0.5) * (box / side), r, Vec3(speed(rng), speed(rng), speed(rng))));
  for (int d = 0; d < 3; ++d) {
    Vec3 n = Vec3::Zero();
    n[d] = 1;
    s.walls.push_back(plane(Vec3::Zero(), n));
    s.walls.push_back(plane(n * box, -n));
  }
}

// Runs until `done(sim)` or max_steps; returns the number of steps taken.
template <class Done>
std::int64_t step_until(Simulation& sim, std::int64_t max_steps, Done&& done) {
  std::int64_t k = 0;
  while (k < max_steps && !done(sim)) {
    sim.step();
    ++k;
  }
  return k;
}

}  // namespace dem::test
