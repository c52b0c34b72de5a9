// Breakable ballast stones (BallastDEM section 4.1.2): stones built as bonded agglomerates of small
// spheres. Each stone is one fragment of its own (bonds never join two stones), its spheres weigh
// the stone's mass, and a stone crushed slowly between two plates gives a force-displacement curve
// with a peak and a drop at breakage, the peak rising with the bonds' strength.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <sstream>

#include "sim/simulation.hpp"
#include "spec/spec_loader.hpp"
#include "support/report.hpp"
#include "support/scenes.hpp"
#include "support/spec_problems.hpp"

namespace dem::test::test_breakable_stones {
namespace {

constexpr double kDensity = 2600, kSphere = 0.003;

// `count` breakable stones of about `mass` kg (bounded to +-10%) in a 0.3 m box, bonds of the
// given strength (none when 0), the given walls (JSON array items), no gravity.
std::string stone_spec(int count, double mass, double strength, const std::string& walls, double duration,
                       double sphere_radius = kSphere) {
  std::ostringstream s;
  s.precision(17);
  s << R"({"name": "breakable stones",
  "materials": [{"name": "rock", "density": )"
    << kDensity << R"(, "normalStiffness": 2e6}, {"name": "steel", "rigid": true}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.3, "friction": 0.5},
                   {"a": "rock", "b": "steel", "restitution": 0.3, "friction": 0.5}],
  "contact": {"normal": "LINEAR"},
  "ballastStones": [{"count": )"
    << count << R"(, "massLogMean": )" << std::log(mass) << R"(, "massLogSigma": 0.05,
                     "massMin": )"
    << 0.9 * mass << R"(, "massMax": )" << 1.1 * mass << R"(, "minSpheres": 3, "maxSpheres": 8,
                     "min": {"x": -0.15, "y": -0.15, "z": -0.15}, "max": {"x": 0.15, "y": 0.15, "z": 0.15},
                     "material": "rock", "seed": 3, "bonded": {"sphereRadius": )"
    << sphere_radius << R"(}}],)";
  if (strength > 0)
    s << R"("bonds": {"youngsModulus": 1e9, "tensileStrength": )" << strength << R"(, "shearStrength": )"
      << 2 * strength << R"(},)";
  s << R"(
  "walls": [)"
    << walls << R"(],
  "numerics": {"localDamping": 0.7},
  "time": {"duration": )"
    << duration << R"(},
  "outputs": {"everySteps": 100000000}})";
  return s.str();
}

Scene scene_of(const std::string& json) { return spec::to_scene(spec::parse_json(json)); }

TEST(BreakableStones, EachStoneIsOnePieceOfBondedSpheresWeighingItsMass) {
  const double mass = 0.05;
  Simulation sim(scene_of(stone_spec(6, mass, 1e6, "", 1e-3)));
  const Scene& scene = sim.scene();
  const double sphere = sphere_mass(kDensity, kSphere);
  std::vector<int> spheres_of(6, 0);
  for (const ParticleInit& p : scene.particles) {
    ASSERT_GE(p.stone, 0);
    ASSERT_LT(p.stone, 6);
    EXPECT_EQ(p.radius, kSphere);
    EXPECT_EQ(p.clump, -1) << "a breakable stone is not a rigid clump";
    ++spheres_of[p.stone];
  }
  for (int s = 0; s < 6; ++s) {
    const double got = spheres_of[s] * sphere;
    std::printf("stone %d: %d spheres, %.5f kg\n", s + 1, spheres_of[s], got);
    EXPECT_GE(got, 0.9 * mass - sphere);  // within the bounds, to about one sphere's mass
    EXPECT_LE(got, 1.1 * mass + sphere);
  }
  // bonds join spheres of one stone only, and every stone is one fragment
  const std::vector<int>& id = sim.particles().id;
  for (const Bond& b : sim.bonds().bonds()) EXPECT_EQ(scene.particles[id[b.i]].stone, scene.particles[id[b.j]].stone);
  const std::vector<int> fragment = sim.fragments();
  std::set<std::pair<int, int>> fragment_of_stone;
  for (std::size_t i = 0; i < fragment.size(); ++i)
    fragment_of_stone.insert({scene.particles[id[i]].stone, fragment[i]});
  EXPECT_EQ(fragment_of_stone.size(), 6u) << "each stone one fragment, no stone split";
  EXPECT_GT(sim.bonds().bonds().size(), 4u * scene.particles.size())
      << "an fcc fill: 12 bonded neighbours inside, fewer at the surface";
}

