// The edges of the input range: a value whose squares or step counts would overflow is a spec error
// naming the field; an output interval longer than the run gives its first and last frames; a step
// at the stable limit, however it was computed, is accepted.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "sim/runner.hpp"
#include "sim/simulation.hpp"
#include "spec/spec_loader.hpp"
#include "support/spec_problems.hpp"

namespace dem::test {
namespace {

// One sphere falling onto a floor, with `extra` replacing the marker.
std::string spec_with(const std::string& time, const std::string& extra = "", const std::string& sphere = "") {
  return R"({
  "materials": [{"name": "rock", "density": 2600, "youngsModulus": 1e9, "poissonRatio": 0.25}, {"name": "floor", "rigid": true}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5}, {"a": "rock", "b": "floor", "restitution": 0.5}],
  "contact": {"normal": "HERTZ"},
  "particles": [{"position": {"z": 0.02}, "radius": 0.01, "material": "rock")" +
         sphere + R"(}],
  "walls": [{"material": "floor", "plane": {"normal": {"z": 1}}}],
  "gravity": {"z": -9.81},
  "time": )" +
         time + extra + "}";
}

// The problems of a spec, including those only its Simulation finds (the time step and the step count).
std::string problems(const std::string& json) {
  std::string found = spec_problems(json);
  if (!found.empty()) return found;
  try {
    Simulation sim(spec::to_scene(spec::parse_json(json)));
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(InputRange, ARunTooLongToCountIsRefusedNamingTheDuration) {
  const std::string p = problems(spec_with(R"({"duration": 1e300})"));
  EXPECT_NE(p.find("time.duration: 1e+300 s"), std::string::npos) << p;
  EXPECT_NE(p.find("more than a run can count"), std::string::npos) << p;
}

TEST(InputRange, ATinyGivenStepIsRefusedNamingTheDuration) {
  const std::string p = problems(spec_with(R"({"duration": 1, "dt": 1e-300})"));
  EXPECT_NE(p.find("time.duration:"), std::string::npos) << p;
  EXPECT_NE(p.find("(given)"), std::string::npos) << p;
}

TEST(InputRange, TooManyStepsAreRefused) {
  const std::string p = problems(spec_with(R"({"steps": 9223372036854775807})"));
  EXPECT_NE(p.find("time.steps:"), std::string::npos) << p;
}

TEST(InputRange, AnAbsurdModulusIsASpecErrorNotANegativeStepCount) {
  std::string json = spec_with(R"({"duration": 1})");
  json.replace(json.find("1e9"), 3, "1e300");
  const std::string p = problems(json);
  EXPECT_NE(p.find("materials[0].youngsModulus: must be at most 1e+15 Pa"), std::string::npos) << p;
}

TEST(InputRange, AbsurdGravityAndSpeedAreSpecErrors) {
  std::string json = spec_with(R"({"duration": 1})");
  json.replace(json.find("-9.81"), 5, "-1e300");
  EXPECT_NE(problems(json).find("gravity: must be at most 1e+09 m/s^2"), std::string::npos) << problems(json);
  const std::string fast = spec_with(R"({"duration": 1})", "", R"(, "velocity": {"x": 1e300})");
  EXPECT_NE(problems(fast).find("particles[0].velocity: must be at most 3e+08 m/s"), std::string::npos)
      << problems(fast);
  const std::string huge = spec_with(R"({"duration": 1})", "", R"(, "position": {"z": 1e200})");
  EXPECT_NE(problems(huge).find("particles[0].position"), std::string::npos) << problems(huge);
}

TEST(InputRange, AnIntervalLongerThanTheRunGivesTheFirstAndLastFrames) {
  const std::string json = spec_with(R"({"steps": 50})", R"(, "outputs": {"interval": 1e300})");
  Simulation sim(spec::to_scene(spec::parse_json(json)));
  struct Count : Observer {
    int frames = 0;
    void frame(const Simulation&) override { ++frames; }
  } count;
  EXPECT_TRUE(run(sim, {&count}).ok);
  EXPECT_EQ(count.frames, 2);
}

TEST(InputRange, AStepAtTheStableLimitIsAccepted) {
  const Simulation probe(spec::to_scene(spec::parse_json(spec_with(R"({"steps": 5})"))));
  const double limit = probe.time_step().stable_limit;
  char printed[32];
  std::snprintf(printed, sizeof printed, "%.6e", limit);  // as the report prints it (rounded either way)
  for (const std::string& dt : {std::to_string(limit), std::string(printed)}) {
    char exact[40];
    std::snprintf(exact, sizeof exact, "%.17g", dt == printed ? std::stod(printed) : limit);
    EXPECT_EQ(problems(spec_with(std::string(R"({"steps": 5, "dt": )") + exact + "}")), "") << exact;
  }
  char above[40];
  std::snprintf(above, sizeof above, "%.17g", limit * 1.001);
  EXPECT_NE(problems(spec_with(std::string(R"({"steps": 5, "dt": )") + above + "}")).find("above the stable limit"),
            std::string::npos);
}

// Quantities so small that the contact time, the bond's inertia or the step underflow: a density of
// 1e-300 once gave "dt = 0 (automatic)", valid, then a run stopped at step 0 blaming the step; a bond
// disc of 1e-80 radii wrote -nan into Energy.dat and the run "succeeded".
TEST(InputRange, TinyDensitiesRadiiStiffnessesAndBondDiscsAreSpecErrors) {
  std::string json = spec_with(R"({"duration": 1})");
  json.replace(json.find("2600"), 4, "1e-300");
  EXPECT_NE(problems(json).find("materials[0].density: must be at least 0.001 kg/m^3 (got 1e-300)"), std::string::npos)
      << problems(json);
  json = spec_with(R"({"duration": 1})");
  json.replace(json.find("\"radius\": 0.01"), 14, "\"radius\": 5e-324");
  EXPECT_NE(problems(json).find("particles[0].radius: must be at least 1e-09 m"), std::string::npos) << problems(json);
  json = spec_with(R"({"duration": 1})");
  json.replace(json.find("\"youngsModulus\": 1e9"), 20, "\"youngsModulus\": 5e-324");
  EXPECT_NE(problems(json).find("materials[0].youngsModulus: must be at least 0.001 Pa"), std::string::npos)
      << problems(json);
  const std::string bonded =
      spec_with(R"({"duration": 1})", R"(, "bonds": {"youngsModulus": 1e8, "tensileStrength": 1e6,
      "shearStrength": 1e6, "radiusMultiplier": 1e-80})");
  EXPECT_NE(problems(bonded).find("bonds.radiusMultiplier: must be at least 0.001 (got 1e-80)"), std::string::npos)
      << problems(bonded);
}

// A density given wrong is reported once (the normal model's required properties and every particle
// material's own check both reported it).
TEST(InputRange, ABadDensityIsReportedOnce) {
  std::string json = spec_with(R"({"duration": 1})");
  json.replace(json.find("2600"), 4, "-1");
  const std::string p = problems(json);
  EXPECT_NE(p.find("materials[0].density"), std::string::npos) << p;
  EXPECT_EQ(p.find("materials[0].density"), p.rfind("materials[0].density")) << p;
}

// A refused value is quoted as it was given: 0.10000001 is not "(got 0.1)".
TEST(InputRange, ARefusedValueIsQuotedInFull) {
  const std::string p = problems(spec_with(R"({"duration": 1, "dtFraction": 0.10000001})"));
  EXPECT_NE(p.find("(got 0.10000001)"), std::string::npos) << p;
}

// The step count's edges: 2^53 + 1 steps is one more than a run can count; a positive duration
// shorter than one step still runs one (5e-324 s ran none).
TEST(InputRange, StepCountsAtTheEdges) {
  EXPECT_NE(problems(spec_with(R"({"steps": 9007199254740993})")).find("time.steps:"), std::string::npos);
  EXPECT_EQ(problems(spec_with(R"({"steps": 9007199254740992})")), "");
  const Simulation sim(spec::to_scene(spec::parse_json(spec_with(R"({"duration": 5e-324})"))));
  EXPECT_EQ(sim.total_steps(), 1);
}

// A bonds block that glues nothing (no two spheres within reach) leaves the step to the contacts: it
// once shrank the step by the bonds' period all the same (3.2x for Eb = 1e8 Pa).
TEST(InputRange, BondsThatGlueNothingDoNotShortenTheStep) {
  const std::string plain = spec_with(R"({"duration": 1})");
  const std::string bonded =
      spec_with(R"({"duration": 1})", R"(, "bonds": {"youngsModulus": 1e15, "tensileStrength": 1e6,
      "shearStrength": 1e6})");
  const Simulation a(spec::to_scene(spec::parse_json(plain)));
  const Simulation b(spec::to_scene(spec::parse_json(bonded)));
  EXPECT_EQ(b.bonds().bonds().size(), 0u);
  EXPECT_EQ(a.dt(), b.dt());
}

// Every free number of a spec has a bound far beyond any scene: loads, bonds, friction, given mass
// properties, motions. Unbounded, a cyclic load's mass of 1e-300 sent the plate 5e294 m away, a
// servo of 1e300 drove it through the bed, a bond's shear ratio of 1e300 made a non-finite number at
// step 0, a rolling friction of 1e160 one at step 2062, and a clump's given mass of 1e-300 was
// blamed on time.duration; each "succeeded" or failed at run time instead of naming its field.
TEST(InputRange, EveryFreeNumberHasABound) {
  const std::string base = R"({
  "materials": [{"name": "rock", "density": 2600, "normalStiffness": 1e5}, {"name": "steel", "rigid": true}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5, "friction": FRICTION, "rollingFriction": ROLLING},
                   {"a": "rock", "b": "steel", "restitution": 0.5, "friction": 0.5}],
  "contact": {"rolling": "EPSD"},
  "clumpShapes": [{"name": "pair", "spheres": [{"radius": 0.01}, {"center": {"x": 0.01}, "radius": 0.01}],
                   "given": {"mass": GIVENMASS, "inertia": {"xx": INERTIA, "yy": 2e-6, "zz": 2e-6}}}],
  "clumps": [{"shape": "pair", "material": "rock", "position": {"z": 0.5}}],
  "particles": [{"position": {"z": 0.05}, "radius": 0.01, "material": "rock"}, {"position": {"z": 0.071}, "radius": 0.01, "material": "rock"}],
  "bonds": {"youngsModulus": 1e8, "tensileStrength": TENSILE, "shearStrength": 1e6, "shearStiffnessRatio": SHEARRATIO,
            "strengthSpread": SPREAD, "gapTolerance": GAP, "zones": [{"min": {}, "max": {"x": 1}, "strengthRatio": ZONE}]},
  "walls": [{"material": "steel", "plane": {"normal": {"z": 1}}},
            {"material": "steel", "plate": {"c1": {"z": 0.2}, "c2": {"x": 1, "z": 0.2}, "c3": {"x": 1, "y": 1, "z": 0.2}, "c4": {"y": 1, "z": 0.2}},
             "load": {"mass": LOADMASS, "cyclic": {"fMin": 1, "fMax": FMAX, "frequency": FREQ, "cycles": 2}}},
            {"material": "steel", "plate": {"c1": {"z": 0.3}, "c2": {"x": 1, "z": 0.3}, "c3": {"x": 1, "y": 1, "z": 0.3}, "c4": {"y": 1, "z": 0.3}},
             "load": {"servo": {"target": TARGET, "gain": GAIN, "maxSpeed": MAXSPEED}}},
            {"material": "steel", "plate": {"c1": {"z": 0.4}, "c2": {"x": 1, "z": 0.4}, "c3": {"x": 1, "y": 1, "z": 0.4}, "c4": {"y": 1, "z": 0.4}},
             "motion": {"amplitude": {"z": 0.1}, "frequency": MOTIONFREQ}}],
  "gravity": {"z": -9.81},
  "time": {"duration": 0.01}
})";
  const std::map<std::string, std::string> fine = {
      {"FRICTION", "0.5"}, {"ROLLING", "0.1"},  {"GIVENMASS", "0.01"}, {"INERTIA", "2e-6"},
      {"TENSILE", "1e6"},  {"SHEARRATIO", "1"}, {"SPREAD", "0.2"},     {"GAP", "0.001"},
      {"ZONE", "1"},       {"LOADMASS", "10"},  {"FMAX", "100"},       {"FREQ", "3"},
      {"TARGET", "100"},   {"GAIN", "1e-4"},    {"MAXSPEED", "0.1"},   {"MOTIONFREQ", "5"}};
  auto spec_with = [&](const std::string& field, const std::string& value) {
    std::string json = base;
    for (const auto& [key, v] : fine) {
      const std::size_t at = json.find(key);
      json.replace(at, key.size(), key == field ? value : v);
    }
    return json;
  };
  ASSERT_EQ(spec_problems(spec_with("", "")), "");
  const std::pair<const char*, std::pair<const char*, const char*>> cases[] = {
      {"FRICTION", {"1e300", "interactions[0].friction: must be at most 1000"}},
      {"ROLLING", {"1e160", "interactions[0].rollingFriction: must be in [0, 1]"}},
      {"ROLLING", {"1.5", "interactions[0].rollingFriction: must be in [0, 1]"}},
      {"GIVENMASS", {"1e-300", "clumpShapes[0].given.mass: must be at least 1e-30 kg"}},
      {"GIVENMASS", {"1e300", "clumpShapes[0].given.mass: must be at most 1e+15 kg"}},
      {"INERTIA", {"1e300", "clumpShapes[0].given.inertia: must be at most 1e+30 kg m^2"}},
      {"TENSILE", {"1e300", "bonds.tensileStrength: must be at most 1e+15 Pa"}},
      {"SHEARRATIO", {"1e300", "bonds.shearStiffnessRatio: must be at most 1000"}},
      {"SPREAD", {"1e300", "bonds.strengthSpread: must be at most 1000"}},
      {"GAP", {"1e300", "bonds.gapTolerance: must be at most 1000"}},
      {"ZONE", {"1e300", "bonds.zones[0].strengthRatio: must be at most 1000"}},
      {"LOADMASS", {"1e-300", "walls[1].load.mass: must be at least 1e-30 kg"}},
      {"LOADMASS", {"1e300", "walls[1].load.mass: must be at most 1e+15 kg"}},
      {"FMAX", {"1e300", "walls[1].load.cyclic.fMax: must be at most 1e+15 N"}},
      {"FREQ", {"1e300", "walls[1].load.cyclic.frequency: must be at most 1e+09 Hz"}},
      {"TARGET", {"1e300", "walls[2].load.servo.target: must be at most 1e+15 N"}},
      {"GAIN", {"1e300", "walls[2].load.servo.gain: must be at most 1e+06 m/(N s)"}},
      {"MAXSPEED", {"1e300", "walls[2].load.servo.maxSpeed: must be at most 3e+08 m/s"}},
      {"MOTIONFREQ", {"1e300", "walls[3].motion.frequency: must be at most 1e+09 Hz"}},
  };
  for (const auto& [field, expect] : cases) {
    const std::string p = spec_problems(spec_with(field, expect.first));
    EXPECT_NE(p.find(expect.second), std::string::npos) << field << " = " << expect.first << ":\n" << p;
  }
}

