// The spec's stages (JobSpec.stages, spec/stages_section.cpp): a staged job as a user writes it,
// and each mistake refused with the path of the field and what is wrong.
#include <gtest/gtest.h>

#include <string>

#include "spec/spec_loader.hpp"
#include "support/spec_problems.hpp"

namespace dem::test {
namespace {

// A key block's set-up in four stages: fill under gravity, grow, bond, release (the funnel goes).
std::string staged(const std::string& stages, const std::string& extra = "") {
  return R"({
  "name": "staged",
  "materials": [
    {"name": "rock", "density": 2500, "normalStiffness": 1e5},
    {"name": "steel", "rigid": true}
  ],
  "interactions": [
    {"a": "rock", "b": "rock", "restitution": 0.5, "friction": 0.3},
    {"a": "rock", "b": "steel", "restitution": 0.5, "friction": 0.3}
  ],
  "particles": [
    {"position": {"z": 0.05}, "radius": 0.01, "material": "rock"},
    {"position": {"x": 0.05, "z": 0.05}, "radius": 0.01, "material": "rock"}
  ],
  "walls": [
    {"name": "floor", "material": "steel", "plane": {"normal": {"z": 1}}},
    {"name": "funnel", "material": "steel", "plane": {"point": {"x": -0.1}, "normal": {"x": 1}}}
  ],
  "bonds": {"youngsModulus": 1e8, "tensileStrength": 1e6, "shearStrength": 1e6},
  "gravity": {"z": -9.81},
  )" + extra +
         R"(
  "stages": [)" +
         stages + R"(]
})";
}

const char* kFourStages = R"(
    {"name": "fill", "duration": 0.2, "untilKineticEnergy": 1e-6},
    {"name": "grow", "duration": 0.1, "growthFactor": 1.05},
    {"name": "bond", "steps": 10, "bond": true},
    {"name": "release", "duration": 0.5, "removeWalls": ["funnel"], "gravity": {"z": -9.81, "x": 1},
     "interactions": [{"a": "rock", "b": "steel", "restitution": 0.5, "friction": 0.6}],
     "addWalls": [{"name": "lid", "material": "steel", "plane": {"point": {"z": 1}, "normal": {"z": -1}}}],
     "wallChanges": [{"wall": "lid", "motion": {"velocity": {"z": -0.1}}}]})";

TEST(StageSpec, AKeyBlocksFourStagesLoadAsWritten) {
  const Scene scene = spec::to_scene(spec::parse_json(staged(kFourStages)));
  ASSERT_EQ(scene.stages.size(), 4u);
  EXPECT_EQ(scene.stages[0].name, "fill");
  EXPECT_EQ(scene.stages[0].until_kinetic_energy, 1e-6);
  EXPECT_EQ(scene.stages[0].min_duration, -1);  // a tenth of its length
  EXPECT_EQ(scene.stages[1].growth_factor, 1.05);
  EXPECT_TRUE(scene.stages[2].glue_bonds);
  EXPECT_EQ(scene.stages[2].steps, 10);
  ASSERT_EQ(scene.walls.size(), 3u);
  EXPECT_EQ(scene.walls[1].last_stage, 2);  // the funnel is there until the release
  EXPECT_EQ(scene.walls[2].name, "lid");
  EXPECT_EQ(scene.walls[2].first_stage, 3);
  ASSERT_TRUE(scene.stages[3].interactions);
  EXPECT_EQ(scene.stages[3].interactions->at(1).friction, 0.6);  // rock-steel, both ways
  EXPECT_EQ(scene.stages[3].interactions->at(2).friction, 0.6);
  EXPECT_EQ(scene.stages[3].interactions->at(0).friction, 0.3);  // rock-rock as before
  ASSERT_EQ(scene.stages[3].wall_changes.size(), 1u);
  EXPECT_EQ(scene.stages[3].wall_changes[0].wall, 2);
  EXPECT_EQ(scene.stages[3].gravity, Vec3(1, 0, -9.81));
  EXPECT_EQ(scene.stages[0].name, "fill");
  EXPECT_EQ(spec::to_scene(spec::parse_json(staged(R"({"steps": 5})"))).stages[0].name, "stage 1");
  // a stage may change a material's interaction with itself (the particles' friction)
  const Scene rough = spec::to_scene(spec::parse_json(
      staged(R"({"steps": 5, "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5, "friction": 0.9}]})")));
  EXPECT_EQ(rough.stages[0].interactions->at(0).friction, 0.9);
}

