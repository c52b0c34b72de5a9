// Energy conservation: an elastic, frictionless gas of spheres in a box of walls (e = 1, mu = 0)
// at the default time step keeps its total energy (kinetic + elastic): over 1e5 steps its mean
// drifts by less than 1e-4, and it never strays by more than 1e-3 (velocity Verlet's bounded
// wobble inside each contact, (omega dt)^2 / 4 = 1e-3 of the energy in contacts at 50 steps per
// contact, of either sign).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "output/energy_output.hpp"
#include "support/scenes.hpp"

namespace dem::test::test_energy {
namespace {

Scene elastic_gas(std::string_view model, std::uint32_t seed) {
  Scene s = base_scene(model, 2500, 1e8, 0.25, 1.0, 0.0, 1e4);
  const double r = 0.005, box = 0.1;
  fill_gas_box(s, 6, r, box, seed);
  return s;
}

class EnergyConservation : public ::testing::TestWithParam<std::string_view> {};

TEST_P(EnergyConservation, DriftsLessThanOneIn1e4Over1e5Steps) {
  Simulation sim(elastic_gas(GetParam(), 7));
  auto energy = [&] { return sim.kinetic_energy() + sim.contact_summary().elastic_energy; };
  const double e0 = energy();
  double worst = 0, start = 0, end = 0;
  int samples = 0;
  std::size_t contacts_seen = 0;
  constexpr int kSteps = 100000, kEvery = 10, kWindow = 10000;  // means over the first and last 1e4 steps
  for (int k = 1; k <= kSteps; ++k) {
    sim.step();
    if (k % kEvery != 0) continue;
    const ContactSummary c = sim.contact_summary();
    contacts_seen += c.contacts;
    const double e = sim.kinetic_energy() + c.elastic_energy;
    worst = std::max(worst, std::abs(e - e0) / e0);
    if (k <= kWindow) start += e;
    if (k > kSteps - kWindow) end += e;
    ++samples;
  }
  const double drift = std::abs(end - start) / (kWindow / kEvery) / e0;
  const char* law = GetParam() == HertzNormal::kName ? "hertz" : "linear";
  std::printf("[ measured ] %s elastic gas: drift of the mean energy %.3g, largest deviation %.3g over 1e5 steps\n",
              law, drift, worst);
  EXPECT_GT(contacts_seen, 1000u);  // the gas did collide
  EXPECT_LT(drift, 1e-4) << "dt=" << sim.dt();
  EXPECT_LT(worst, 1e-3) << "dt=" << sim.dt();
}

INSTANTIATE_TEST_SUITE_P(ElasticGas, EnergyConservation, ::testing::Values(LinearNormal::kName, HertzNormal::kName),
                         [](const auto& info) {
                           return std::string(info.param == HertzNormal::kName ? "hertz" : "linear");
                         });

// Energy.csv's translational column of spheres that spin in place is 0, not the round-off of the
// kinetic energy less the rotational (an independent check found -1.7e-167 J): each is summed on its
// own.
TEST(EnergyColumns, SpheresSpinningInPlaceHaveNoTranslationalEnergy) {
  Scene s = base_scene(LinearNormal::kName, 2500, 0, 0.25, 1.0, 0.0, 1e4);
  for (int k = 0; k < 40; ++k)
    s.particles.push_back(sphere({0.1 * k, 0, 0}, 0.003 + 1e-4 * k, Vec3::Zero(),
                                 {std::sin(1.7 * k) * std::pow(10.0, k % 9), 3.1 * k, std::cos(k) * 1e-3}));
  Simulation sim(s);
  for (int k = 0; k < 40; ++k) {
    Scene one = s;
    one.particles = {s.particles[k]};
    Simulation single(one);
    const std::vector<double> row = EnergyWriter::make_row(single);
    EXPECT_EQ(row[1], 0.0) << "sphere " << k << ": translation " << row[1] << " J, rotation " << row[2] << " J";
    EXPECT_GT(row[2], 0.0);
  }
  EXPECT_EQ(EnergyWriter::make_row(sim)[1], 0.0);
}

}  // namespace
}  // namespace dem::test::test_energy
