// Radius growth (the PDEM-EGD manual's GROWTH and NGROWTH): a loose random packing at a solid fraction of 0.25
// grown by (0.5 / 0.25)^(1/3) in a closed box packs to 0.5 without excessive overlap.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/runner.hpp"
#include "sim/simulation.hpp"
#include "spec/spec_loader.hpp"
#include "support/report.hpp"

namespace dem::test::test_growth {
namespace {

// The documented set-up (docs/spec.md, "Growth"): 0.25 grown by 2^(1/3) over 20,000 steps in a
// closed box, local damping 0.5; `gravity`: the z component, "" for none.
std::string growth_spec(const std::string& gravity = "", double restitution = 0.3, double local_damping = 0.5) {
  const double factor = std::cbrt(0.5 / 0.25);
  std::string text = R"({
  "materials": [{"name": "rock", "density": 2600, "normalStiffness": 1e5}, {"name": "box", "rigid": true}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": E, "friction": 0.3},
                   {"a": "rock", "b": "box", "restitution": E, "friction": 0.3}],
  "packings": [{"min": {}, "max": {"x": 0.1, "y": 0.1, "z": 0.1}, "material": "rock", "solidFraction": 0.25,
                "sizes": {"kind": "UNIFORM", "dMin": 0.008, "dMax": 0.012}}],
  "walls": [{"material": "box", "plane": {"normal": {"z": 1}}}, {"material": "box", "plane": {"point": {"z": 0.1}, "normal": {"z": -1}}},
            {"material": "box", "plane": {"normal": {"x": 1}}}, {"material": "box", "plane": {"point": {"x": 0.1}, "normal": {"x": -1}}},
            {"material": "box", "plane": {"normal": {"y": 1}}}, {"material": "box", "plane": {"point": {"y": 0.1}, "normal": {"y": -1}}}],
  "growth": {"factor": FACTOR, "steps": 20000},
  "numerics": {"localDamping": DAMPING},
  "time": {"steps": 30000}GRAVITY
})";
  text.replace(text.find("FACTOR"), 6, std::to_string(factor));
  for (std::size_t at; (at = text.find("\"restitution\": E")) != std::string::npos;)
    text.replace(at + 15, 1, std::to_string(restitution));
  text.replace(text.find("DAMPING"), 7, std::to_string(local_damping));
  text.replace(text.find("GRAVITY"), 7, gravity.empty() ? "" : R"(, "gravity": {"z": )" + gravity + "}");
  return text;
}

TEST(Growth, LoosePackingGrowsToTheTargetSolidFraction) {
  Simulation sim(spec::to_scene(spec::parse_json(growth_spec())));
  while (sim.step_count() < sim.total_steps()) sim.step();
  double volume = 0;
  for (double r : sim.particles().radius) volume += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const double fraction = volume / 1e-3;
  report("grown packing: solid fraction", fraction, 0.5);
  EXPECT_NEAR(fraction, 0.5, 0.01 * 0.5);
  const ContactSummary contacts = sim.contact_summary();
  report("grown packing: largest overlap / radius", contacts.max_overlap_fraction, 0.0);
  EXPECT_LT(contacts.max_overlap_fraction, 0.05);
  for (std::size_t i = 0; i < sim.particles().size(); ++i) {  // all still in the box
    const Vec3& x = sim.particles().x[i];
    ASSERT_TRUE((x.array() > 0).all() && (x.array() < 0.1).all()) << i;
  }
}

// Growth is a source of energy (overlaps grow, masses grow at their speed, weight grows): the
// stability guard takes it into account and lets the documented set-up run to its end, with and
// without gravity.
TEST(Growth, TheGuardLetsAGrowingPackingRun) {
  for (const std::string gravity : {"", "-9.81"}) {
    Simulation sim(spec::to_scene(spec::parse_json(growth_spec(gravity))));
    const RunOutcome outcome = run(sim, {});
    EXPECT_TRUE(outcome.ok) << (gravity.empty() ? "no gravity: " : "gravity: ") << outcome.error;
    EXPECT_EQ(outcome.steps, 30000);
  }
}

// The PDEM-EGD manual's own restitution (eps 0.2, section 4.2.1) and no local damping: the contacts'
// dashpots pull while grown spheres push apart, which growth's work must not count (it was stopped
// at step 100).
TEST(Growth, TheGuardLetsAGrowingPackingWithStronglyDampedContactsRun) {
  Simulation sim(spec::to_scene(spec::parse_json(growth_spec("", 0.2, 0.0))));
  const RunOutcome outcome = run(sim, {});
  EXPECT_TRUE(outcome.ok) << outcome.error;
  EXPECT_EQ(outcome.steps, 30000);
}

}  // namespace
}  // namespace dem::test::test_growth
