// The tangential and rolling springs are passive: friction can only take energy out of an impact. Hertz-Mindlin's
// spring stiffness k_t = 8 G* a grows with the contact radius a; with the displacement held while
// a grows, the spring's energy k_t |xi|^2 / 2 grew with nothing paying for it, and the spring gave
// it to the bodies as it relaxed (an independent tester's finding: in an elastic oblique impact the
// tangential force did up to 1.24% of the kinetic energy of net work on the bodies, the same at
// every step). The check: with no dashpot (e = 1), the mechanical energy of kinetic energy and both
// springs' energy never rises above what it was, at a step fine enough that velocity Verlet's own
// error is far below the finding's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "support/impact.hpp"

namespace dem::test::test_spring_passivity {
namespace {

struct EnergyTrace {
  double start = 0;
  double worst_rise = 0;  // the most the energy rose above its lowest value so far, over start
};

EnergyTrace trace_impact(Scene s, double steps_per_contact) {
  const double contact_time = Simulation(s).time_step().contact_time;
  s.time.dt = contact_time / steps_per_contact;
  s.time.allow_unstable_dt = true;
  Simulation sim(s);
  EnergyTrace out;
  out.start = sim.mechanical_energy();
  double lowest = out.start;
  for (int k = 0; k < 4 * steps_per_contact; ++k) {
    sim.step();
    const double e = sim.mechanical_energy();
    out.worst_rise = std::max(out.worst_rise, e - lowest);
    lowest = std::min(lowest, e);
  }
  out.worst_rise /= out.start;
  return out;
}

// Al alloy spheres of R = 0.1 m (Chung & Ooi's), e = 1, mu = 0.4, at v_n = 0.2 and v_t = 0.1 m/s:
// the contact sticks at first and slips near the end (tan 0.5 is below 3.5 mu (1 + e) = 2.8).
Scene oblique_impact(std::string_view law, bool on_a_sphere) {
  const double r = 0.1, vn = 0.2, vt = 0.1;
  Scene s = base_scene(law, 2699, 7.0e10, 0.30, 1.0, 0.4, 1e7);
  if (on_a_sphere) {
    s.particles.push_back(sphere({0, 0, 2 * r * 1.00001}, r, {vt, 0, -vn}));
    s.particles.push_back(sphere({0, 0, 0}, r));
  } else {
    s.particles.push_back(sphere({0, 0, r * 1.00001}, r, {vt, 0, -vn}));
    s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}));
  }
  return s;
}

TEST(SpringPassivity, AnElasticObliqueImpactNeverGainsEnergy) {
  for (std::string_view law : {LinearNormal::kName, HertzNormal::kName}) {
    for (bool on_a_sphere : {false, true}) {
      const EnergyTrace fine = trace_impact(oblique_impact(law, on_a_sphere), 800);
      std::printf("[ measured ] %s on a %s, 800 steps per contact: energy rose by at most %.2e of it\n",
                  std::string(law).c_str(), on_a_sphere ? "sphere" : "plane", fine.worst_rise);
      EXPECT_LT(fine.worst_rise, 1e-5) << law << (on_a_sphere ? " sphere" : " plane");
    }
  }
}

// The rolling spring (EPSD, k_r = 2.25 k_n mu_r^2 R*^2) keeps its moment as k_n changes; with Hertz's
// k_n growing and falling with the overlap, unloading at a held moment would raise its energy
// |M|^2 / 2 k_r. A spinning sphere dropped on a plane and on a sphere, e = 1.
TEST(SpringPassivity, TheRollingSpringNeverGainsEnergy) {
  for (std::string_view law : {LinearNormal::kName, HertzNormal::kName}) {
    for (bool on_a_sphere : {false, true})
      for (double spin : {0.5, 20.0}) {
        Scene s = oblique_impact(law, on_a_sphere);
        set_rolling(s, EpsdRolling::kName, 0.1);
        s.contact.parameters.set(EpsdRolling::kDampingRatio.field, 0);  // nothing to hide a gain
        s.particles[0].angular_velocity = Vec3(0, spin, 0);
        const EnergyTrace fine = trace_impact(s, 800);
        std::printf("[ measured ] %s + EPSD on a %s, spin %g, 800 steps per contact: energy rose by at most %.2e\n",
                    std::string(law).c_str(), on_a_sphere ? "sphere" : "plane", spin, fine.worst_rise);
        EXPECT_LT(fine.worst_rise, 1e-5) << law << (on_a_sphere ? " sphere" : " plane");
      }
  }
}

}  // namespace
}  // namespace dem::test::test_spring_passivity