// Spheres of two stones that touch are not glued: bonds follow the stone, not the contact.
TEST(BreakableStones, BondsNeverJoinTwoStones) {
  Scene s = base_scene(LinearNormal::kName, kDensity, 1e9, 0.25, 0.3, 0.5, 1e6);
  for (int k = 0; k < 4; ++k) {
    s.particles.push_back(sphere({2 * kSphere * k, 0, 0}, kSphere));
    s.particles.back().stone = k < 2 ? 0 : 1;
  }
  BondSettings b;
  b.youngs_modulus = 1e9;
  b.tensile_strength = b.shear_strength = 1e6;
  s.bonds = b;
  Simulation sim(s);
  ASSERT_EQ(sim.bonds().bonds().size(), 2u);
  const std::vector<int> fragment = sim.fragments();
  EXPECT_EQ(*std::max_element(fragment.begin(), fragment.end()), 2);
}

// The same spec with rigid stones gives each stone exactly its drawn mass (the clump's mass; the
// rigid generator's distribution is checked against the lognormal in test_ballast_stones.cpp): the
// bonded stones must weigh those masses, to about one small sphere each.
TEST(BreakableStones, TheBondedStonesWeighTheMassesDrawn) {
  auto spec = [](bool bonded) {
    std::ostringstream json;
    json << R"({"materials": [{"name": "rock", "density": 2600, "normalStiffness": 2e6}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.3, "friction": 0.5}],
  "ballastStones": [{"count": 300, "massLogMean": -3, "massLogSigma": 0.6, "massMin": 0.01, "massMax": 0.3,
                     "min": {"x": 0, "y": 0, "z": 0}, "max": {"x": 1.5, "y": 1.5, "z": 1.5}, "material": "rock")"
         << (bonded ? R"(, "bonded": {"sphereRadius": 0.0025})" : "") << R"(}],
  "bonds": {"youngsModulus": 1e9, "tensileStrength": 1e6, "shearStrength": 1e6},
  "time": {"duration": 1e-3}})";
    return scene_of(json.str());
  };
  const Scene rigid = spec(false), bonded = spec(true);
  ASSERT_EQ(rigid.clumps.size(), 300u);
  std::vector<double> mass(300, 0.0);
  const double sphere = sphere_mass(2600, 0.0025);
  for (const ParticleInit& p : bonded.particles) mass[p.stone] += sphere;
  double worst = 0, mean = 0, want_mean = 0;
  for (int k = 0; k < 300; ++k) {
    worst = std::max(worst, std::abs(mass[k] - rigid.clumps[k].mass) / sphere);
    mean += mass[k] / 300;
    want_mean += rigid.clumps[k].mass / 300;
  }
  std::printf("300 bonded stones: largest mass error %.2f small spheres (%.2g kg each)\n", worst, sphere);
  report("bonded stones' mean mass (kg)", mean, want_mean);
  EXPECT_LE(worst, 1.0);
  EXPECT_NEAR(mean, want_mean, 0.005 * want_mean);
}

TEST(BreakableStones, BadBreakableStonesAreRefusedWithTheirPaths) {
  std::string all = spec_problems(stone_spec(1, 0.05, 0, "", 1e-3));
  EXPECT_NE(all.find("ballastStones[0].bonded: breakable stones need the spec's \"bonds\" block"), std::string::npos)
      << all;
  all = spec_problems(stone_spec(1, 0.05, 1e6, "", 1e-3, -0.003));
  EXPECT_NE(all.find("ballastStones[0].bonded.sphereRadius: must be a positive number"), std::string::npos) << all;
  all = spec_problems(stone_spec(1, 0.05, 1e6, "", 1e-3, 0.0001));
  EXPECT_NE(all.find("ballastStones[0].bonded.sphereRadius: 0.0001 m would put up to"), std::string::npos) << all;
  all = spec_problems(stone_spec(1, 0.05, 1e6, "", 1e-3, 0.05));
  EXPECT_NE(all.find("ballastStones[0]: a stone of"), std::string::npos) << all;
  EXPECT_NE(all.find("holds fewer than 2 bonded spheres"), std::string::npos) << all;
}

