// The spec's sources (JobSpec.sources, spec/sources_section.cpp): a stream of sand as a user writes
// it, and each mistake refused with the path of the field and what is wrong.
#include <gtest/gtest.h>

#include <string>

#include "spec/spec_loader.hpp"
#include "support/spec_problems.hpp"

namespace dem::test {
namespace {

// An empty box that sand is poured into.
std::string with_sources(const std::string& sources, const std::string& time = R"("duration": 0.5)",
                         const std::string& extra = "") {
  return R"({
  "materials": [
    {"name": "sand", "density": 2650, "normalStiffness": 2e3},
    {"name": "steel", "rigid": true}
  ],
  "interactions": [
    {"a": "sand", "b": "sand", "restitution": 0.3, "friction": 0.5},
    {"a": "sand", "b": "steel", "restitution": 0.3, "friction": 0.5}
  ],
  "walls": [
    {"name": "floor", "material": "steel", "plane": {"normal": {"z": 1}}},
    {"name": "lid", "material": "steel", "plate": {"c1": {"x": -0.05, "y": -0.05, "z": 0.3},
      "c2": {"x": 0.05, "y": -0.05, "z": 0.3}, "c3": {"x": 0.05, "y": 0.05, "z": 0.3}, "c4": {"x": -0.05, "y": 0.05, "z": 0.3}}}
  ],
  "gravity": {"z": -9.81},
  )" + extra +
         R"("time": {)" + time + R"(},
  "sources": [)" +
         sources +
         R"(]
})";
}

const char* kSand = R"({"name": "sand", "min": {"x": -0.05, "y": -0.05, "z": 0.25},
  "max": {"x": 0.05, "y": 0.05, "z": 0.3}, "material": "sand",
  "sizes": {"kind": "UNIFORM", "dMin": 0.004, "dMax": 0.006}, "massRate": 0.05, "velocity": {"z": -1}})";

TEST(SourceSpec, ASandStreamLoadsAsWrittenIntoAnEmptyScene) {
  const Scene scene = spec::to_scene(spec::parse_json(with_sources(kSand)));
  EXPECT_TRUE(scene.particles.empty());
  ASSERT_EQ(scene.sources.size(), 1u);
  const ParticleSource& s = scene.sources[0];
  EXPECT_EQ(s.name, "sand");
  EXPECT_EQ(s.region, ParticleSource::Region::Box);
  EXPECT_EQ(s.box.min, Vec3(-0.05, -0.05, 0.25));
  EXPECT_EQ(s.sizes.kind, SizeKind::Uniform);
  EXPECT_EQ(s.mass_rate, 0.05);
  EXPECT_EQ(s.velocity, Vec3(0, 0, -1));
  EXPECT_EQ(s.seed, 1u);
  EXPECT_EQ(s.stage, -1);
  EXPECT_TRUE(std::isinf(s.end));
}

TEST(SourceSpec, ATotalMassOfZeroIsASourceThatInsertsNothing) {
  const std::string sand = kSand;
  const std::string zero = sand.substr(0, sand.size() - 1) + R"(, "mass": 0})";
  const Scene scene = spec::to_scene(spec::parse_json(with_sources(zero)));
  ASSERT_EQ(scene.sources.size(), 1u);
  EXPECT_EQ(scene.sources[0].total_mass, 0);
  EXPECT_EQ(scene.sources[0].total_count, -1);
  const Scene open = spec::to_scene(spec::parse_json(with_sources(kSand)));
  EXPECT_TRUE(std::isinf(open.sources[0].total_mass));
  EXPECT_EQ(open.sources[0].total_count, -1);
  // a stream that would overrun the particle limit over its window stops at its total well within it
  const std::string long_stream = sand.substr(0, sand.size() - 1) + R"(, "end": 1e6, "mass": 0.01})";
  EXPECT_EQ(spec_problems(with_sources(long_stream, R"("duration": 2e6)")), "");
}

