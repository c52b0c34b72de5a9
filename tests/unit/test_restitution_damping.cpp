// Tests of the restitution <-> damping maps (engine/contact/restitution_damping.hpp): the closed
// form of the linear law with tension, the inverses by integration, and the effect of clamping the
// force at zero (Thornton et al. 2013).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "contact/restitution_damping.hpp"

namespace dem {
namespace {

// validation.md section 2: zeta = -ln e / sqrt(pi^2 + ln^2 e).
double closed_form_zeta(double e) {
  const double l = std::log(e);
  return -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

// e = 0.05, 0.10, ..., 1.00
std::vector<double> restitutions() {
  std::vector<double> e;
  for (int k = 1; k <= 20; ++k) e.push_back(0.05 * k);
  return e;
}

TEST(RestitutionDamping, LinearWithTensionIsTheClosedForm) {
  EXPECT_NEAR(linear_damping_ratio(0.5, false), 0.21545, 5e-6);  // validation.md section 2
  for (double e : restitutions())
    EXPECT_NEAR(linear_damping_ratio(e, false), closed_form_zeta(e), 1e-12) << "e = " << e;
}

TEST(RestitutionDamping, LinearIntegrationMatchesTheClosedFormRestitution) {
  // With tension the linear law's rebound is exp(-zeta pi / sqrt(1 - zeta^2)) exactly, an
  // independent check of the integrator the no-tension inversion relies on.
  for (double zeta : {0.0, 0.05, 0.2, 0.5, 0.8}) {
    const double expected = std::exp(-zeta * std::numbers::pi / std::sqrt(1 - zeta * zeta));
    EXPECT_NEAR(linear_restitution(zeta, false), expected, 1e-6) << "zeta = " << zeta;
  }
}

TEST(RestitutionDamping, LinearRoundTripBothTensionSettings) {
  for (bool no_tension : {false, true})
    for (double e : restitutions())
      EXPECT_NEAR(linear_restitution(linear_damping_ratio(e, no_tension), no_tension), e, 1e-6)
          << "e = " << e << ", no tension = " << no_tension;
}

TEST(RestitutionDamping, HertzRoundTripBothTensionSettings) {
  for (bool no_tension : {false, true})
    for (double e : restitutions())
      EXPECT_NEAR(hertz_restitution(hertz_damping_number(e, no_tension), no_tension), e, 1e-6)
          << "e = " << e << ", no tension = " << no_tension;
}

TEST(RestitutionDamping, ClampNeedsMoreDampingForTheSameRestitution) {
  // Clamping the force at zero ends the contact before the spring pulls back: the bodies part
  // faster, so the same damping gives a larger e and the requested e needs more damping.
  for (double e : restitutions()) {
    if (e >= 1) continue;
    EXPECT_GT(linear_damping_ratio(e, true), linear_damping_ratio(e, false)) << "e = " << e;
    EXPECT_GT(hertz_damping_number(e, true), hertz_damping_number(e, false)) << "e = " << e;
  }
}

TEST(RestitutionDamping, ClampRaisesTheUsualFitFromPoint2ToPoint325) {
  // validation.md section 1, test 3: with the force clamped at zero, the tension fit for e = 0.2
  // gives e = 0.325.
  EXPECT_NEAR(linear_restitution(closed_form_zeta(0.2), true), 0.325, 1e-3);
  EXPECT_GT(hertz_restitution(hertz_damping_number(0.2, false), true), 0.3);
}

TEST(RestitutionDamping, PerfectlyElasticNeedsNoDamping) {
  for (bool no_tension : {false, true}) {
    EXPECT_EQ(linear_damping_ratio(1.0, no_tension), 0.0);
    EXPECT_EQ(hertz_damping_number(1.0, no_tension), 0.0);
    EXPECT_NEAR(linear_restitution(0.0, no_tension), 1.0, 1e-6);
    EXPECT_NEAR(hertz_restitution(0.0, no_tension), 1.0, 1e-6);
  }
}

TEST(RestitutionDamping, RestitutionFallsAsDampingRises) {
  for (bool no_tension : {false, true}) {
    double last_linear = 2, last_hertz = 2;
    // Damping numbers below 1: with tension, the linear law is overdamped from zeta = 1 on.
    for (double d = 0; d < 0.95; d += 0.15) {
      const double el = linear_restitution(d, no_tension), eh = hertz_restitution(d, no_tension);
      EXPECT_LT(el, last_linear) << "zeta = " << d;
      EXPECT_LT(eh, last_hertz) << "eta = " << d;
      EXPECT_GE(el, 0.0);
      EXPECT_GE(eh, 0.0);
      last_linear = el;
      last_hertz = eh;
    }
  }
}

}  // namespace
}  // namespace dem