// Far from the origin a double resolves too little of a small sphere: two 1 mm spheres meeting at
// x = 9.9e8 m rebounded with e = 0.844 for 0.8 (a coordinate there is resolved to 1e-7 m, a tenth
// of their overlap). Positions past 1e9 smallest radii from the origin are refused, naming them;
// 1e8 radii away the same impact is right.
TEST(InputRange, PositionsTooFarFromTheOriginForTheSphereSizeAreRefused) {
  auto pair_at = [](double x) {
    Scene s;
    s.materials.push_back({"p", 2500, 0, 0, 1e3, false});
    s.interactions.assign(1, Interaction{0.8, 0, 0});
    s.contact.normal = LinearNormal::kName;
    s.time.steps = 100000000;
    s.outputs.animation = false;
    for (double side : {-1.0, 1.0}) {
      ParticleInit p;
      p.position = {x + side * 1.1e-3, 0, 0};
      p.velocity = {-side * 0.1, 0, 0};
      p.radius = 1e-3;
      s.particles.push_back(p);
    }
    return s;
  };
  try {
    Simulation sim(pair_at(9.9e8));
    ADD_FAILURE() << "spheres of 1 mm at 9.9e8 m were accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("from the origin"), std::string::npos) << e.what();
  }
  Simulation near(pair_at(1e5));  // 1e8 radii out
  while (near.time() < 0.05) near.step();
  EXPECT_NEAR(near.particles().v[1].x() / 0.1, 0.8, 0.01);
}

}  // namespace
}  // namespace dem::test
