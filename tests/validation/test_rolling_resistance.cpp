// Rolling resistance (Ai et al. 2011, Powder Technol. 206:269-282; validation.md section 3): a sphere
// rolling on a plane decelerates at 5/7 mu_r g, stops after 7 v0^2 / (10 mu_r g) in 7 v0 / (5 mu_r g);
// on an incline it stays at rest when tan(theta) <= mu_r and rolls down at
// 5/7 g (sin theta - mu_r cos theta) above. Tolerance 2%.
#include <gtest/gtest.h>

#include <cmath>

#include "support/report.hpp"
#include "support/scenes.hpp"

namespace dem::test::test_rolling_resistance {
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
  Simulation sim(
      sphere_on_plane(GetParam(), {kG * std::sin(theta), 0, -kG * std::cos(theta)}, Vec3::Zero(), Vec3::Zero()));
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
  Simulation sim(
      sphere_on_plane(GetParam(), {kG * std::sin(theta), 0, -kG * std::cos(theta)}, Vec3::Zero(), Vec3::Zero()));
  step_until(sim, 10'000'000, [](const Simulation& s) { return s.time() >= 0.1; });
  const double v1 = sim.particles().v[0].x(), t1 = sim.time();
  step_until(sim, 10'000'000, [](const Simulation& s) { return s.time() >= 0.4; });
  const double a = (sim.particles().v[0].x() - v1) / (sim.time() - t1);
  const double want = 5.0 / 7.0 * kG * (std::sin(theta) - kMuR * std::cos(theta));
  report(std::string(GetParam() == CdtRolling::kName ? "CDT" : "EPSD") + " incline above threshold", a, want);
  EXPECT_NEAR(a, want, 0.02 * want);
}

INSTANTIATE_TEST_SUITE_P(AiEtAl2011, RollingResistance, ::testing::Values(CdtRolling::kName, EpsdRolling::kName),
                         [](const auto& info) {
                           return std::string(info.param == CdtRolling::kName ? "cdt" : "epsd");
                         });

// Faster and with more rolling friction than the case above, both laws: the rolling moment never
// exceeds mu_r R* F_n, so the distance is the closed form's (EPSD's dashpot once added its moment on
// top of the spring's at the limit whenever F_n rose: 2.8% short at mu_r = 0.6, 6.3% with eta_r 1).
struct StopCase {
  std::string_view law, model;
  double mu_r, damping_ratio;
};

class RollingStop : public ::testing::TestWithParam<StopCase> {};

TEST_P(RollingStop, StopsAtTheClosedFormDistance) {
  const StopCase c = GetParam();
  const double v0 = 1.0, r = 0.005;
  Scene s = base_scene(c.law, kDensity, 5e8, 0.25, 0.5, 0.5, kKn);
  set_rolling(s, c.model, c.mu_r);
  s.contact.parameters.set(EpsdRolling::kDampingRatio.field, c.damping_ratio);
  s.gravity = {0, 0, -kG};
  s.particles.push_back(sphere({0, 0, r * 0.9999}, r, {v0, 0, 0}, {0, v0 / r, 0}));
  s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}));
  s.time.steps = 100000000;
  Simulation sim(s);
  step_until(sim, 100'000'000, [](const Simulation& m) { return m.particles().v[0].x() <= 0 || m.time() > 5; });
  const double want = 7 * v0 * v0 / (10 * c.mu_r * kG);
  report(std::string(c.law) + " " + std::string(c.model) + " mu_r " + std::to_string(c.mu_r) + ", eta_r " +
             std::to_string(c.damping_ratio) + ": stopping distance",
         sim.particles().x[0].x(), want);
  EXPECT_NEAR(sim.particles().x[0].x(), want, 0.01 * want);
}

std::vector<StopCase> stop_cases() {
  std::vector<StopCase> out;
  for (std::string_view law : {LinearNormal::kName, HertzNormal::kName})
    for (double mu_r : {0.05, 0.2, 0.4, 0.6}) {
      out.push_back({law, CdtRolling::kName, mu_r, 0.3});
      for (double eta : {0.0, 0.3, 1.0}) out.push_back({law, EpsdRolling::kName, mu_r, eta});
    }
  return out;
}

INSTANTIATE_TEST_SUITE_P(FastAndRough, RollingStop, ::testing::ValuesIn(stop_cases()));

