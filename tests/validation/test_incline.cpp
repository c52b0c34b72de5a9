// A sphere on an inclined plane (validation.md section 4): sliding when tan(theta) > 3.5 mu with
// a = g (sin theta - mu cos theta); rolling without slip below, a = 5/7 g sin theta.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/report.hpp"
#include "support/scenes.hpp"

namespace dem::test::test_incline {
namespace {

constexpr double kR = 0.01, kG = 9.81;

struct InclineCase {
  std::string_view model;
  double theta_deg, mu;
};

class Incline : public ::testing::TestWithParam<InclineCase> {};

// The plane is tilted about y; x' runs down the slope. Acceleration is measured over 0.1..0.4 s,
// after the contact has settled.
TEST_P(Incline, AccelerationMatchesClosedFormWithinHalfAPermille) {
  const InclineCase c = GetParam();
  const double th = c.theta_deg * std::numbers::pi / 180;
  Scene s = base_scene(c.model, 2500, 1e8, 0.25, 0.5, c.mu, 1e5);
  s.gravity = {0, 0, -kG};
  const Vec3 normal(std::sin(th), 0, std::cos(th));  // tilted so that +x is downhill
  const Vec3 downhill(std::cos(th), 0, -std::sin(th));
  s.walls.push_back(plane(Vec3::Zero(), normal));
  s.particles.push_back(sphere(normal * kR * 0.9999, kR));
  Simulation sim(s);
  step_until(sim, 10'000'000, [](const Simulation& x) { return x.time() >= 0.1; });
  const double v1 = sim.particles().v[0].dot(downhill), t1 = sim.time();
  step_until(sim, 10'000'000, [](const Simulation& x) { return x.time() >= 0.4; });
  const double a = (sim.particles().v[0].dot(downhill) - v1) / (sim.time() - t1);
  const bool slides = std::tan(th) > 3.5 * c.mu;
  const double want = slides ? kG * (std::sin(th) - c.mu * std::cos(th)) : 5.0 / 7.0 * kG * std::sin(th);
  report(std::string(c.model == HertzNormal::kName ? "hertz" : "linear") + (slides ? " sliding" : " rolling") +
             " acceleration",
         a, want);
  EXPECT_NEAR(a, want, 5e-4 * want) << (slides ? "sliding" : "rolling");
  // no motion off the plane
  EXPECT_LT(std::abs(sim.particles().v[0].dot(normal)), 1e-6 * sim.particles().v[0].norm());
}

INSTANTIATE_TEST_SUITE_P(
    SphereOnIncline, Incline,
    ::testing::Values(InclineCase{LinearNormal::kName, 30, 0.1}, InclineCase{LinearNormal::kName, 20, 0.5},
                      InclineCase{HertzNormal::kName, 30, 0.1}, InclineCase{HertzNormal::kName, 20, 0.5}),
    [](const auto& info) {
      const auto& c = info.param;
      return std::string(c.model == HertzNormal::kName ? "hertz" : "linear") +
             (std::tan(c.theta_deg * std::numbers::pi / 180) > 3.5 * c.mu ? "_sliding" : "_rolling");
    });

}  // namespace
}  // namespace dem::test::test_incline
