// Chung & Ooi (2011) tests 4-8: oblique impacts in gross sliding, against rigid-body impact theory.
// Test 4 also against the numbers of validation.md section 1.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/impact.hpp"
#include "support/impulse.hpp"
#include "support/report.hpp"

namespace dem::test::test_chung_ooi_oblique {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

Body body_of(const Simulation& sim, int k) {
  const Particles& p = sim.particles();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.id[i] != k) continue;
    Body b;
    b.v = p.v[i];
    b.w = p.w[i];
    b.m = p.mass[i];
    b.inertia = 0.4 * p.mass[i] * p.radius[i] * p.radius[i];
    b.r = p.radius[i];
    return b;
  }
  return {};
}

// Runs one impact and compares the velocity and spin changes of every body with impact theory:
// each change within 1% of the size of that change. The normal is the line of the two centres,
// or the plane's.
void check_against_impact_theory(Scene s, double e, double mu, const std::string& label) {
  const bool two = s.particles.size() == 2;
  const Vec3 n = two ? Vec3((s.particles[0].position - s.particles[1].position).normalized())
                     : std::get<PlaneShape>(s.walls[0].shape).normal;
  Simulation sim(std::move(s));
  Body i0 = body_of(sim, 0), j0 = two ? body_of(sim, 1) : Body{};
  const ImpactResult expected = impact_in_gross_sliding(i0, j0, n, e, mu);
  ASSERT_TRUE(expected.gross_sliding) << label << ": set-up is not in gross sliding";
  record_impact(sim, 1000000);
  auto check = [&](const Vec3& before, const Vec3& after, const Vec3& want, const char* what) {
    const double change = (want - before).norm();
    report(label + " " + what + " change", (after - before).norm(), change);
    EXPECT_LE((after - want).norm(), 0.01 * change)
        << label << " " << what << ": got " << after.transpose() << " want " << want.transpose();
  };
  const Body i1 = body_of(sim, 0);
  check(i0.v, i1.v, expected.i.v, "v_i");
  check(i0.w, i1.w, expected.i.w, "w_i");
  if (two) {
    const Body j1 = body_of(sim, 1);
    check(j0.v, j1.v, expected.j.v, "v_j");
    check(j0.w, j1.w, expected.j.w, "w_j");
  }
}

// The same scene turned by `turn` (positions, velocities, spins, planes) and, for free bodies,
// moving with `drift` on top: impact theory must hold in any frame.
Scene in_frame(Scene s, const Quat& turn, const Vec3& drift) {
  for (ParticleInit& p : s.particles) {
    p.position = turn * p.position;
    p.velocity = turn * p.velocity + drift;
    p.angular_velocity = turn * p.angular_velocity;
  }
  for (WallInit& w : s.walls) {
    PlaneShape& plane = std::get<PlaneShape>(w.shape);
    plane.point = turn * plane.point;
    plane.normal = turn * plane.normal;
  }
  return s;
}

// Each case in the test's own frame, and turned to an arbitrary 3D normal (with the centre of mass
// moving, for two spheres).
void expect_matches_impact_theory(const Scene& s, double e, double mu, const std::string& label) {
  check_against_impact_theory(s, e, mu, label);
  const Quat turn(Eigen::AngleAxisd(1.1, Vec3(0.3, -1, 0.6).normalized()));
  const Vec3 drift = s.walls.empty() ? Vec3(0.25, -0.4, 0.15) : Vec3::Zero();
  check_against_impact_theory(in_frame(s, turn, drift), e, mu,
                              label + ", turned" + (s.walls.empty() ? " and moving" : ""));
}

// Test 4: Al oxide sphere, 3.9 m/s at angle theta to the normal, mu = 0.092, e = 0.98.
struct ObliqueCase {
  double angle_deg, spin, rebound_deg;
};

class ObliqueImpact : public ::testing::TestWithParam<std::tuple<std::string_view, ObliqueCase>> {};

TEST_P(ObliqueImpact, SpinAndReboundAngleWithinOnePercent) {
  const auto [model, c] = GetParam();
  const double r = 0.0025, v = 3.9, mu = 0.092, e = 0.98;
  // linear: k_n = 1e7 N/m overlaps by 0.6% of R at 3.9 m/s (the force acts at r - delta/2)
  Scene s = base_scene(model, 4000, 3.8e11, 0.23, e, mu, 1e7);
  const double th = c.angle_deg * kDeg;
  s.particles.push_back(sphere({0, 0, r * 1.0001}, r, {v * std::sin(th), 0, -v * std::cos(th)}));
  s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}));
  Simulation sim(s);
  record_impact(sim, 1000000);
  const Vec3 vel = sim.particles().v[0], w = sim.particles().w[0];
  // contact point velocity after the impact: v + w x (-r n)
  const Vec3 vc = vel + w.cross(Vec3(0, 0, -r));
  const double rebound = std::atan2(vc.x(), vc.z()) / kDeg;
  const std::string label = std::string(model == HertzNormal::kName ? "hertz" : "linear") + " theta " +
                            std::to_string(static_cast<int>(c.angle_deg));
  report(label + " spin", w.norm(), c.spin);
  report(label + " rebound angle", rebound, c.rebound_deg);
  EXPECT_NEAR(w.norm(), c.spin, 0.01 * c.spin) << "theta=" << c.angle_deg;
  EXPECT_NEAR(rebound, c.rebound_deg, 0.01 * c.rebound_deg) << "theta=" << c.angle_deg;
  // tangential rebound v_t' = v_t - mu (1 + e) v_n (gross sliding)
  const double vt = v * std::sin(th) - mu * (1 + e) * v * std::cos(th);
  EXPECT_NEAR(vel.x(), vt, 0.01 * vt);
}

