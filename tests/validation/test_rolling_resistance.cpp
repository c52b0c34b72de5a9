// Rolling resistance (Ai et al. 2011, Powder Technol. 206:269-282; validation.md section 3): a sphere
// rolling on a plane decelerates at 5/7 mu_r g, stops after 7 v0^2 / (10 mu_r g) in 7 v0 / (5 mu_r g);
// on an incline it stays at rest when tan(theta) <= mu_r and rolls down at
// 5/7 g (sin theta - mu_r cos theta) above. Tolerance 2%.
#include <gtest/gtest.h>

#include <cmath>

#include "support/report.hpp"
#include "support/scenes.hpp"

namespace dem::test {
namespace {

constexpr double kR = 0.01, kDensity = 2500, kKn = 1e5, kG = 9.81, kMuR = 0.1;

// A sphere resting on the plane z = 0 under gravity g (its overlap already at the static value).
Scene sphere_on_plane(std::string_view model, const Vec3& g, const Vec3& v0, const Vec3& w0) {
  Scene s = base_scene(LinearNormal::kName, kDensity, 0, 0.25, 0.5, 0.5, kKn);
  set_rolling(s, model, kMuR);
  s.gravity = g;
  const double m = sphere_mass(kDensity, kR);
  // the linear wall contact has K_n = 2 k (rigid wall, the PDEM-EGD manual's eq. 4)
  const double overlap = m * std::abs(g.z()) / (2 * kKn);
  s.particles.push_back(sphere({0, 0, kR - overlap}, kR, v0, w0));
  s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}));
  s.time.steps = 1;
  return s;
}

class RollingResistance : public ::testing::TestWithParam<std::string_view> {};

TEST_P(RollingResistance, RollingSphereStopsAtTheClosedFormDistanceAndTime) {
  const double v0 = 0.5;
  Simulation sim(sphere_on_plane(GetParam(), {0, 0, -kG}, {v0, 0, 0}, {0, v0 / kR, 0}));
  step_until(sim, 10'000'000, [](const Simulation& s) { return s.particles().v[0].x() <= 0; });
  const double distance = sim.particles().x[0].x();
  const double time = sim.time();
  const double want_distance = 7 * v0 * v0 / (10 * kMuR * kG);
  const double want_time = 7 * v0 / (5 * kMuR * kG);
  const std::string model = GetParam() == CdtRolling::kName ? "CDT" : "EPSD";
  report(model + " stopping distance", distance, want_distance);
  report(model + " stopping time", time, want_time);
  EXPECT_NEAR(distance, want_distance, 0.02 * want_distance);
  EXPECT_NEAR(time, want_time, 0.02 * want_time);
}

TEST_P(RollingResistance, DecelerationIsFiveSeventhsMuRG) {
  const double v0 = 0.5;
  Simulation sim(sphere_on_plane(GetParam(), {0, 0, -kG}, {v0, 0, 0}, {0, v0 / kR, 0}));
  step_until(sim, 10'000'000, [](const Simulation& s) { return s.time() >= 0.1; });
  const double v1 = sim.particles().v[0].x(), t1 = sim.time();
  step_until(sim, 10'000'000, [](const Simulation& s) { return s.time() >= 0.5; });
  const double a = (sim.particles().v[0].x() - v1) / (sim.time() - t1);
  report(std::string(GetParam() == CdtRolling::kName ? "CDT" : "EPSD") + " deceleration", -a, 5.0 / 7.0 * kMuR * kG);
  EXPECT_NEAR(-a, 5.0 / 7.0 * kMuR * kG, 0.02 * 5.0 / 7.0 * kMuR * kG);
}

TEST_P(RollingResistance, StaysAtRestOnAnInclineBelowTheThreshold) {
  const double theta = std::atan(0.8 * kMuR);
  Simulation sim(sphere_on_plane(GetParam(), {kG * std::sin(theta), 0, -kG * std::cos(theta)}, Vec3::Zero(),
                                 Vec3::Zero()));
  step_until(sim, 10'000'000, [](const Simulation& s) { return s.time() >= 1.0; });
  // EPSD: the rolling spring winds up by M / k_r (a few micrometres of travel), then nothing moves.
  // CDT has no spring: its torque can only stop the rotation gained in the last step, so the sphere
  // creeps by a fraction of the per-step gain (Ai et al. 2011 recommend model C for static packings):
  // measured 1.1e-5 m in 1 s here; bounded at twice that.
  std::printf("[ measured ] %s at rest below the threshold: moved %.3g m in 1 s\n",
              GetParam() == CdtRolling::kName ? "CDT" : "EPSD", std::abs(sim.particles().x[0].x()));
  const double allowed = GetParam() == EpsdRolling::kName ? 1e-3 * kR : 2e-3 * kR;
  EXPECT_LT(std::abs(sim.particles().x[0].x()), allowed);
  EXPECT_LT(sim.particles().v[0].norm(), 1e-4);
}

TEST_P(RollingResistance, RollsDownAnInclineAboveTheThreshold) {
  const double theta = std::atan(2 * kMuR);
  Simulation sim(sphere_on_plane(GetParam(), {kG * std::sin(theta), 0, -kG * std::cos(theta)}, Vec3::Zero(),
                                 Vec3::Zero()));
  step_until(sim, 10'000'000, [](const Simulation& s) { return s.time() >= 0.1; });
  const double v1 = sim.particles().v[0].x(), t1 = sim.time();
  step_until(sim, 10'000'000, [](const Simulation& s) { return s.time() >= 0.4; });
  const double a = (sim.particles().v[0].x() - v1) / (sim.time() - t1);
  const double want = 5.0 / 7.0 * kG * (std::sin(theta) - kMuR * std::cos(theta));
  report(std::string(GetParam() == CdtRolling::kName ? "CDT" : "EPSD") + " incline above threshold", a, want);
  EXPECT_NEAR(a, want, 0.02 * want);
}

INSTANTIATE_TEST_SUITE_P(AiEtAl2011, RollingResistance, ::testing::Values(CdtRolling::kName, EpsdRolling::kName),
                         [](const auto& info) { return std::string(info.param == CdtRolling::kName ? "cdt" : "epsd"); });

}  // namespace
}  // namespace dem::test