// A frictionless sphere spinning about a horizontal axis dropped on a plane: rolling resistance can
// take at most mu_r R J_n / I of its spin (J_n the normal impulse); EPSD's dashpot took 1.44 times
// that (2.5 times with eta_r 1).
TEST(RollingTouchDown, TakesNoMoreSpinThanTheRollingLimitAllows) {
  const double r = 0.005, mu_r = 0.1, m = sphere_mass(2600, r), inertia = 0.4 * m * r * r;
  for (std::string_view law : {LinearNormal::kName, HertzNormal::kName})
    for (auto [model, eta] : {std::pair{CdtRolling::kName, 0.3},
                              {EpsdRolling::kName, 0.0},
                              {EpsdRolling::kName, 0.3},
                              {EpsdRolling::kName, 1.0},
                              {EpsdRolling::kName, 10.0}}) {
      Scene s = base_scene(law, 2600, 5e7, 0.25, 0.5, 0.0, 1e5);
      set_rolling(s, model, mu_r);
      s.contact.parameters.set(EpsdRolling::kDampingRatio.field, eta);
      s.particles.push_back(sphere({0, 0, r * 1.0001}, r, {0, 0, -1}, {0, 200, 0}));
      s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}));
      s.time.steps = 100000000;
      Simulation sim(s);
      bool touched = false;
      step_until(sim, 10'000'000, [&](const Simulation& x) {
        const bool now = x.contact_counts()[0] > 0;
        touched = touched || now;
        return touched && !now;
      });
      const double impulse = m * (sim.particles().v[0].z() + 1);
      const double taken = 200 - sim.particles().w[0].y(), most = mu_r * r * impulse / inertia;
      report(std::string(law) + " " + std::string(model) + " eta_r " + std::to_string(eta) + ": spin taken / limit",
             taken / most, 1.0);
      EXPECT_LE(taken, most * (1 + 1e-9)) << law << " " << model << " eta_r " << eta;
      // CDT's torque is at the limit throughout (the spin never stops); EPSD's spring winds up first
      if (model == CdtRolling::kName) {
        EXPECT_NEAR(taken, most, 1e-6 * most) << law;
      }
    }
}

// A stiff rolling dashpot (eta_r 10 to 1000) in a settling pile: no energy made from nothing. Its
// moment once overshot within a step and, after losses, made 1.65 times the initial energy.
TEST(RollingDashpot, AnyDampingRatioMakesNoEnergy) {
  for (double eta : {10.0, 100.0, 1000.0}) {
    Scene s = base_scene(LinearNormal::kName, 2600, 0, 0.25, 0.5, 0.5, 1e5);
    set_rolling(s, EpsdRolling::kName, 0.1);
    s.contact.parameters.set(EpsdRolling::kDampingRatio.field, eta);
    s.gravity = {0, 0, -kG};
    const double r = 0.005;
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
          s.particles.push_back(
              sphere({2.1 * r * i + 0.3 * r * (k % 2), 2.1 * r * j + 0.2 * r * (k % 2), r + 2.2 * r * k}, r,
                     Vec3::Zero(), Vec3(10 * std::sin(i + 2 * j + 3 * k), 10 * std::cos(3 * i + j), 5)));
    s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}));
    s.walls.push_back(plane({-r, 0, 0}, {1, 0, 0}));
    s.walls.push_back(plane({8.5 * r, 0, 0}, {-1, 0, 0}));
    s.walls.push_back(plane({0, -r, 0}, {0, 1, 0}));
    s.walls.push_back(plane({0, 8.5 * r, 0}, {0, -1, 0}));
    s.time.steps = 100000000;
    Simulation sim(s);
    const double e0 = sim.mechanical_energy() - sim.gravitational_energy() + std::abs(sim.gravitational_energy());
    double lowest = sim.mechanical_energy(), worst_gain = 0;
    while (sim.time() < 0.3) {
      sim.step();
      const double e = sim.mechanical_energy();
      lowest = std::min(lowest, e);
      worst_gain = std::max(worst_gain, (e - lowest) / e0);
    }
    report("EPSD eta_r " + std::to_string(eta) + ": largest energy gain over the lowest so far / scale", worst_gain,
           0.0);
    EXPECT_LT(worst_gain, 1e-3) << "eta_r " << eta;
  }
}

}  // namespace
}  // namespace dem::test::test_rolling_resistance
