// Partial slip: an oblique impact below the gross-sliding threshold, where the contact sticks, slips
// and sticks again within one impact. No closed form; the spin after the impact must converge in
// the time step at second order, like the normal direction and gross sliding (an independent
// tester's finding: the linear law's spin was 3% off at the default 50 steps per contact and first
// order in the step; the tangential dashpot lagged by half a step, a new contact's spring took a whole
// step's travel, and the dashpot went off when sliding began, a jump in the force).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/impact.hpp"

namespace dem::test::test_partial_slip {
namespace {

// Sphere of R = 0.1 m (Al alloy, as Chung & Ooi tests 5-8) onto a plane at v_n = v_t = 0.2 m/s,
// mu = 0.4, e = 0.5: tan(angle) = 1 is below the gross-sliding threshold 3.5 mu (1 + e) = 2.1.
double spin_after_impact(std::string_view law, double steps_per_contact, double v_t = 0.2, double e = 0.5) {
  const double r = 0.1, v = 0.2;
  Scene s = base_scene(law, 2699, 7.0e10, 0.30, e, 0.4, 1e7);
  s.particles.push_back(sphere({0, 0, r * 1.00001}, r, {v_t, 0, -v}));
  s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}));
  if (steps_per_contact > 0) {
    const double contact_time = Simulation(s).time_step().contact_time;
    s.time.dt = contact_time / steps_per_contact;
    s.time.allow_unstable_dt = true;
  }
  Simulation sim(s);
  record_impact(sim, 10000000);
  return sim.particles().w[0].y();
}

TEST(PartialSlip, SpinConvergesAtSecondOrderInTheStep) {
  for (std::string_view law : {LinearNormal::kName, HertzNormal::kName}) {
    const double exact = spin_after_impact(law, 6400);
    double worst_coarse = 0, worst_fine = 0;
    // several step sizes near each end: where the steps fall against the stick-slip switches varies
    for (double n : {45.0, 50.0, 55.0, 60.0})
      worst_coarse = std::max(worst_coarse, std::abs(spin_after_impact(law, n) - exact));
    for (double n : {360.0, 400.0, 440.0, 480.0})
      worst_fine = std::max(worst_fine, std::abs(spin_after_impact(law, n) - exact));
    const double order = std::log(worst_coarse / worst_fine) / std::log(8.0);
    const double at_default = std::abs(spin_after_impact(law, 0) - exact) / std::abs(exact);
    std::printf(
        "[ measured ] %s partial slip: spin %.6g rad/s, order over N = 45-60..360-480: %.2f, default step %.2e\n",
        std::string(law).c_str(), exact, order, at_default);
    EXPECT_GT(order, 1.6) << law;
    EXPECT_LT(at_default, 0.005) << law;
  }
}

// A glancing impact that sticks nearly throughout (v_t = v_n / 4, e = 1): Hertz-Mindlin's spring,
// loaded from a contact radius of zero, took the step's mean stiffness as the mean of its two ends,
// half of the exact 2/3 on the first step: an error of order dt^1.5 that the stuck contact kept
// (an independent tester's finding: order 1.1-1.3, 2.4e-3 off at the default step).
TEST(PartialSlip, AGlancingStuckImpactConvergesAtSecondOrderToo) {
  for (std::string_view law : {LinearNormal::kName, HertzNormal::kName}) {
    const double exact = spin_after_impact(law, 6400, 0.05, 1.0);
    double worst_coarse = 0, worst_fine = 0;
    for (double n : {45.0, 50.0, 55.0, 60.0})
      worst_coarse = std::max(worst_coarse, std::abs(spin_after_impact(law, n, 0.05, 1.0) - exact));
    for (double n : {360.0, 400.0, 440.0, 480.0})
      worst_fine = std::max(worst_fine, std::abs(spin_after_impact(law, n, 0.05, 1.0) - exact));
    const double order = std::log(worst_coarse / worst_fine) / std::log(8.0);
    const double at_default = std::abs(spin_after_impact(law, 0, 0.05, 1.0) - exact) / std::abs(exact);
    std::printf("[ measured ] %s glancing stuck impact: spin %.6g rad/s, order %.2f, default step %.2e\n",
                std::string(law).c_str(), exact, order, at_default);
    EXPECT_GT(order, 1.6) << law;
    EXPECT_LT(at_default, 0.002) << law;
  }
}

}  // namespace
}  // namespace dem::test::test_partial_slip