// The crushing test: one stone between a fixed floor plate and a top plate moving down at
// 0.05 m/s (a strain rate of ~1/s: quasi-static for a stone whose waves cross it in ~0.1 ms), until
// the press has lost 80% of its load or has squeezed 5% of the stone's height. Returns the peak
// force on the top plate and the lowest force after it.
struct Crush {
  double peak = 0, peak_at = 0, after = 0;
  int fragments_after = 0;
};

Crush crush(double strength) {
  // the stone alone first, to find its height (the same seed gives the same stone)
  const Scene alone = scene_of(stone_spec(1, 0.05, strength, "", 1e-3));
  double top = -1, bottom = 1;
  for (const ParticleInit& p : alone.particles) {
    top = std::max(top, p.position.z() + p.radius);
    bottom = std::min(bottom, p.position.z() - p.radius);
  }
  const double height = top - bottom, speed = 0.05, squeeze = 0.05 * height;
  auto plate = [](double z, const char* name, double v) {
    std::ostringstream w;
    w.precision(17);
    w << R"({"name": ")" << name << R"(", "material": "steel", "plate": {"c1": {"x": -0.1, "y": -0.1, "z": )" << z
      << R"(}, "c2": {"x": 0.1, "y": -0.1, "z": )" << z << R"(}, "c3": {"x": 0.1, "y": 0.1, "z": )" << z
      << R"(}, "c4": {"x": -0.1, "y": 0.1, "z": )" << z << R"(}})";
    if (v != 0) w << R"(, "motion": {"velocity": {"z": )" << -v << "}}";
    w << "}";
    return w.str();
  };
  const std::string walls = plate(bottom, "floor", 0) + ", " + plate(top, "press", speed);
  Simulation sim(scene_of(stone_spec(1, 0.05, strength, walls, squeeze / speed)));
  Crush c;
  std::vector<std::pair<double, double>> curve;  // displacement, force
  double highest = 0;
  while (sim.step_count() < sim.total_steps()) {
    sim.step();
    const double force = sim.boundary_loads()[1].force.z();
    curve.emplace_back(speed * sim.time(), force);
    highest = std::max(highest, force);
    if (force < 0.2 * highest) break;  // broken: the press has lost most of its load
  }
  auto peak =
      std::max_element(curve.begin(), curve.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  c.peak = peak->second;
  c.peak_at = peak->first;
  c.after = peak->second;
  for (auto it = peak; it != curve.end(); ++it) c.after = std::min(c.after, it->second);
  const std::vector<int> fragment = sim.fragments();
  c.fragments_after = *std::max_element(fragment.begin(), fragment.end());
  std::printf(
      "bond strength %.2f MPa: stone %.1f mm high, peak %.1f N at %.3f mm, then down to %.1f N at %.3f mm; %d "
      "fragments; "
      "%lld steps of %.3g s\n",
      strength / 1e6, height * 1e3, c.peak, c.peak_at * 1e3, c.after, curve.back().first * 1e3, c.fragments_after,
      static_cast<long long>(sim.step_count()), sim.dt());
  return c;
}

TEST(BreakableStones, ACrushedStoneBreaksAtAPeakThatRisesWithBondStrength) {
  const Crush weak = crush(0.25e6), middle = crush(0.5e6), strong = crush(1e6);
  for (const Crush& c : {weak, middle, strong}) {
    EXPECT_GT(c.peak, 0);
    EXPECT_LT(c.after, 0.5 * c.peak) << "the force drops at breakage";
    EXPECT_GT(c.fragments_after, 1) << "the stone broke";
  }
  EXPECT_GT(middle.peak, 1.2 * weak.peak);
  EXPECT_GT(strong.peak, 1.2 * middle.peak);
}

}  // namespace
}  // namespace dem::test::test_breakable_stones
