// BallastDEM's stones, as rigid clumps or as breakable bonded agglomerates (its section 4.1):
// masses from a lognormal distribution bounded to [mass_min, mass_max], irregular shapes of a few
// to about 20 overlapping spheres, random orientations, placed without overlap in a box (to be
// settled under gravity by the run). Reproducible from the seed.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "core/scene.hpp"

namespace dem::spec {

struct StoneRequest {
  int count = 0;
  double log_mean = 0;                // mean of ln(mass / 1 kg)
  double log_sigma = 0;               // standard deviation of ln(mass / 1 kg)
  double mass_min = 0, mass_max = 0;  // kg
  int min_spheres = 3, max_spheres = 12;
  int shapes = 32;  // distinct shapes the stones are drawn from (each scaled to its stone's mass)
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  int material = 0;
  double density = 0;
  std::uint32_t seed = 1;
  double bonded_sphere_radius = 0;  // > 0: breakable stones filled with bonded spheres of this radius
};

// Masses of `count` stones: ln m ~ N(log_mean, log_sigma), redrawn when outside [mass_min, mass_max].
std::vector<double> sample_stone_masses(const StoneRequest& r, std::mt19937_64& rng);

// Appends the stones to the scene (after its particles): as clumps, or, breakable, as spheres that
// share a ParticleInit::stone number (the scene's bonds glue them). Throws std::runtime_error
// saying how many fitted when the box is too small, or when a stone cannot hold 2 spheres.
void add_ballast_stones(const StoneRequest& r, Scene& scene);

}  // namespace dem::spec
