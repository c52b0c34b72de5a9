// Energy conservation: an elastic, frictionless gas of spheres in a box of walls (e = 1, mu = 0)
// keeps its total energy (kinetic + elastic) within 1e-4 over 1e5 steps at the default time step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "support/scenes.hpp"

namespace dem::test {
namespace {

Scene elastic_gas(std::string_view model, std::uint32_t seed) {
  Scene s = base_scene(model, 2500, 1e8, 0.25, 1.0, 0.0, 1e4);
  // 200 steps per contact. Each contact's start and end (a kink in the force) leaves a small energy
  // error of random sign, which adds up as a random walk: over 1e5 steps the largest deviation was
  // 1.3e-4 at 50 steps per contact, 1.2e-4 at 100 and 1.4e-5 at 200 (docs/validation.md).
  s.time.dt_fraction = 0.005;
  const double r = 0.005, box = 0.1;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> speed(-1.0, 1.0);
  // 6 x 6 x 6 lattice with room between spheres, random velocities
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 6; ++k)
        s.particles.push_back(sphere(Vec3(i + 0.5, j + 0.5, k + 0.5) * (box / 6), r,
                                     Vec3(speed(rng), speed(rng), speed(rng))));
  for (int d = 0; d < 3; ++d) {
    Vec3 n = Vec3::Zero();
    n[d] = 1;
    s.walls.push_back(plane(Vec3::Zero(), n));
    s.walls.push_back(plane(n * box, -n));
  }
  return s;
}

class EnergyConservation : public ::testing::TestWithParam<std::string_view> {};

TEST_P(EnergyConservation, TotalEnergyWithinOneIn1e4Over1e5Steps) {
  Simulation sim(elastic_gas(GetParam(), 7));
  auto energy = [&] { return sim.kinetic_energy() + sim.contact_summary().elastic_energy; };
  const double e0 = energy();
  double worst = 0;
  std::size_t contacts_seen = 0;
  for (int k = 0; k < 100000; ++k) {
    sim.step();
    if (k % 100 == 0) {
      const ContactSummary c = sim.contact_summary();
      contacts_seen += c.contacts;
      worst = std::max(worst, std::abs(sim.kinetic_energy() + c.elastic_energy - e0) / e0);
    }
  }
  std::printf("[ measured ] %s elastic gas: largest energy deviation %.3g over 1e5 steps\n",
              GetParam() == HertzNormal::kName ? "hertz" : "linear", worst);
  EXPECT_GT(contacts_seen, 100u);  // the gas did collide
  EXPECT_LT(worst, 1e-4) << "dt=" << sim.dt();
}

INSTANTIATE_TEST_SUITE_P(ElasticGas, EnergyConservation, ::testing::Values(LinearNormal::kName, HertzNormal::kName),
                         [](const auto& info) { return std::string(info.param == HertzNormal::kName ? "hertz" : "linear"); });

}  // namespace
}  // namespace dem::test