TEST(StageSpec, EachMistakeIsNamedWithItsPath) {
  const std::pair<std::string, std::string> cases[] = {
      {R"({"steps": 5, "duration": 1})", "stages[0]: give its duration (s) or its steps, one of them"},
      {R"({})", "stages[0]: give its duration (s) or its steps, one of them"},
      {R"({"steps": -3})", "stages[0].steps: must be >= 1 (got -3)"},
      {R"({"steps": 5, "removeWalls": ["roof"]})", "stages[0].removeWalls[0]: no wall is named \"roof\""},
      {R"({"steps": 5, "removeWalls": ["funnel"]}, {"steps": 5, "removeWalls": ["funnel"]})",
       "stages[1].removeWalls[0]: wall \"funnel\" is not there at this stage (it was removed at stage 1)"},
      {R"({"steps": 5, "wallChanges": [{"wall": "lid"}]}, {"steps": 5, "addWalls": [{"name": "lid",
         "material": "steel", "plane": {"normal": {"z": -1}}}]})",
       "stages[0].wallChanges[0].wall: no wall is named \"lid\""},
      {R"({"steps": 5, "addWalls": [{"name": "floor", "material": "steel", "plane": {"normal": {"z": 1}}}]})",
       "stages[0].addWalls[0].name: another wall is named \"floor\""},
      {R"({"steps": 5, "bond": true}, {"steps": 5, "bond": true})",
       "stages[1].bond: only one stage may glue bonds (stage 1 does already)"},
      {R"({"steps": 5, "growthFactor": 1.1, "untilKineticEnergy": 1})",
       "stages[0].growthFactor: a stage that grows the particles runs its whole length"},
      {R"({"steps": 5, "growthFactor": 2}, {"steps": 5, "growthFactor": 2})",
       "stages[1].growthFactor: the stages' growth factors multiply to 4 by here, more than 3"},
      {R"({"steps": 5, "minDuration": 0.1})", "stages[0].minDuration: delays an end condition, and the stage has none"},
      {R"({"steps": 5, "untilWallForce": 10})", "stages[0].untilWallForce: needs untilWall"},
      {R"({"steps": 5, "untilWall": "floor"})", "stages[0].untilWallForce: must be a positive number (got 0)"},
      {R"({"steps": 5, "wallChanges": [{"wall": "funnel", "motion": {"center": {"x": 1}}}]})",
       "stages[0].wallChanges[0].motion.center: a stage's motion turns the wall about its centre"},
      {R"({"steps": 5, "interactions": [{"a": "rock", "b": "clay", "friction": 1}]})",
       "stages[0].interactions[0].b: unknown material \"clay\""},
      {R"({"steps": 5, "name": "a\nb"})", "stages[0].name: must not hold control characters"},
      {R"({"steps": 5, "localDamping": 1})", "stages[0].localDamping: must be in [0, 1)"},
      {R"({"steps": 5, "addWalls": [{"name": "lid", "material": "steel", "plane": {"normal": {"z": -1}}}],
          "removeWalls": ["lid"]})",
       "stages[0].removeWalls[0]: wall \"lid\" is added by this stage"},
      {R"({"steps": 5, "wallChanges": [{"wall": "floor"}, {"wall": "floor", "motion": {"velocity": {"z": 1}}}]})",
       "stages[0].wallChanges[1].wall: wall \"floor\" is changed twice in this stage"},
      {R"({"steps": 5, "removeWalls": ["floor"], "untilWall": "floor", "untilWallForce": 1})",
       "stages[0].untilWall: wall \"floor\" is not there at this stage"},
      {R"({"steps": 5, "name": "a\u2028b"})", "stages[0].name: must not hold control characters or line separators"},
      {R"({"steps": 5, "name": "a\u0085b"})", "stages[0].name: must not hold control characters or line separators"},
  };
  for (const auto& [stages, expected] : cases)
    EXPECT_NE(spec_problems(staged(stages)).find(expected), std::string::npos) << stages << "\ngave:\n"
                                                                               << spec_problems(staged(stages));
}

TEST(StageSpec, AStageMayEndOnTheForceOfAWallItAdds) {
  EXPECT_EQ(spec_problems(staged(R"({"steps": 5, "untilWall": "lid", "untilWallForce": 1,
    "addWalls": [{"name": "lid", "material": "steel", "plane": {"normal": {"z": -1}}}]})")),
            "");
}

TEST(StageSpec, AStagedRunsLengthIsItsStagesAndItGrowsInAStage) {
  EXPECT_NE(spec_problems(staged(R"({"steps": 5})", R"("time": {"steps": 100},)"))
                .find("time: a staged run lasts as long as its stages: leave time.duration and time.steps out"),
            std::string::npos);
  EXPECT_NE(spec_problems(staged(R"({"steps": 5})", R"("growth": {"factor": 1.1, "steps": 10},)"))
                .find("growth: a staged run grows its particles in a stage"),
            std::string::npos);
  // a spec without stages still needs its length
  EXPECT_NE(spec_problems(R"({"materials": [{"name": "a", "density": 1, "normalStiffness": 1}],
    "interactions": [{"a": "a", "b": "a"}], "particles": [{"radius": 1, "material": "a"}]})")
                .find("time: give the run's duration (s) or its number of steps"),
            std::string::npos);
}

TEST(StageSpec, ABondStageNeedsTheBondsBlock) {
  std::string json = staged(R"({"steps": 5, "bond": true})");
  const std::size_t at = json.find("\"bonds\"");
  json.erase(at, json.find('\n', at) - at + 1);
  EXPECT_NE(spec_problems(json).find("stages[0].bond: needs the spec's \"bonds\" block"), std::string::npos)
      << spec_problems(json);
}

}  // namespace
}  // namespace dem::test
