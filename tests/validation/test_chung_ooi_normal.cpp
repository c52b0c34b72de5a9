// Chung & Ooi (2011), Granular Matter 13:643-656, tests 1-3: normal impacts against Hertz theory
// and the requested restitution (numbers from validation.md section 1).
#include <gtest/gtest.h>

#include <cmath>

#include "support/impact.hpp"
#include "support/report.hpp"

namespace dem::test::test_chung_ooi_normal {
namespace {

struct HertzCase {
  const char* name;
  double youngs, poisson, density, radius, speed;
  bool on_plane;
  double t_c, alpha_max, f_max;  // validation.md table
};

class ElasticImpact : public ::testing::TestWithParam<HertzCase> {};

TEST_P(ElasticImpact, MatchesHertzTheoryWithinOnePercent) {
  const HertzCase c = GetParam();
  Scene s = base_scene(HertzNormal::kName, c.density, c.youngs, c.poisson, 1.0, 0.0);
  if (c.on_plane) {
    // test 2: sphere at 0.2 m/s onto a rigid plane
    s.particles.push_back(sphere({0, 0, c.radius * 1.001}, c.radius, {0, 0, -c.speed}));
    s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}));
  } else {
    // test 1: two identical spheres, +-V/2 each (V = 20 m/s approach speed of the table)
    s.particles.push_back(sphere({-c.radius * 1.001, 0, 0}, c.radius, {c.speed / 2, 0, 0}));
    s.particles.push_back(sphere({c.radius * 1.001, 0, 0}, c.radius, {-c.speed / 2, 0, 0}));
  }
  Simulation sim(s);  // the project's default (automatic) time step
  const ImpactRecord r = record_impact(sim, 100000);
  report(std::string(c.name) + " contact time", r.contact_time, c.t_c);
  report(std::string(c.name) + " max overlap", r.max_overlap, c.alpha_max);
  report(std::string(c.name) + " max force", r.max_force, c.f_max);
  EXPECT_NEAR(r.contact_time, c.t_c, 0.01 * c.t_c) << c.name << " dt=" << sim.dt();
  EXPECT_NEAR(r.max_overlap, c.alpha_max, 0.01 * c.alpha_max) << c.name;
  EXPECT_NEAR(r.max_force, c.f_max, 0.01 * c.f_max) << c.name;
}

INSTANTIATE_TEST_SUITE_P(
    ChungOoiTests1And2, ElasticImpact,
    ::testing::Values(HertzCase{"glass", 4.8e10, 0.20, 2800, 0.010, 20.0, false, 40.34e-6, 274.1e-6, 10.70e3},
                      HertzCase{"limestone", 2.0e10, 0.25, 2500, 0.010, 20.0, false, 54.20e-6, 368.3e-6, 7.108e3},
                      HertzCase{"al_alloy", 7.0e10, 0.30, 2699, 0.10, 0.2, true, 731.7e-6, 49.72e-6, 11.37e3},
                      HertzCase{"mg_alloy", 4.0e10, 0.35, 1800, 0.10, 0.2, true, 767.1e-6, 52.12e-6, 7.233e3}),
    [](const auto& info) { return std::string(info.param.name); });

struct RestitutionCase {
  std::string_view model;
  bool no_tensile;
  double youngs, poisson, density;
};

class Restitution : public ::testing::TestWithParam<RestitutionCase> {};

// Test 3: 2.5 mm sphere at 3.9 m/s on a plane; measured e equals the input within 1% for e = 0.1..1.
TEST_P(Restitution, MeasuredEqualsInputWithinOnePercent) {
  const RestitutionCase c = GetParam();
  const double r = 0.0025, v = 3.9;
  const double kn = 1e6;  // linear model: a stiffness giving a contact time of a few microseconds
  for (int k = 1; k <= 10; ++k) {
    const double e = 0.1 * k;
    Scene s = base_scene(c.model, c.density, c.youngs, c.poisson, e, 0.0, kn);
    s.contact.no_tensile_force = c.no_tensile;
    s.particles.push_back(sphere({0, 0, r * 1.0001}, r, {0, 0, -v}));
    s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}));
    Simulation sim(s);
    record_impact(sim, 1000000);
    const double measured = sim.particles().v[0].z() / v;
    report(std::string(c.model == HertzNormal::kName ? "hertz" : "linear") + (c.no_tensile ? " no-tension" : "") +
               " restitution",
           measured, e);
    EXPECT_NEAR(measured, e, 0.01 * e) << "e=" << e << " model=" << (c.model == HertzNormal::kName ? "hertz" : "linear")
                                       << " no_tensile=" << c.no_tensile;
  }
}

