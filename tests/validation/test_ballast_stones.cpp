// Generated ballast stones (BallastDEM's inlaid stones): the sample's masses follow the requested
// bounded lognormal distribution, each stone's mass is its density times the volume of its union of
// spheres, stones do not overlap, and the same seed gives the same stones.
#include <gtest/gtest.h>

#include <cmath>

#include "clumps/mass_properties.hpp"
#include "sim/simulation.hpp"
#include "spec/spec_loader.hpp"
#include "support/report.hpp"
#include "support/spec_problems.hpp"

namespace dem::test::test_ballast_stones {
namespace {

std::string stones_spec(int count, std::uint32_t seed, double box) {
  return R"({"name": "stones",
    "materials": [{"name": "granite", "density": 2650, "normalStiffness": 1e6}],
    "interactions": [{"a": "granite", "b": "granite", "restitution": 0.5, "friction": 0.6}],
    "ballastStones": [{"count": )" +
         std::to_string(count) + R"(, "massLogMean": -3.0, "massLogSigma": 0.6,
                       "massMin": 0.01, "massMax": 0.3, "minSpheres": 3, "maxSpheres": 20,
                       "min": {"x": 0, "y": 0, "z": 0}, "max": {"x": )" +
         std::to_string(box) + R"(, "y": )" + std::to_string(box) + R"(, "z": )" + std::to_string(box) +
         R"(}, "material": "granite", "seed": )" + std::to_string(seed) + R"(}],
    "gravity": {"z": -9.81}, "time": {"steps": 10}})";
}

// Mean and standard deviation of m when ln m ~ N(mu, sigma) bounded to [lo, hi] (Simpson's rule in ln m).
std::pair<double, double> bounded_lognormal_moments(double mu, double sigma, double lo, double hi) {
  const int n = 20000;
  const double a = std::log(lo), b = std::log(hi), h = (b - a) / n;
  double w0 = 0, w1 = 0, w2 = 0;
  for (int k = 0; k <= n; ++k) {
    const double y = a + k * h, m = std::exp(y);
    const double weight = (k == 0 || k == n ? 1 : (k % 2 ? 4 : 2)) * std::exp(-0.5 * std::pow((y - mu) / sigma, 2));
    w0 += weight;
    w1 += weight * m;
    w2 += weight * m * m;
  }
  const double mean = w1 / w0;
  return {mean, std::sqrt(w2 / w0 - mean * mean)};
}

TEST(BallastStones, TwoThousandStonesFollowTheRequestedMassDistribution) {
  const Scene scene = spec::to_scene(spec::parse_json(stones_spec(2000, 7, 2.5)));
  ASSERT_EQ(scene.clumps.size(), 2000u);
  double sum = 0, sum2 = 0;
  for (const ClumpInit& c : scene.clumps) {
    EXPECT_GE(c.mass, 0.01);
    EXPECT_LE(c.mass, 0.3);
    EXPECT_GE(c.count, 3);
    EXPECT_LE(c.count, 20);
    sum += c.mass;
    sum2 += c.mass * c.mass;
  }
  const double mean = sum / 2000, spread = std::sqrt(sum2 / 2000 - mean * mean);
  const auto [want_mean, want_spread] = bounded_lognormal_moments(-3.0, 0.6, 0.01, 0.3);
  report("mean stone mass (kg) of 2000", mean, want_mean);
  report("spread of stone masses (kg) of 2000", spread, want_spread);
  EXPECT_NEAR(mean, want_mean, 0.03 * want_mean);
  EXPECT_NEAR(spread, want_spread, 0.03 * want_spread);
}

TEST(BallastStones, EachStonesMassIsItsDensityTimesItsVolumeAndNoTwoOverlap) {
  const Scene scene = spec::to_scene(spec::parse_json(stones_spec(150, 3, 1.2)));
  for (std::size_t k = 0; k < 5; ++k) {  // a few stones, their members measured afresh
    const ClumpInit& c = scene.clumps[k];
    std::vector<MemberSphere> spheres;
    for (int i = c.first; i < c.first + c.count; ++i)
      spheres.push_back({scene.particles[i].position, scene.particles[i].radius});
    const MassProperties mp = union_mass_properties(spheres, 1e-4);
    EXPECT_NEAR(2650 * mp.volume, c.mass, 3e-3 * c.mass) << "stone " << k;
    EXPECT_NEAR((mp.centroid - c.position).norm(), 0, 1e-3 * std::cbrt(mp.volume)) << "stone " << k;
    EXPECT_NEAR(2650 * mp.principal_moments[2], c.moments[2], 1e-2 * c.moments[2]) << "stone " << k;
  }
  for (std::size_t a = 0; a < scene.particles.size(); ++a)
    for (std::size_t b = a + 1; b < scene.particles.size(); ++b) {
      const ParticleInit &p = scene.particles[a], &q = scene.particles[b];
      if (p.clump == q.clump) continue;
      ASSERT_GE((p.position - q.position).norm(), p.radius + q.radius)
          << "stones " << p.clump << " and " << q.clump << " overlap";
    }
}

TEST(BallastStones, TheSameSeedGivesTheSameStonesAndAnotherSeedOthers) {
  const Scene a = spec::to_scene(spec::parse_json(stones_spec(50, 11, 1.0)));
  const Scene b = spec::to_scene(spec::parse_json(stones_spec(50, 11, 1.0)));
  const Scene c = spec::to_scene(spec::parse_json(stones_spec(50, 12, 1.0)));
  ASSERT_EQ(a.particles.size(), b.particles.size());
  for (std::size_t i = 0; i < a.particles.size(); ++i) EXPECT_EQ(a.particles[i].position, b.particles[i].position);
  EXPECT_NE(a.clumps[0].mass, c.clumps[0].mass);
}

TEST(BallastStones, GeneratedStonesFallOntoTheFloorWithoutPassingThrough) {
  std::string spec = stones_spec(20, 5, 0.3);
  spec.replace(spec.find(R"("gravity")"), 0,
               R"("walls": [{"material": "granite", "plane": {"point": {}, "normal": {"z": 1}}}], )");
  spec.replace(spec.find(R"("time": {"steps": 10})"), 21, R"("time": {"duration": 0.2})");
  Simulation sim(spec::to_scene(spec::parse_json(spec)));
  while (sim.step_count() < sim.total_steps()) sim.step();
  const Particles& p = sim.particles();
  double lowest = 1;
  for (std::size_t i = 0; i < p.size(); ++i) lowest = std::min(lowest, p.x[i].z() - p.radius[i]);
  std::printf("20 stones after 0.2 s: lowest member surface at %.2e m, kinetic energy %.3e J\n", lowest,
              sim.kinetic_energy());
  EXPECT_GT(lowest, -0.05 * 0.01) << "no stone falls through the floor";
  EXPECT_TRUE(std::isfinite(sim.kinetic_energy()));
}

TEST(BallastStones, ABoxTooSmallSaysHowManyFitted) {
  try {
    spec::to_scene(spec::parse_json(stones_spec(500, 1, 0.3)));
    FAIL() << "expected a SpecError";
  } catch (const spec::SpecError& e) {
    ASSERT_FALSE(e.problems().empty());
    EXPECT_NE(e.problems()[0].find("ballastStones[0]: only "), std::string::npos) << e.problems()[0];
  }
}

// A distribution the sampler can never hit is refused before generation (it would redraw forever).
TEST(BallastStones, AnEmptyOrUndefinedMassDistributionIsRefused) {
  auto problems = [](const std::string& from, const std::string& to) {
    std::string json = stones_spec(10, 1, 1.0);
    json.replace(json.find(from), from.size(), to);
    return spec_problems(json);
  };
  std::string all = problems(R"("massLogSigma": 0.6)", R"("massLogSigma": 0)");  // exp(-3) = 0.0498 kg: fine
  EXPECT_EQ(all, "");
  all = problems(R"("massLogMean": -3.0, "massLogSigma": 0.6)", R"("massLogMean": 0, "massLogSigma": 0)");
  EXPECT_NE(
      all.find("ballastStones[0].massLogMean: with massLogSigma 0 every stone weighs exp(massLogMean) = 1 kg, outside"),
      std::string::npos)
      << all;
  all = problems(R"("massLogMean": -3.0)", R"("massLogMean": "NaN")");
  EXPECT_NE(all.find("ballastStones[0].massLogMean: must be a finite number"), std::string::npos) << all;
  // infinite bounds and boxes are named, not passed on to the generator
  all = problems(R"("massMax": 0.3)", R"("massMax": "Infinity")");
  EXPECT_NE(all.find("ballastStones[0].massMax: must be a finite number"), std::string::npos) << all;
  all = problems(R"("min": {"x": 0)", R"("min": {"x": "-Infinity")");
  EXPECT_NE(all.find("ballastStones[0].min: must be finite"), std::string::npos) << all;
  all = problems(R"("max": {"x": 1.000000)", R"("max": {"x": "Infinity")");
  EXPECT_NE(all.find("ballastStones[0].max: must be finite"), std::string::npos) << all;
}

}  // namespace
}  // namespace dem::test::test_ballast_stones