TEST(SourceSpec, AFaceSourceTakesTheLargestDiameterAsItsDepth) {
  const Scene scene = spec::to_scene(spec::parse_json(with_sources(
      R"({"face": "lid", "material": "sand", "sizes": {"kind": "ONE_SIZE", "mean": 0.005}, "countRate": 100})")));
  ASSERT_EQ(scene.sources.size(), 1u);
  EXPECT_EQ(scene.sources[0].region, ParticleSource::Region::Face);
  EXPECT_EQ(scene.sources[0].face_wall, 1);
  EXPECT_EQ(scene.sources[0].depth, 0.005);
  EXPECT_EQ(scene.sources[0].name, "source 1");
}

TEST(SourceSpec, EachMistakeIsNamedWithItsPath) {
  const std::string sizes = R"("material": "sand", "sizes": {"kind": "ONE_SIZE", "mean": 0.005})";
  const std::string box = R"("min": {"z": 0.1}, "max": {"x": 0.05, "y": 0.05, "z": 0.2})";
  const std::pair<std::string, std::string> cases[] = {
      {"{" + sizes + R"(, "massRate": 1})",
       "sources[0]: give its region: a box (min and max) or the faces of a wall (face), one of them"},
      {"{" + sizes + ", " + box + R"(, "face": "lid", "massRate": 1})",
       "sources[0]: give its region: a box (min and max) or the faces of a wall (face), one of them"},
      {"{" + sizes + ", " + box + "}",
       "sources[0]: give massRate (kg/s) or countRate (particles/s), one of them, positive"},
      {"{" + sizes + ", " + box + R"(, "massRate": 1, "countRate": 5})",
       "sources[0]: give massRate (kg/s) or countRate (particles/s), one of them, positive"},
      {"{" + sizes + R"(, "face": "roof", "massRate": 1})", "sources[0].face: no wall is named \"roof\""},
      {"{" + sizes + R"(, "face": "floor", "massRate": 1})",
       "sources[0].face: wall \"floor\" is an infinite plane: give a plate or a mesh"},
      {"{" + sizes + R"(, "min": {"z": 0.1}, "max": {"x": 0.004, "y": 0.05, "z": 0.2}, "massRate": 1})",
       "sources[0].max: the box must be at least the largest diameter (0.005 m) wide in x, y and z, above min"},
      {"{" + sizes + ", " + box + R"(, "massRate": 1, "start": -1})",
       "sources[0].start: must be in [0, 1e+12] s (got -1)"},
      {"{" + sizes + ", " + box + R"(, "massRate": 1, "start": 0.2, "end": 0.1})",
       "sources[0].end: must be after start and at most 1e+12 s (got 0.1)"},
      {"{" + sizes + ", " + box + R"(, "massRate": 1, "stage": "pour"})",
       "sources[0].stage: no stage is named \"pour\""},
      {"{" + sizes + ", " + box + R"(, "massRate": 1, "everySteps": -2})",
       "sources[0].everySteps: must be in [0, 2^53] (got -2)"},
      {"{" + sizes + ", " + box + R"(, "countRate": 2e9})", "sources[0].countRate: must be in (0, 1e+09] (got 2e+09)"},
      {R"({"material": "steel", "sizes": {"kind": "ONE_SIZE", "mean": 0.005}, )" + box + R"(, "massRate": 1})",
       "sources[0].material: material \"steel\" is rigid: only walls may use it"},
      {R"({"material": "sand", "sizes": {"kind": "NORMAL", "mean": 0.005, "spread": 1, "dMin": 0.0049, "dMax": 0.0050001}, )" +
           box + R"(, "massRate": 1})",
       "sources[0].sizes: hardly any size drawn"},
      {"{" + sizes + ", " + box + R"(, "massRate": -1})", "sources[0].massRate: must be a positive number (got -1)"},
      {"{" + sizes + ", " + box + R"(, "massRate": 1, "mass": -1})", "sources[0].mass: must be"},
      {"{" + sizes + ", " + box + R"(, "massRate": 1, "count": -3})", "sources[0].count: must be"},
      {"{" + sizes + ", " + box + R"(, "massRate": 1, "mass": 1, "count": 3})",
       "sources[0]: give mass (kg) or count (particles), one of them"},
      {"{" + sizes + ", " + box + R"(, "massRate": 1, "start": 0.5})",
       "sources[0].start: the source starts at 0.5 s, when its run of 0.5 s is over: it would never insert"},
      {"{" + sizes + ", " + box + R"(, "massRate": 1, "name": "a\nb"})",
       "sources[0].name: must not hold control characters (byte 1 is 0x0A)"},
  };
  for (const auto& [source, problem] : cases) {
    const std::string problems = spec_problems(with_sources(source));
    EXPECT_NE(problems.find(problem), std::string::npos) << source << "\ngave:\n" << problems;
  }
}