INSTANTIATE_TEST_SUITE_P(ChungOoiTest3, Restitution,
                         ::testing::Values(RestitutionCase{HertzNormal::kName, false, 3.8e11, 0.23, 4000},
                                           RestitutionCase{HertzNormal::kName, true, 3.8e11, 0.23, 4000},
                                           RestitutionCase{LinearNormal::kName, false, 3.8e11, 0.23, 4000},
                                           RestitutionCase{LinearNormal::kName, true, 3.8e11, 0.23, 4000},
                                           RestitutionCase{HertzNormal::kName, false, 1.0e11, 0.25, 7000},
                                           RestitutionCase{HertzNormal::kName, true, 1.0e11, 0.25, 7000}),
                         [](const auto& info) {
                           const auto& c = info.param;
                           return std::string(c.model == HertzNormal::kName ? "hertz" : "linear") +
                                  (c.no_tensile ? "_no_tension" : "") +
                                  (c.density == 4000 ? "_al_oxide" : "_cast_iron");
                         });

// Test 3 wherever the steps fall: the sphere starts at 20 positions across one step of travel, for
// both tension settings of the linear law (e = 0.1, 0.2, 0.3: the strongest dashpots). With tension
// the dashpot still pulls at parting, and where the parting falls between the next step's window
// and its evaluation the share of that window was guessed from the speed alone: at two of the
// twenty positions it was counted twice and the rebound came out 3.4-4.3% short.
TEST(RestitutionAnywhereInTheStep, LinearLawWithinOnePercent) {
  const double r = 0.0025, v = 3.9;
  for (bool no_tensile : {false, true}) {
    for (double e : {0.1, 0.2, 0.3}) {
      double worst = 0;
      for (int k = 0; k < 20; ++k) {
        Scene s = base_scene(LinearNormal::kName, 4000, 0, 0.23, e, 0.0, 1e6);
        s.contact.no_tensile_force = no_tensile;
        s.particles.push_back(sphere({0, 0, r + 1e-4}, r, {0, 0, -v}));
        s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}));
        s.particles[0].position.z() += v * Simulation(s).dt() * k / 20.0;
        Simulation sim(s);
        record_impact(sim, 1000000);
        worst = std::max(worst, std::abs(sim.particles().v[0].z() / v - e) / e);
      }
      report(std::string("linear") + (no_tensile ? " no-tension" : " with tension") +
                 " restitution e = " + std::to_string(e).substr(0, 3) + ", largest error over 20 positions of the step",
             worst, 0.0);
      EXPECT_LT(worst, 0.01) << "e = " << e << (no_tensile ? " no tension" : " with tension");
    }
  }
}

// Test 3's reference contact time: Al oxide, e = 1, t_c = 6.104 us.
TEST(ChungOoiTest3, AluminiumOxideElasticContactTime) {
  const double r = 0.0025, v = 3.9;
  Scene s = base_scene(HertzNormal::kName, 4000, 3.8e11, 0.23, 1.0, 0.0);
  s.particles.push_back(sphere({0, 0, r * 1.0001}, r, {0, 0, -v}));
  s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}));
  Simulation sim(s);
  const ImpactRecord rec = record_impact(sim, 1000000);
  report("Al oxide e = 1 contact time", rec.contact_time, 6.104e-6);
  EXPECT_NEAR(rec.contact_time, 6.104e-6, 0.01 * 6.104e-6);
}

}  // namespace
}  // namespace dem::test::test_chung_ooi_normal

namespace dem::test::test_chung_ooi_normal {
namespace {

// The damped impacts converge in the time step at second order, for both laws: the rebound of test
// 3's sphere at e = 0.1, 0.3, 0.5 (no tension) at t_c/N for N = 50 .. 400 against N = 3200. The Hertz
// dashpot rises as delta^(1/4) from the first touch, and scaling it at the boundary step like the
// linear law's dashpot (which jumps) left an error of order dt^(5/4): the slope was 1.0 over N = 50-400.
double rebound(std::string_view law, double e, double n) {
  const double r = 0.0025, v = 3.9;
  Scene s = base_scene(law, 4000, 3.8e11, 0.23, e, 0.0, 1e7);
  s.particles.push_back(sphere({0, 0, r * 1.0001}, r, {0, 0, -v}));
  s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}));
  const double contact_time = Simulation(s).time_step().contact_time;  // at twice the impact speed: a scale
  s.time.dt = contact_time / n;
  s.time.allow_unstable_dt = true;
  Simulation sim(s);
  record_impact(sim, 10000000);
  return sim.particles().v[0].z() / v;
}

TEST(RestitutionConvergence, IsSecondOrderInTheStep) {
  for (std::string_view law : {HertzNormal::kName, LinearNormal::kName}) {
    double worst_coarse = 0, worst_fine = 0;
    for (double e : {0.1, 0.3, 0.5}) {
      const double exact = rebound(law, e, 3200);
      worst_coarse = std::max(worst_coarse, std::abs(rebound(law, e, 50) - exact));
      worst_fine = std::max(worst_fine, std::abs(rebound(law, e, 400) - exact));
    }
    const double order = std::log(worst_coarse / worst_fine) / std::log(8.0);
    std::printf("[ measured ] %s restitution: order of convergence over N = 50..400: %.2f\n",
                law == HertzNormal::kName ? "hertz" : "linear", order);
    EXPECT_GT(order, 1.6) << law;
  }
}

}  // namespace
}  // namespace dem::test::test_chung_ooi_normal
