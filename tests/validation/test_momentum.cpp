// Total linear and angular momentum of free bodies are conserved to round-off: in oblique impacts
// of two spheres (any normal, a moving centre of mass) and in a dense frictional cloud collapsing
// on itself, for both normal laws, with and without rolling resistance. The tangential force acts
// at the contact point, at r - delta/2 from each centre (as in YADE); through the full radius, each
// sliding contact leaked angular momentum of relative size delta / R.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "support/report.hpp"
#include "support/scenes.hpp"

namespace dem::test::test_momentum {
namespace {

struct Momenta {
  Vec3 linear = Vec3::Zero(), angular = Vec3::Zero();
  double scale = 0;  // sum of |m v| + |x| |m v| + I |w|: what round-off is relative to
};

Momenta momenta(const Simulation& sim) {
  const Particles& p = sim.particles();
  Momenta m;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3 mv = p.mass[i] * p.v[i];
    const Vec3 spin = 0.4 * p.mass[i] * p.radius[i] * p.radius[i] * p.w[i];
    m.linear += mv;
    m.angular += p.x[i].cross(mv) + spin;
    m.scale += mv.norm() * (1 + p.x[i].norm()) + spin.norm();
  }
  return m;
}

// The largest change of either momentum over the run, relative to the scale.
double largest_drift(Simulation& sim, int steps) {
  const Momenta start = momenta(sim);
  double worst = 0;
  for (int k = 0; k < steps; ++k) {
    sim.step();
    const Momenta now = momenta(sim);
    worst = std::max(
        {worst, (now.linear - start.linear).norm() / start.scale, (now.angular - start.angular).norm() / start.scale});
  }
  return worst;
}

class Momentum : public ::testing::TestWithParam<std::string_view> {};

// Chung & Ooi tests 7 and 8 turned to an arbitrary normal, with the pair's centre of mass moving
// (Al alloy, R and R/2, e = 0.5, mu = 0.4, spins and tangential velocities of tests 7-8).
TEST_P(Momentum, IsKeptThroughOneObliqueImpact) {
  const Vec3 n = Vec3(1, -2, 0.5).normalized();
  const Vec3 t = n.cross(Vec3::UnitZ()).normalized(), drift(0.3, -0.1, 0.7);
  Scene s = base_scene(GetParam(), 2699, 7.0e10, 0.30, 0.5, 0.4, 1e7);
  s.particles.push_back(sphere(-0.1 * 1.00001 * n, 0.1, 0.1 * n + 0.1 * t + drift, 15 * t.cross(n)));
  s.particles.push_back(sphere(0.05 * 1.00002 * n, 0.05, -0.1 * n - 0.1 * t + drift, -5 * t + 3 * n));
  Simulation sim(s);
  const double worst = largest_drift(sim, 4000);
  report(std::string(GetParam()) + ": oblique impact, largest momentum change / scale", worst, 0.0);
  EXPECT_LT(worst, 1e-13);
}

// 400 spheres in a ball, each moving towards the centre at up to 2 m/s with a random spin: they meet, pile up and
// rebound, many contacts at once sliding and sticking. No gravity, no walls.
Scene collapsing_cloud(std::string_view law, bool rolling) {
  Scene s = base_scene(law, 2600, 1e8, 0.25, 0.5, 0.5, 1e5);
  if (rolling) set_rolling(s, EpsdRolling::kName, 0.1);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  while (s.particles.size() < 400) {
    const Vec3 x(u(rng), u(rng), u(rng));
    if (x.norm() > 1) continue;
    const double r = 0.01 * (1 + 0.3 * u(rng));
    const Vec3 at = 0.15 * x;
    bool free = true;
    for (const ParticleInit& p : s.particles) free = free && (p.position - at).norm() > p.radius + r;
    if (free)
      s.particles.push_back(
          sphere(at, r, -2.0 * x + 0.05 * Vec3(u(rng), u(rng), u(rng)), 10 * Vec3(u(rng), u(rng), u(rng))));
  }
  return s;
}

TEST_P(Momentum, IsKeptInACollapsingFrictionalCloud) {
  for (bool rolling : {false, true}) {
    Simulation sim(collapsing_cloud(GetParam(), rolling));
    const double worst = largest_drift(sim, 6000);
    const std::string label = std::string(GetParam()) + (rolling ? ", EPSD rolling" : "");
    report(label + ": collapsing cloud, largest momentum change / scale", worst, 0.0);
    EXPECT_LT(worst, 1e-12) << label;
  }
}

INSTANTIATE_TEST_SUITE_P(BothLaws, Momentum, ::testing::Values(LinearNormal::kName, HertzNormal::kName),
                         [](const auto& info) {
                           return std::string(info.param == HertzNormal::kName ? "hertz" : "linear");
                         });

}  // namespace
}  // namespace dem::test::test_momentum