// What a source would insert over the run is counted against the particle limit: over its window,
// not past the run's end (an end of 1e9 s on a 0.5 s run was refused as 1e11 particles).
TEST(SourceSpec, TheParticlesASourceWouldInsertOverTheRunCountAgainstTheLimit) {
  const std::string source = R"({"material": "sand", "sizes": {"kind": "ONE_SIZE", "mean": 0.005},
    "min": {"x": -0.05, "y": -0.05, "z": 0.25}, "max": {"x": 0.05, "y": 0.05, "z": 0.3}, "massRate": 1, "end": 1e6})";
  // 1 kg/s of 5 mm grains for 1e6 s: 5.8 billion particles
  EXPECT_NE(spec_problems(with_sources(source, R"("duration": 2e6)")).find("sources[0]: would make 5"),
            std::string::npos);
  EXPECT_EQ(spec_problems(with_sources(source)), "");  // for 0.5 s: 2,900
}

// Particles due while the face's wall is away would all enter at once when it comes (a tester's source
// on a plate added at the third stage inserted 189 grains in one step): refused.
TEST(SourceSpec, AFaceSourceMustHaveItsWallThereWheneverItIsActive) {
  const std::string source = R"({"face": "lid", "material": "sand", "sizes": {"kind": "ONE_SIZE", "mean": 0.005},
    "countRate": 100})";
  const std::string stages =
      R"("stages": [{"name": "a", "steps": 10, "removeWalls": ["lid"]}, {"name": "b", "steps": 10,
    "addWalls": [{"name": "lid2", "material": "steel", "plate": {"c1": {"x": -0.05, "y": -0.05, "z": 0.2},
      "c2": {"x": 0.05, "y": -0.05, "z": 0.2}, "c3": {"x": 0.05, "y": 0.05, "z": 0.2}, "c4": {"x": -0.05, "y": 0.05, "z": 0.2}}}]}],)";
  const std::string no_time = R"("dtFraction": 0.02)";
  EXPECT_NE(spec_problems(with_sources(source, no_time, stages))
                .find("sources[0].face: wall \"lid\" is not there at stage 1 (\"a\"), where the source is active"),
            std::string::npos)
      << spec_problems(with_sources(source, no_time, stages));
  const std::string later = R"({"face": "lid2", "stage": "b", "material": "sand", "sizes": {"kind": "ONE_SIZE",
    "mean": 0.005}, "countRate": 100})";
  EXPECT_EQ(spec_problems(with_sources(later, no_time, stages)), "");
}

TEST(SourceSpec, AStreamForARunInStepsIsNotCountedAheadButOneInSecondsIs) {
  const std::string many = R"({"material": "sand", "sizes": {"kind": "ONE_SIZE", "mean": 0.005}, "min": {"z": 0.1},
    "max": {"x": 0.05, "y": 0.05, "z": 0.2}, "massRate": 10})";
  EXPECT_EQ(spec_problems(with_sources(many, R"("steps": 1000)")), "");
  EXPECT_NE(spec_problems(with_sources(many, R"("duration": 1e6)")).find("would make"), std::string::npos);
}

}  // namespace
}  // namespace dem::test