INSTANTIATE_TEST_SUITE_P(ChungOoiTest4, ObliqueImpact,
                         ::testing::Combine(::testing::Values(HertzNormal::kName, LinearNormal::kName),
                                            ::testing::Values(ObliqueCase{40, 544.2, 11.62},
                                                              ObliqueCase{50, 456.7, 29.49},
                                                              ObliqueCase{85, 61.9, 84.81})),
                         [](const auto& info) {
                           return std::string(std::get<0>(info.param) == HertzNormal::kName ? "hertz" : "linear") +
                                  "_" + std::to_string(static_cast<int>(std::get<1>(info.param).angle_deg)) + "deg";
                         });

// Tests 5-8 use Al alloy spheres (E 7.0e10 Pa, nu 0.30, rho 2699) of R = 0.1 m, v_n = 0.2 m/s,
// e = 0.5 and mu = 0.4, in the gross-sliding range of each test, at the engine's defaults: no
// tensile force (impact theory has none; with tension the pull at parting has no friction, and the
// spin came out 3.3% high), and for the linear law C_s = C_n (with the manuals' C_s = 0 each contact
// began with a stick phase while the spring stretched to mu F_n: up to 2% less friction impulse).
constexpr double kR = 0.1, kVn = 0.2, kE = 0.5, kMu = 0.4;

Scene alloy_scene(std::string_view model, double mu = kMu) {
  return base_scene(model, 2699, 7.0e10, 0.30, kE, mu, 1e7);
}

class TestsFiveToEight : public ::testing::TestWithParam<std::string_view> {};

// Test 5: onto a plane with spin only (no tangential velocity): the spin drives the sliding.
TEST_P(TestsFiveToEight, Test5PlaneWithSpin) {
  for (double w0 : {-20.0, -8.0, 8.0, 20.0}) {
    Scene s = alloy_scene(GetParam());
    s.particles.push_back(sphere({0, 0, kR * 1.00001}, kR, {0, 0, -kVn}, {0, w0, 0}));
    s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}));
    expect_matches_impact_theory(s, kE, kMu, "test 5, w0=" + std::to_string(w0));
  }
}

// Test 6: onto a plane with a tangential velocity and a spin, topspin and backspin.
TEST_P(TestsFiveToEight, Test6PlaneWithVelocityAndSpin) {
  for (double w0 : {-30.0, -10.0, 20.0, 40.0}) {
    Scene s = alloy_scene(GetParam());
    s.particles.push_back(sphere({0, 0, kR * 1.00001}, kR, {1.0, 0, -kVn}, {0, w0, 0}));
    s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}));
    expect_matches_impact_theory(s, kE, kMu, "test 6, w0=" + std::to_string(w0));
  }
}

// Test 7: two identical spheres, equal and opposite normal velocities, spins of either sense.
TEST_P(TestsFiveToEight, Test7IdenticalSpheresWithSpin) {
  for (auto [wa, wb] : {std::pair{10.0, 10.0}, std::pair{15.0, -5.0}, std::pair{-20.0, 0.0}}) {
    Scene s = alloy_scene(GetParam());
    s.particles.push_back(sphere({0, 0, -kR * 1.00001}, kR, {0, 0, kVn / 2}, {0, wa, 0}));
    s.particles.push_back(sphere({0, 0, kR * 1.00001}, kR, {0, 0, -kVn / 2}, {0, wb, 0}));
    expect_matches_impact_theory(s, kE, kMu, "test 7, w=" + std::to_string(wa) + "," + std::to_string(wb));
  }
}

// Test 8: spheres of R and R/2, constant normal velocity, varying tangential velocities. Spheres that
// slide past each other change their overlap by about dx^2 / (2 R*) over the tangential travel dx of
// one contact, which impact theory ignores; it stays below 0.5% of the overlap for vt <= v_n, so
// this test uses mu = 0.05 to be in gross sliding there.
TEST_P(TestsFiveToEight, Test8DifferentSizesWithTangentialVelocity) {
  const double mu = 0.05;
  for (double vt : {0.1, 0.15, 0.2}) {
    Scene s = alloy_scene(GetParam(), mu);
    s.particles.push_back(sphere({0, 0, -kR * 1.00001}, kR, {vt / 2, 0, kVn / 2}));
    s.particles.push_back(sphere({0, 0, kR / 2 * 1.00002}, kR / 2, {-vt / 2, 0, -kVn / 2}));
    expect_matches_impact_theory(s, kE, mu, "test 8, vt=" + std::to_string(vt));
  }
}

INSTANTIATE_TEST_SUITE_P(ChungOoi, TestsFiveToEight, ::testing::Values(HertzNormal::kName, LinearNormal::kName),
                         [](const auto& info) {
                           return std::string(info.param == HertzNormal::kName ? "hertz" : "linear");
                         });

}  // namespace
}  // namespace dem::test::test_chung_ooi_oblique
