// Tests of the job spec loader (spec/spec_loader.hpp): JSON and protobuf bytes -> checked Scene.
// A good spec must give exactly the scene it describes; each bad one a SpecError whose problems
// name the field (its JSON path) and say what is wrong.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <variant>
#include <vector>

#include "bonds/bond_models.hpp"
#include "contact/models.hpp"
#include "spec/referenced_files.hpp"
#include "spec/spec_loader.hpp"

namespace dem::spec {
namespace {

// Two glass spheres above a steel floor: every section a small scene needs, nothing optional.
const char* kGoodSpec = R"({
  "name": "two spheres",
  "materials": [
    {"name": "glass", "density": 2500, "normalStiffness": 1e5, "poissonRatio": 0.2},
    {"name": "steel", "rigid": true}
  ],
  "interactions": [
    {"a": "glass", "b": "glass", "restitution": 0.5, "friction": 0.3},
    {"a": "glass", "b": "steel", "restitution": 0.8, "friction": 0.1}
  ],
  "contact": {"normal": "LINEAR", "rolling": "NONE"},
  "particles": [
    {"position": {"x": 0, "y": 0, "z": 0.1}, "radius": 0.01, "material": "glass", "velocity": {"z": -1}},
    {"position": {"x": 0.05, "y": 0, "z": 0.1}, "radius": 0.02, "material": "glass", "fixed": true}
  ],
  "walls": [
    {"name": "floor", "material": "steel", "plane": {"point": {"z": 0}, "normal": {"z": 2}}}
  ],
  "gravity": {"z": -9.81},
  "time": {"steps": 100}
})";

// Replaces the first occurrence of `from` in `text` by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at == std::string::npos) {
    ADD_FAILURE() << "test set-up: \"" << from << "\" is not in the spec";
    return text;
  }
  return text.replace(at, from.size(), to);
}

// kGoodSpec with the first occurrence of `from` replaced by `to`.
std::string good_with(const std::string& from, const std::string& to) { return replaced(kGoodSpec, from, to); }

// The problems reported for a spec, from parsing or from checking; a failure if there are none.
std::vector<std::string> problems_of(const std::string& json) {
  try {
    to_scene(parse_json(json));
  } catch (const SpecError& e) {
    return e.problems();
  }
  ADD_FAILURE() << "the spec was accepted:\n" << json;
  return {};
}

std::string listing(const std::vector<std::string>& problems) {
  std::string s;
  for (const std::string& p : problems) s += "\n  " + p;
  return s;
}

// A problem that starts with `path` (its JSON path) and says `reason`.
testing::AssertionResult has_problem(const std::vector<std::string>& problems, const std::string& path,
                                     const std::string& reason) {
  for (const std::string& p : problems)
    if (p.rfind(path, 0) == 0 && p.find(reason) != std::string::npos) return testing::AssertionSuccess();
  return testing::AssertionFailure() << "no problem \"" << path << "...: ..." << reason
                                     << "...\" among:" << listing(problems);
}

// ---------------------------------------------------------------------------------------------
// A good spec

TEST(SpecLoader, GoodSpecBuildsTheSceneItDescribes) {
  const Scene s = to_scene(parse_json(kGoodSpec));
  EXPECT_EQ(s.name, "two spheres");

  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[0].name, "glass");
  EXPECT_EQ(s.materials[0].density, 2500);
  EXPECT_EQ(s.materials[0].normal_stiffness, 1e5);
  EXPECT_EQ(s.materials[0].poisson_ratio, 0.2);
  EXPECT_FALSE(s.materials[0].rigid);
  EXPECT_EQ(s.materials[1].name, "steel");
  EXPECT_TRUE(s.materials[1].rigid);

  // 2 x 2 table, symmetric; the pair nobody gave (steel-steel) keeps the defaults.
  ASSERT_EQ(s.interactions.size(), 4u);
  EXPECT_EQ(s.interaction(0, 0).restitution, 0.5);
  EXPECT_EQ(s.interaction(0, 0).friction, 0.3);
  EXPECT_EQ(s.interaction(0, 1).restitution, 0.8);
  EXPECT_EQ(s.interaction(1, 0).restitution, 0.8);
  EXPECT_EQ(s.interaction(1, 0).friction, 0.1);
  EXPECT_EQ(s.interaction(0, 1).rolling_friction, 0.0);

  ASSERT_EQ(s.particles.size(), 2u);
  EXPECT_EQ(s.particles[0].position, Vec3(0, 0, 0.1));
  EXPECT_EQ(s.particles[0].velocity, Vec3(0, 0, -1));
  EXPECT_EQ(s.particles[0].radius, 0.01);
  EXPECT_EQ(s.particles[0].material, 0);
  EXPECT_FALSE(s.particles[0].fixed);
  EXPECT_EQ(s.particles[1].position, Vec3(0.05, 0, 0.1));
  EXPECT_EQ(s.particles[1].radius, 0.02);
  EXPECT_TRUE(s.particles[1].fixed);

  ASSERT_EQ(s.walls.size(), 1u);
  EXPECT_EQ(s.walls[0].name, "floor");
  EXPECT_EQ(s.walls[0].material, 1);
  const auto* plane = std::get_if<PlaneShape>(&s.walls[0].shape);
  ASSERT_NE(plane, nullptr);
  EXPECT_EQ(plane->point, Vec3(0, 0, 0));
  EXPECT_EQ(plane->normal, Vec3(0, 0, 1));  // given as (0, 0, 2): made unit

  EXPECT_EQ(s.gravity, Vec3(0, 0, -9.81));
  EXPECT_EQ(s.contact.normal, LinearNormal::kName);
  EXPECT_EQ(s.contact.rolling, NoRolling::kName);
  EXPECT_EQ(s.time.steps, 100);
  EXPECT_EQ(s.time.duration, 0.0);
  EXPECT_FALSE(s.domain.has_value());
}

TEST(SpecLoader, OmittedFieldsTakeTheDocumentedDefaults) {
  const Scene s = to_scene(parse_json(kGoodSpec));
  // contact (dem.proto ContactModel; the manuals' rns = 0.5; C_s = C_n, where the manuals' rzs is 0;
  // Ai et al. eta_r = 0.3): the models' own defaults, for parameters the spec does not give; no
  // tensile force
  EXPECT_TRUE(s.contact.no_tensile_force);
  EXPECT_TRUE(s.contact.parameters.given().empty());
  EXPECT_EQ(s.contact.parameters.value(LinearNormal::kStiffnessRatio), 0.5);
  EXPECT_EQ(s.contact.parameters.value(LinearNormal::kDampingRatio), 1.0);
  EXPECT_EQ(s.contact.parameters.value(EpsdRolling::kDampingRatio), 0.3);
  // time: automatic step at 1/50 of the contact time
  EXPECT_EQ(s.time.dt, 0.0);
  EXPECT_EQ(s.time.dt_fraction, 1.0 / 50.0);
  EXPECT_FALSE(s.time.allow_unstable_dt);
  // outputs: animation on, force chains off, metres, %.6e, first and last frame only
  EXPECT_TRUE(s.outputs.animation);
  EXPECT_FALSE(s.outputs.force_chains);
  EXPECT_EQ(s.outputs.length_unit, 1.0);
  EXPECT_EQ(s.outputs.length_unit_name, "m");
  EXPECT_EQ(s.outputs.number_format, FileNumberFormat::Scientific);
  EXPECT_EQ(s.outputs.every_steps, 0);
  EXPECT_EQ(s.outputs.interval_seconds, 0.0);
  // numerics
  EXPECT_EQ(s.numerics.skin_fraction, 0.1);
  EXPECT_EQ(s.numerics.search_interval, 0);
  EXPECT_EQ(s.numerics.threads, 0);
  EXPECT_EQ(s.numerics.max_overlap_fraction, 0.25);
  EXPECT_EQ(s.numerics.check_interval, 100);
  EXPECT_EQ(s.numerics.reorder_interval, 10);
}

TEST(SpecLoader, GivenOptionsOverrideTheDefaults) {
  const std::string json = good_with(R"("time": {"steps": 100})",
                                     R"("time": {"duration": 0.5, "dt": 1e-6, "dtFraction": 0.01},
  "outputs": {"everySteps": 7, "animation": false, "forceChains": true, "lengthUnit": "mm",
              "numberFormat": "LEGACY_FIXED"},
  "numerics": {"skin": 0.3, "threads": 2, "checkInterval": 5, "reorderInterval": 3},
  "domain": {"min": {"x": -1, "y": -1, "z": -1}, "max": {"x": 1, "y": 1, "z": 2}})");
  const Scene s = to_scene(parse_json(json));
  EXPECT_EQ(s.time.duration, 0.5);
  EXPECT_EQ(s.time.steps, 0);
  EXPECT_EQ(s.time.dt, 1e-6);
  EXPECT_EQ(s.time.dt_fraction, 0.01);
  EXPECT_EQ(s.outputs.every_steps, 7);
  EXPECT_FALSE(s.outputs.animation);
  EXPECT_TRUE(s.outputs.force_chains);
  EXPECT_EQ(s.outputs.length_unit, 1e-3);
  EXPECT_EQ(s.outputs.length_unit_name, "mm");
  EXPECT_EQ(s.outputs.number_format, FileNumberFormat::LegacyFixed);
  EXPECT_EQ(s.numerics.skin_fraction, 0.3);
  EXPECT_EQ(s.numerics.threads, 2);
  EXPECT_EQ(s.numerics.check_interval, 5);
  EXPECT_EQ(s.numerics.reorder_interval, 3);
  ASSERT_TRUE(s.domain.has_value());
  EXPECT_EQ(s.domain->min, Vec3(-1, -1, -1));
  EXPECT_EQ(s.domain->max, Vec3(1, 1, 2));
}

// A key given twice in one object is named, not settled silently by keeping the last (the docs say
// nothing is ignored): also when its two spellings, camelCase and the proto's, are mixed.
TEST(SpecLoader, AKeyGivenTwiceIsNamed) {
  const auto twice = problems_of(good_with(R"("restitution": 0.8,)", R"("restitution": 0.8, "restitution": 0.9,)"));
  EXPECT_TRUE(has_problem(twice, "interactions[1].restitution", "given twice")) << listing(twice);
  const auto spelled =
      problems_of(good_with(R"("normalStiffness": 1e5,)", R"("normalStiffness": 1e5, "normal_stiffness": 2e5,)"));
  EXPECT_TRUE(has_problem(spelled, "materials[0].normal_stiffness", "given twice")) << listing(spelled);
  const auto top = problems_of(std::string(kGoodSpec).replace(1, 0, R"("name": "first",)"));
  EXPECT_TRUE(has_problem(top, "name", "given twice")) << listing(top);
  // the same key in different objects is fine
  EXPECT_NO_THROW(to_scene(parse_json(kGoodSpec)));
}

// A list given as one value, a list inside a list or a null element is named: protobuf's parser
// would take the value as a list of one, flatten the inner list and drop the null (an independent
// tester's finding: "tags": "abc" was accepted as ["abc"]).
TEST(SpecLoader, AListThatIsNotAListIsNamed) {
  const auto single = problems_of(std::string(kGoodSpec).replace(1, 0, R"("tags": "abc",)"));
  EXPECT_TRUE(has_problem(single, "tags", "expected a list, got a string")) << listing(single);
  const auto nested = problems_of(std::string(kGoodSpec).replace(1, 0, R"("tags": [["a"]],)"));
  EXPECT_TRUE(has_problem(nested, "tags[0]", "expected a string, got a list")) << listing(nested);
  const auto null = problems_of(std::string(kGoodSpec).replace(1, 0, R"("tags": ["a", null],)"));
  EXPECT_TRUE(has_problem(null, "tags[1]", "expected a string, got null")) << listing(null);
  const auto object =
      problems_of(good_with(R"("walls": [
    {"name": "floor", "material": "steel", "plane": {"point": {"z": 0}, "normal": {"z": 2}}}
  ],)",
                            R"("walls": {"name": "floor", "material": "steel", "plane": {"normal": {"z": 1}}},)"));
  EXPECT_TRUE(has_problem(object, "walls", "expected a list, got an object")) << listing(object);
  const auto deep = problems_of(good_with(R"("plane": {"point": {"z": 0}, "normal": {"z": 2}})",
                                          R"("mesh": {"vertices": [null], "triangles": {"i": 1}})"));
  EXPECT_TRUE(has_problem(deep, "walls[0].mesh.vertices[0]", "expected an object, got null")) << listing(deep);
  EXPECT_TRUE(has_problem(deep, "walls[0].mesh.triangles", "expected a list, got an object")) << listing(deep);
  // a list given as null is a list left out, as the parser reads it
  EXPECT_NO_THROW(to_scene(parse_json(std::string(kGoodSpec).replace(1, 0, R"("tags": null,)"))));
}

// A normal of any length is made unit, a tiny one too (its square underflowed: refused as zero).
TEST(SpecLoader, ATinyNormalIsADirection) {
  const Scene s = to_scene(parse_json(good_with(R"("normal": {"z": 2})", R"("normal": {"z": 1e-300})")));
  EXPECT_EQ(std::get<PlaneShape>(s.walls[0].shape).normal, Vec3::UnitZ());
  const auto zero = problems_of(good_with(R"("normal": {"z": 2})", R"("normal": {"z": 0})"));
  EXPECT_TRUE(has_problem(zero, "walls[0].plane.normal", "must not be zero")) << listing(zero);
}

TEST(SpecLoader, ProtoFieldNamesAreAcceptedAsWellAsCamelCase) {
  // The canonical JSON mapping accepts both spellings (dem.proto header).
  const Scene s = to_scene(parse_json(good_with(R"("normalStiffness": 1e5)", R"("normal_stiffness": 2e5)")));
  EXPECT_EQ(s.materials[0].normal_stiffness, 2e5);
}

TEST(SpecLoader, LatticeSitesFollowTheListedParticles) {
  // A cubic lattice of radius 0.01 in a 0.04 box: 2 x 2 x 2 sites, appended after the two
  // listed particles, each with the lattice's velocity and material.
  const Scene s = to_scene(parse_json(good_with(R"("walls": [)", R"("lattices": [
    {"kind": "CUBIC", "min": {"x": 1, "y": 1, "z": 1}, "max": {"x": 1.04, "y": 1.04, "z": 1.04},
     "radius": 0.01, "material": "glass", "velocity": {"x": 0.5}}],
  "walls": [)")));
  ASSERT_EQ(s.particles.size(), 10u);
  EXPECT_EQ(s.particles[0].position, Vec3(0, 0, 0.1));
  for (std::size_t k = 2; k < 10; ++k) {
    EXPECT_EQ(s.particles[k].radius, 0.01);
    EXPECT_EQ(s.particles[k].material, 0);
    EXPECT_EQ(s.particles[k].velocity, Vec3(0.5, 0, 0));
    for (int d = 0; d < 3; ++d) {
      EXPECT_GE(s.particles[k].position[d], 1.01 - 1e-12);
      EXPECT_LE(s.particles[k].position[d], 1.03 + 1e-12);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Parser errors: syntax (with line and column), unknown fields and wrong types, by JSON path

TEST(SpecLoader, UnknownFieldIsNamed) {
  const auto problems = problems_of(good_with(R"("radius": 0.01)", R"("radiuss": 0.01)"));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("particles[0].radiuss: unknown field"), std::string::npos) << problems[0];
}

TEST(SpecLoader, StringForANumberIsNamed) {
  const auto problems = problems_of(good_with(R"("density": 2500)", R"("density": "heavy")"));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("materials[0].density: expected a number, got \"heavy\""), std::string::npos)
      << problems[0];
}

TEST(SpecLoader, UnknownEnumValueIsAnError) {
  const auto problems = problems_of(good_with(R"("normal": "LINEAR")", R"("normal": "LINEAER")"));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("contact.normal: expected one of LINEAR, HERTZ"), std::string::npos) << problems[0];
  EXPECT_NE(problems[0].find("LINEAER"), std::string::npos) << problems[0];
}

// A value of the wrong shape, or a field whose name has a character a name does not, is said as the
// checks say what is wrong (protobuf's own words came through: "invalid value Starting an object on
// a scalar field for type density": an independent tester).
TEST(SpecLoader, AValueOfTheWrongShapeIsNamedInPlainWords) {
  const std::pair<std::pair<const char*, const char*>, const char*> cases[] = {
      // an enum's number that is none of its values was read as the unset value ('no normal model
      // "" in this build'); an empty key was protobuf's "Proto fields must have a name."
      {{R"("normal": "LINEAR")", R"("normal": 7)"}, "contact.normal: expected one of LINEAR, HERTZ, got 7"},
      {{R"("normal": "LINEAR")", R"("normal": 1.5)"}, "contact.normal: expected one of LINEAR, HERTZ, got 1.5"},
      {{R"("contact": {)", R"("": 1, "contact": {)"}, "spec: a key is empty (\"\"): unknown field"},
      {{R"("normal": "LINEAR")", R"("normal": "LINEAR", "": 1)"}, "contact: a key is empty (\"\"): unknown field"},
      {{R"("contact": {)", R"("": 1, "": 2, "contact": {)"}, "spec: a key is empty (\"\"), and given twice"},
      // a spelling the parser does not take beside the field is an unknown field, not the field
      // given twice (it was "materials[0].DENSITY: is given twice in its object")
      {{R"("density": 2500)", R"("density": 2500, "DENSITY": 1)"}, "materials[0].DENSITY: unknown field"},
      {{R"("density": 2500)", R"("density": {"x": 1})"}, "materials[0].density: expected a number, got an object"},
      {{R"("density": 2500)", R"("density": [1, 2])"}, "materials[0].density: expected a number, got a list"},
      {{R"("density": 2500)", R"("de/nsity": 2500)"}, "materials[0].de/nsity: unknown field"},
      {{R"("time": {"steps": 100})", R"("time": 5)"}, "time: expected an object, got 5"},
      {{R"("time": {"steps": 100})", R"("time": [5])"}, "time: expected an object, got a list"},
  };
  for (const auto& [edit, said] : cases) {
    const auto problems = problems_of(good_with(edit.first, edit.second));
    ASSERT_EQ(problems.size(), 1u) << edit.second;
    EXPECT_NE(problems[0].find(said), std::string::npos) << problems[0];
  }
}

TEST(SpecLoader, MalformedJsonIsAnError) {
  const auto problems = problems_of(std::string(kGoodSpec).substr(0, 200));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].rfind("spec: malformed JSON: ", 0), 0u) << problems[0];
  EXPECT_NE(problems[0].find("line "), std::string::npos) << problems[0];  // where it broke
}

// A number past a double's range is named with its place, as a syntax error is (it was the JSON
// library's "[json.exception.out_of_range.406] number overflow parsing '1e400'", with no place).
// The same characters earlier in a name are not the number (an independent tester: the name's column).
TEST(SpecLoader, ANumberOutOfADoublesRangeIsNamedWithItsLineAndColumn) {
  std::string text = good_with(R"("density": 2500)", R"("density": 2.5e400)");
  text.replace(text.find("two spheres"), 11, R"(2.5e400 \" 2.5e400)");
  const std::size_t at = text.find("2.5e400", text.find("density"));
  const std::size_t line_start = text.rfind('\n', at) + 1;
  const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
  const std::string place = "line " + std::to_string(line) + ", column " + std::to_string(at - line_start + 1);
  const auto problems = problems_of(text);
  ASSERT_EQ(problems.size(), 1u) << listing(problems);
  EXPECT_EQ(problems[0],
            "spec: malformed JSON: " + place + ": the number 2.5e400 is out of a double's range (about ±1.8e308)")
      << problems[0];
}

// ---------------------------------------------------------------------------------------------
// Checker errors, one per rule

TEST(SpecLoader, NegativeRadius) {
  const auto problems = problems_of(good_with(R"("radius": 0.01)", R"("radius": -0.01)"));
  EXPECT_TRUE(has_problem(problems, "particles[0].radius:", "must be a positive number (got -0.01)"));
  EXPECT_EQ(problems.size(), 1u) << listing(problems);
}

TEST(SpecLoader, UnknownMaterialName) {
  const auto problems =
      problems_of(good_with(R"("radius": 0.02, "material": "glass")", R"("radius": 0.02, "material": "glas")"));
  EXPECT_TRUE(has_problem(problems, "particles[1].material:", "unknown material \"glas\""));
}

TEST(SpecLoader, MissingInteractionBetweenTwoParticleMaterials) {
  // sand meets itself and the floor, but nobody said how it meets glass.
  std::string json = good_with(R"({"name": "steel", "rigid": true})",
                               R"({"name": "steel", "rigid": true},
    {"name": "sand", "density": 2600, "normalStiffness": 1e5})");
  json = replaced(json, R"("interactions": [)", R"("interactions": [
    {"a": "sand", "b": "sand", "restitution": 0.5},
    {"a": "steel", "b": "sand", "restitution": 0.5},)");
  json = replaced(json, R"("radius": 0.02, "material": "glass")", R"("radius": 0.02, "material": "sand")");
  const auto problems = problems_of(json);
  EXPECT_TRUE(has_problem(problems, "interactions:", "no interaction between \"glass\" and \"sand\""));
  EXPECT_EQ(problems.size(), 1u) << listing(problems);
}

TEST(SpecLoader, MissingInteractionBetweenParticleAndWallMaterial) {
  const auto problems = problems_of(good_with(R"({"a": "glass", "b": "steel", "restitution": 0.8, "friction": 0.1})",
                                              R"({"a": "steel", "b": "steel", "restitution": 0.8})"));
  EXPECT_TRUE(has_problem(problems, "interactions:", "no interaction between \"glass\" and wall material \"steel\""));
}

TEST(SpecLoader, RestitutionZeroIsRejected) {
  const auto problems = problems_of(good_with(R"("restitution": 0.5)", R"("restitution": 0)"));
  EXPECT_TRUE(has_problem(problems, "interactions[0].restitution:", "must be in (0, 1] (got 0)"));
}

TEST(SpecLoader, RestitutionAboveOneIsRejected) {
  const auto problems = problems_of(good_with(R"("restitution": 0.8)", R"("restitution": 1.5)"));
  EXPECT_TRUE(has_problem(problems, "interactions[1].restitution:", "must be in (0, 1] (got 1.5)"));
}

TEST(SpecLoader, RestitutionOneIsAccepted) {
  EXPECT_NO_THROW(to_scene(parse_json(good_with(R"("restitution": 0.5)", R"("restitution": 1)"))));
}

TEST(SpecLoader, RollingFrictionWithoutARollingModel) {
  const auto problems = problems_of(good_with(R"("friction": 0.3})", R"("friction": 0.3, "rollingFriction": 0.05})"));
  EXPECT_TRUE(has_problem(problems, "interactions[0].rollingFriction:", "contact.rolling is NONE"));
}

TEST(SpecLoader, RollingFrictionWithARollingModelIsAccepted) {
  std::string json = good_with(R"("friction": 0.3})", R"("friction": 0.3, "rollingFriction": 0.05})");
  json = replaced(json, R"("rolling": "NONE")", R"("rolling": "EPSD")");
  const Scene s = to_scene(parse_json(json));
  EXPECT_EQ(s.contact.rolling, EpsdRolling::kName);
  EXPECT_EQ(s.interaction(0, 0).rolling_friction, 0.05);
}

// Contact parameters belong to models (contact/models.hpp): the chosen models read theirs, a
// parameter of a model not chosen is refused naming its owner, and each is checked to its range.
TEST(SpecLoader, ContactParametersReachTheirModel) {
  const std::string json =
      replaced(kGoodSpec, R"("rolling": "NONE")",
               R"("rolling": "EPSD", "tangentialStiffnessRatio": 0.3, "rollingDampingRatio": 0.1)");
  const Scene s = to_scene(parse_json(json));
  EXPECT_EQ(s.contact.parameters.value(LinearNormal::kStiffnessRatio), 0.3);
  EXPECT_EQ(s.contact.parameters.value(EpsdRolling::kDampingRatio), 0.1);
  EXPECT_EQ(s.contact.parameters.value(LinearNormal::kDampingRatio), 1.0);  // not given: the model's default
}

TEST(SpecLoader, TensionIsAllowedOnlyWhenAsked) {
  EXPECT_TRUE(to_scene(parse_json(kGoodSpec)).contact.no_tensile_force);
  const std::string json = replaced(kGoodSpec, R"("rolling": "NONE")", R"("rolling": "NONE", "noTensileForce": false)");
  EXPECT_FALSE(to_scene(parse_json(json)).contact.no_tensile_force);
}

TEST(SpecLoader, AParameterOfAModelNotChosenIsRefused) {
  std::string json =
      replaced(kGoodSpec, R"("normal": "LINEAR")", R"("normal": "HERTZ", "tangentialDampingRatio": 0.5)");
  json = replaced(json, R"("density": 2500)", R"("density": 2500, "youngsModulus": 1e9)");
  const auto problems = problems_of(json);
  EXPECT_TRUE(
      has_problem(problems, "contact.tangentialDampingRatio:",
                  "is not used by the chosen models (normal HERTZ, rolling NONE); it is a parameter of LINEAR"));
}

TEST(SpecLoader, AContactParameterOutOfRangeIsRefused) {
  const auto problems =
      problems_of(replaced(kGoodSpec, R"("rolling": "NONE")", R"("rolling": "NONE", "tangentialStiffnessRatio": -1)"));
  EXPECT_TRUE(has_problem(problems, "contact.tangentialStiffnessRatio:", "must be in [0, inf) (got -1)"));
  // an unbounded range is open: infinity is outside it, and the message says so (it said "[0, inf]")
  const auto infinite = problems_of(
      replaced(kGoodSpec, R"("rolling": "NONE")", R"("rolling": "NONE", "tangentialStiffnessRatio": "Infinity")"));
  EXPECT_TRUE(has_problem(infinite, "contact.tangentialStiffnessRatio:", "must be in [0, inf) (got inf)"));
}

// The normal model says which material properties it needs.
TEST(SpecLoader, TheNormalModelNamesTheMaterialPropertiesItNeeds) {
  const auto problems = problems_of(replaced(kGoodSpec, R"("normal": "LINEAR")", R"("normal": "HERTZ")"));
  EXPECT_TRUE(has_problem(problems, "materials[0].youngsModulus:", "must be a positive number (got 0)"));
}

TEST(SpecLoader, BothDurationAndSteps) {
  const auto problems = problems_of(good_with(R"("steps": 100)", R"("steps": 100, "duration": 1.0)"));
  EXPECT_TRUE(has_problem(problems, "time:", "not both"));
}

TEST(SpecLoader, NeitherDurationNorSteps) {
  const auto problems = problems_of(good_with(R"("time": {"steps": 100})", R"("time": {"dt": 1e-6})"));
  EXPECT_TRUE(has_problem(problems, "time:", "duration"));
}

TEST(SpecLoader, LatticeWithMaxBelowMin) {
  const auto problems = problems_of(good_with(R"("walls": [)", R"("lattices": [
    {"kind": "FCC", "min": {"x": 0, "y": 0, "z": 0}, "max": {"x": 1, "y": -1, "z": 1},
     "radius": 0.01, "material": "glass"}],
  "walls": [)"));
  EXPECT_TRUE(has_problem(problems, "lattices[0].max:", "must be above min"));
}

TEST(SpecLoader, PlateWithNonPlanarCorners) {
  const auto problems = problems_of(good_with(R"("plane": {"point": {"z": 0}, "normal": {"z": 2}})",
                                              R"("plate": {"c1": {"x": -1, "y": -1}, "c2": {"x": 1, "y": -1},
                                                           "c3": {"x": 1, "y": 1}, "c4": {"x": -1, "y": 1, "z": 0.2}})"));
  EXPECT_TRUE(has_problem(problems, "walls[0].plate", "not in one plane"));
}

TEST(SpecLoader, SmallPlateFarFromTheOriginIsAccepted) {
  // A planar 1/128 m plate at map-grid coordinates (every value exact in binary): the planarity
  // check must not be fooled by rounding in a normal summed over absolute coordinates.
  const std::string json = good_with(R"("plane": {"point": {"z": 0}, "normal": {"z": 2}})",
                                     R"("plate": {"c1": {"x": 452000, "y": 4500000, "z": 312},
                                                  "c2": {"x": 452000.0078125, "y": 4500000, "z": 312},
                                                  "c3": {"x": 452000.0078125, "y": 4500000.0078125, "z": 312.0078125},
                                                  "c4": {"x": 452000, "y": 4500000.0078125, "z": 312.0078125}})");
  try {
    const Scene s = to_scene(parse_json(json));
    EXPECT_TRUE(std::holds_alternative<PlateShape>(s.walls[0].shape));
  } catch (const SpecError& e) {
    ADD_FAILURE() << "a planar convex plate was rejected:" << listing(e.problems());
  }
}

TEST(SpecLoader, PlateWithCornersOutOfOrder) {
  // c1 c3 c2 c4 of a square: a bow tie, whose two halves cancel: no area.
  const auto problems = problems_of(good_with(R"("plane": {"point": {"z": 0}, "normal": {"z": 2}})",
                                              R"("plate": {"c1": {"x": -1, "y": -1}, "c2": {"x": 1, "y": 1},
                                                           "c3": {"x": 1, "y": -1}, "c4": {"x": -1, "y": 1}})"));
  EXPECT_TRUE(has_problem(problems, "walls[0].plate:", "degenerate plate"));
}

TEST(SpecLoader, ConcavePlateIsRejected) {
  // An arrowhead: c3 is pushed in past the diagonal c2-c4, the contact code assumes a convex plate.
  const auto problems = problems_of(good_with(R"("plane": {"point": {"z": 0}, "normal": {"z": 2}})",
                                              R"("plate": {"c1": {"x": 0, "y": 0}, "c2": {"x": 2, "y": 0},
                                                           "c3": {"x": 0.5, "y": 0.5}, "c4": {"x": 0, "y": 2}})"));
  EXPECT_TRUE(has_problem(problems, "walls[0].plate:", "convex quadrilateral"));
}

TEST(SpecLoader, PlateWithAnInfiniteCorner) {
  // The JSON mapping accepts "Infinity" for a double; a plate out there has no plane at all.
  const auto problems = problems_of(good_with(R"("plane": {"point": {"z": 0}, "normal": {"z": 2}})",
                                              R"("plate": {"c1": {"x": "-Infinity", "y": -1}, "c2": {"x": 1, "y": -1},
                                                           "c3": {"x": 1, "y": 1}, "c4": {"x": -1, "y": 1}})"));
  EXPECT_TRUE(has_problem(problems, "walls[0].plate.c1:", "finite"));
  EXPECT_EQ(problems.size(), 1u) << listing(problems);
}

TEST(SpecLoader, LatticeWithANonFiniteVelocity) {
  // Listed particles' velocities are checked; a lattice's must be too.
  const auto problems = problems_of(good_with(R"("walls": [)", R"("lattices": [
    {"kind": "CUBIC", "min": {"x": 1, "y": 1, "z": 1}, "max": {"x": 1.04, "y": 1.04, "z": 1.04},
     "radius": 0.01, "material": "glass", "velocity": {"x": "NaN"}}],
  "walls": [)"));
  EXPECT_TRUE(has_problem(problems, "lattices[0].velocity:", "finite"));
}

TEST(SpecLoader, NonFiniteParticleVelocity) {
  const auto problems = problems_of(good_with(R"("velocity": {"z": -1})", R"("velocity": {"z": "-Infinity"})"));
  EXPECT_TRUE(has_problem(problems, "particles[0].velocity:", "finite"));
}

TEST(SpecLoader, DomainWithAnInfiniteBound) {
  // The domain is written into every ANIMATION_3D.dat frame header, where "inf" cannot be read.
  const auto problems = problems_of(good_with(R"("time": {"steps": 100})",
                                              R"("time": {"steps": 100},
  "domain": {"min": {"x": "-Infinity", "y": -1, "z": -1}, "max": {"x": 1, "y": 1, "z": 1}})"));
  EXPECT_TRUE(has_problem(problems, "domain.min:", "finite"));
}

TEST(SpecLoader, BadLengthUnit) {
  const auto problems =
      problems_of(good_with(R"("time": {"steps": 100})", R"("time": {"steps": 100}, "outputs": {"lengthUnit": "km"})"));
  EXPECT_TRUE(has_problem(problems, "outputs.lengthUnit:", "must be \"m\", \"cm\" or \"mm\" (got \"km\")"));
}

TEST(SpecLoader, HertzNeedsYoungsModulus) {
  const auto problems = problems_of(good_with(R"("normal": "LINEAR")", R"("normal": "HERTZ")"));
  EXPECT_TRUE(has_problem(problems, "materials[0].youngsModulus:", "must be a positive number (got 0)"));
}

TEST(SpecLoader, RigidMaterialOnAParticle) {
  const auto problems =
      problems_of(good_with(R"("radius": 0.02, "material": "glass")", R"("radius": 0.02, "material": "steel")"));
  EXPECT_TRUE(has_problem(problems, "particles[1].material:", "rigid"));
}

TEST(SpecLoader, EveryProblemOfASpecIsReported) {
  // Five independent mistakes in one spec: the user sees them all at once.
  std::string json = good_with(R"("radius": 0.01)", R"("radius": -0.01)");
  json = replaced(json, R"("restitution": 0.5)", R"("restitution": 0)");
  json = replaced(json, R"("material": "glass", "fixed")", R"("material": "glas", "fixed")");
  json = replaced(json, R"("time": {"steps": 100})", R"("time": {}, "outputs": {"lengthUnit": "ft"})");
  const auto problems = problems_of(json);
  EXPECT_TRUE(has_problem(problems, "particles[0].radius:", "positive"));
  EXPECT_TRUE(has_problem(problems, "interactions[0].restitution:", "(0, 1]"));
  EXPECT_TRUE(has_problem(problems, "particles[1].material:", "unknown material \"glas\""));
  EXPECT_TRUE(has_problem(problems, "time:", "duration"));
  EXPECT_TRUE(has_problem(problems, "outputs.lengthUnit:", "\"ft\""));
  EXPECT_EQ(problems.size(), 5u) << listing(problems);
}

TEST(SpecLoader, SpecErrorMessageListsEveryProblem) {
  try {
    to_scene(parse_json(good_with(R"("time": {"steps": 100})", R"("time": {}, "outputs": {"lengthUnit": "ft"})")));
    FAIL() << "accepted";
  } catch (const SpecError& e) {
    ASSERT_EQ(e.problems().size(), 2u);
    EXPECT_EQ(std::string(e.what()), e.problems()[0] + "\n" + e.problems()[1]);
  }
}

// ---------------------------------------------------------------------------------------------
// Protobuf bytes

TEST(SpecLoader, GarbageBytesFailCleanly) {
  const std::vector<std::string> garbage = {
      std::string(12, '\xff'),                         // a varint tag that never ends
      std::string("\x0a\x7f\x01", 3),                  // materials: 127 bytes announced, 1 given
      std::string("\x0f\x00", 2),                      // wire type 7 does not exist
      std::string("\x12\x05\xff\xff\xff\xff\xff", 7),  // a nested message that is itself garbage
  };
  for (const std::string& bytes : garbage) {
    try {
      parse_binary(bytes);
      ADD_FAILURE() << "accepted " << bytes.size() << " garbage bytes";
    } catch (const SpecError& e) {
      ASSERT_EQ(e.problems().size(), 1u);
      EXPECT_TRUE(has_problem(e.problems(), "spec:", "protobuf"));
    }
  }
}

TEST(SpecLoader, BinaryRoundTripGivesTheSameSpecAndScene) {
  const api::JobSpec from_json = parse_json(kGoodSpec);
  const std::string bytes = from_json.SerializeAsString();
  const api::JobSpec from_bytes = parse_binary(bytes);
  EXPECT_EQ(from_bytes.SerializeAsString(), bytes);

  const Scene a = to_scene(from_json), b = to_scene(from_bytes);
  EXPECT_EQ(b.name, a.name);
  ASSERT_EQ(b.particles.size(), a.particles.size());
  for (std::size_t k = 0; k < a.particles.size(); ++k) {
    EXPECT_EQ(b.particles[k].position, a.particles[k].position);
    EXPECT_EQ(b.particles[k].velocity, a.particles[k].velocity);
    EXPECT_EQ(b.particles[k].radius, a.particles[k].radius);
    EXPECT_EQ(b.particles[k].fixed, a.particles[k].fixed);
  }
  ASSERT_EQ(b.interactions.size(), a.interactions.size());
  for (std::size_t k = 0; k < a.interactions.size(); ++k) {
    EXPECT_EQ(b.interactions[k].restitution, a.interactions[k].restitution);
    EXPECT_EQ(b.interactions[k].friction, a.interactions[k].friction);
  }
  EXPECT_EQ(b.materials[0].normal_stiffness, a.materials[0].normal_stiffness);
  EXPECT_EQ(b.time.steps, 100);
  EXPECT_EQ(b.walls.size(), 1u);
}

TEST(SpecLoader, EmptyBytesAreAnEmptySpecThatFailsTheChecks) {
  // Zero bytes are a valid (empty) message: the checker, not the parser, must refuse it.
  const api::JobSpec spec = parse_binary("");
  try {
    to_scene(spec);
    FAIL() << "an empty spec was accepted";
  } catch (const SpecError& e) {
    EXPECT_TRUE(has_problem(e.problems(), "materials:", "at least one material"));
    EXPECT_TRUE(has_problem(e.problems(), "particles:", "no particles"));
  }
}

// ---------------------------------------------------------------------------------------------
// Meshes, motions and loads

const char* kMeshFloor =
    R"({"name": "floor", "material": "steel", "mesh": {"vertices": [{"x": 0, "y": 0}, {"x": 1000}, {"x": 1000, "y": 1000}, {"y": 1000}],
        "triangles": [{"i": 1, "j": 2, "k": 3}, {"i": 1, "j": 3, "k": 4}], "scale": 0.001,
        "rotationAxis": {"z": 1}, "rotationDegrees": 90, "translation": {"z": -0.5}}})";

std::string with_wall(const std::string& wall) {
  return good_with(R"({"name": "floor", "material": "steel", "plane": {"point": {"z": 0}, "normal": {"z": 2}}})", wall);
}

TEST(SpecLoader, InlineMeshIsScaledRotatedAndMoved) {
  const Scene s = to_scene(parse_json(with_wall(kMeshFloor)));
  const auto* mesh = std::get_if<MeshShape>(&s.walls[0].shape);
  ASSERT_NE(mesh, nullptr);
  ASSERT_EQ(mesh->vertices.size(), 4u);
  EXPECT_TRUE(mesh->vertices[1].isApprox(Vec3(0, 1, -0.5), 1e-12))
      << mesh->vertices[1].transpose();  // (1, 0) turned 90 deg
  EXPECT_EQ(mesh->triangles[1], (std::array<int, 3>{0, 2, 3}));
}

TEST(SpecLoader, MeshFileIsReadNextToTheSpec) {
  const auto dir = std::filesystem::temp_directory_path() / ("dem_spec_mesh_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    std::ofstream out(dir / "terrain.dat");
    out << "3 1\n0 0 0\n1 0 0\n0 1 0\n1 2 3\n";
  }
  const std::string wall = R"({"name": "floor", "material": "steel", "mesh": {"file": "terrain.dat"}})";
  const Scene s = to_scene(parse_json(with_wall(wall)), dir.string());
  EXPECT_EQ(std::get<MeshShape>(s.walls[0].shape).triangles.size(), 1u);
  // a bad file: the error names the field, the file, the line and the reason
  {
    std::ofstream out(dir / "terrain.dat");
    out << "3 1\n0 0 0\n1 0 0\n0 1 0\n1 2 7\n";
  }
  try {
    to_scene(parse_json(with_wall(wall)), dir.string());
    ADD_FAILURE() << "accepted a triangle with vertex 7 of 3";
  } catch (const SpecError& e) {
    EXPECT_TRUE(has_problem(e.problems(), "walls[0].mesh.file:", "terrain.dat line 5: triangle 1 refers to vertex 7"))
        << listing(e.problems());
  }
  std::filesystem::remove_all(dir);
}

TEST(SpecLoader, MissingMeshFileIsNamed) {
  const auto problems = problems_of(with_wall(R"({"material": "steel", "mesh": {"file": "/nowhere/t.stl"}})"));
  EXPECT_TRUE(has_problem(problems, "walls[0].mesh.file:", "/nowhere/t.stl: cannot open the file"));
}

TEST(SpecLoader, MeshWithFileAndInlineTriangles) {
  const auto problems = problems_of(with_wall(
      R"({"material": "steel", "mesh": {"file": "t.stl", "vertices": [{"x": 1}], "triangles": [{"i": 1, "j": 1, "k": 1}]}})"));
  EXPECT_TRUE(has_problem(problems, "walls[0].mesh:", "has both a file and inline vertices/triangles"));
}

TEST(SpecLoader, DegenerateInlineTriangle) {
  const auto problems = problems_of(with_wall(
      R"({"material": "steel", "mesh": {"vertices": [{"x": 0}, {"x": 1}, {"x": 2}], "triangles": [{"i": 1, "j": 2, "k": 3}]}})"));
  EXPECT_TRUE(has_problem(problems, "walls[0].mesh:", "walls[0].mesh.triangles[0]: triangle 1 is degenerate"));
}

TEST(SpecLoader, RotationWithoutAnAxis) {
  std::string wall = kMeshFloor;
  wall = replaced(wall, R"("rotationAxis": {"z": 1}, )", "");
  const auto problems = problems_of(with_wall(wall));
  EXPECT_TRUE(has_problem(problems, "walls[0].mesh.rotationAxis:", "must be a non-zero vector"));
}

TEST(SpecLoader, MotionAndLoadAreRead) {
  const std::string moving = R"({"name": "floor", "material": "steel", "plane": {"point": {"z": 0}, "normal": {"z": 1}},
      "motion": {"velocity": {"x": 0.1}, "amplitude": {"z": 0.01}, "frequency": 2, "phaseDegrees": 90}})";
  const Scene s = to_scene(parse_json(with_wall(moving)));
  ASSERT_TRUE(s.walls[0].motion.has_value());
  EXPECT_EQ(s.walls[0].motion->velocity, Vec3(0.1, 0, 0));
  EXPECT_NEAR(s.walls[0].motion->phase, std::numbers::pi / 2, 1e-15);
  const std::string loaded =
      R"({"name": "sleeper", "material": "steel", "plate": {"c1": {}, "c2": {"x": 1}, "c3": {"x": 1, "y": 1}, "c4": {"y": 1}},
      "load": {"mass": 2, "cyclic": {"fMin": 1500, "fMax": 51840, "frequency": 3, "cycles": 15}}})";
  const Scene t = to_scene(parse_json(with_wall(loaded)));
  ASSERT_TRUE(t.walls[0].load.has_value());
  EXPECT_EQ(t.walls[0].load->f_max, 51840);
  EXPECT_EQ(t.walls[0].load->direction, Vec3(0, 0, -1));
  EXPECT_NEAR(t.walls[0].load->force_at(1.0 / 6), 51840, 1e-6);  // the top of the first cycle
  EXPECT_EQ(t.walls[0].load->force_at(5.01), 1500);              // after 15 cycles at 3 Hz
}

TEST(SpecLoader, BadLoadsAreNamed) {
  const std::string plate = R"("plate": {"c1": {}, "c2": {"x": 1}, "c3": {"x": 1, "y": 1}, "c4": {"y": 1}})";
  auto wall = [&](const std::string& load) {
    return with_wall(R"({"name": "sleeper", "material": "steel", )" + plate + ", " + load + "}");
  };
  auto p = problems_of(wall(R"("load": {"mass": 0, "cyclic": {"fMin": 10, "fMax": 5, "frequency": 3, "cycles": 0}})"));
  EXPECT_TRUE(has_problem(p, "walls[0].load.mass:", "must be a positive number"));
  EXPECT_TRUE(has_problem(p, "walls[0].load.cyclic.fMax:", "must be >= fMin"));
  EXPECT_TRUE(has_problem(p, "walls[0].load.cyclic.cycles:", "must be >= 1"));
  p = problems_of(wall(R"("load": {"mass": 1})"));
  EXPECT_TRUE(has_problem(p, "walls[0].load:", "needs a control: cyclic or servo"));
  p = problems_of(wall(R"("load": {"servo": {"target": 100, "gain": -1, "maxSpeed": 0.1}})"));
  EXPECT_TRUE(has_problem(p, "walls[0].load.servo.gain:", "must be a positive number"));
  // a servo's mass was accepted and never used (an independent tester's finding)
  p = problems_of(wall(R"("load": {"mass": 1, "servo": {"target": 100, "gain": 1e-3, "maxSpeed": 0.1}})"));
  EXPECT_TRUE(has_problem(p, "walls[0].load.mass:", "a servo moves at the speed it sets, so it has no mass"));
  p = problems_of(
      wall(R"("motion": {"velocity": {"x": 1}}, "load": {"servo": {"target": 1, "gain": 1, "maxSpeed": 1}})"));
  EXPECT_TRUE(has_problem(p, "walls[0]:", "has both a motion and a load"));
  p = problems_of(wall(R"("motion": {"amplitude": {"x": 1}})"));
  EXPECT_TRUE(has_problem(p, "walls[0].motion.frequency:", "must be > 0 when an amplitude is given"));
}

TEST(SpecLoader, BondsAreRead) {
  const std::string json = replaced(kGoodSpec, R"("gravity": {"z": -9.81},)", R"("gravity": {"z": -9.81},
  "bonds": {"model": "CONTACT", "youngsModulus": 1e9, "tensileStrength": 16e6, "shearStrength": 20e6,
            "zones": [{"min": {"x": -1, "y": -1, "z": -1}, "max": {"x": 1, "y": 1, "z": 0}, "strengthRatio": 0.2}]},)");
  const Scene s = to_scene(parse_json(json));
  ASSERT_TRUE(s.bonds.has_value());
  EXPECT_EQ(s.bonds->model, ContactBond::kName);
  EXPECT_EQ(s.bonds->radius_multiplier, 1.0);
  EXPECT_EQ(s.bonds->shear_stiffness_ratio, 1.0);
  EXPECT_EQ(s.bonds->gap_tolerance, 1e-3);
  EXPECT_EQ(s.bonds->tensile_strength, 16e6);
  ASSERT_EQ(s.bonds->zones.size(), 1u);
  EXPECT_EQ(s.bonds->zones[0].strength_ratio, 0.2);
}

TEST(SpecLoader, BadBondsAreNamed) {
  const std::string json = replaced(kGoodSpec, R"("gravity": {"z": -9.81},)", R"("gravity": {"z": -9.81},
  "bonds": {"youngsModulus": -1, "tensileStrength": -5, "radiusMultiplier": -0.5,
            "region": {"min": {"x": 1}, "max": {"x": 0}}},)");
  const auto p = problems_of(json);
  EXPECT_TRUE(has_problem(p, "bonds.youngsModulus:", "must be a positive number"));
  EXPECT_TRUE(has_problem(p, "bonds.tensileStrength:", "must be >= 0"));
  EXPECT_TRUE(has_problem(p, "bonds.radiusMultiplier:", "must be a positive number"));
  EXPECT_TRUE(has_problem(p, "bonds.region:", "max is below min"));
}

TEST(SpecLoader, ExternalForceAndLocalDamping) {
  std::string json = replaced(kGoodSpec, R"("fixed": true})", R"("fixed": true, "force": {"z": -2.5}})");
  json = replaced(json, R"("time": {"steps": 100})", R"("time": {"steps": 100}, "numerics": {"localDamping": 0.7})");
  const Scene s = to_scene(parse_json(json));
  EXPECT_EQ(s.particles[1].force, Vec3(0, 0, -2.5));
  EXPECT_EQ(s.numerics.local_damping, 0.7);
  const auto p = problems_of(replaced(json, R"("localDamping": 0.7)", R"("localDamping": 1.0)"));
  EXPECT_TRUE(has_problem(p, "numerics.localDamping:", "must be in [0, 1)"));
}

TEST(SpecLoader, GrowthIsCheckedAndRead) {
  const std::string json = replaced(kGoodSpec, R"("time": {"steps": 100})",
                                    R"("time": {"steps": 100}, "growth": {"factor": 1.2, "steps": 50})");
  const Scene s = to_scene(parse_json(json));
  ASSERT_TRUE(s.growth.has_value());
  EXPECT_EQ(s.growth->factor, 1.2);
  EXPECT_EQ(s.growth->steps, 50);
  const auto p = problems_of(replaced(json, R"("factor": 1.2, "steps": 50)", R"("factor": 0.5, "steps": 0)"));
  EXPECT_TRUE(has_problem(p, "growth.factor:", "must be in [1, 3]"));
  EXPECT_TRUE(has_problem(p, "growth.steps:", "must be >= 1"));
}

}  // namespace
}  // namespace dem::spec

namespace dem::test {
namespace {

// Every field that names a file is listed (the server refuses them all, the client inlines them
// all): a lattice's inside and a stage's added mesh were not, and the server opened them (an
// independent tester read /proc/self/environ through a lattice's inside).
TEST(SpecFiles, EveryFieldThatNamesAFileIsListed) {
  const api::JobSpec spec = spec::parse_json(R"({
    "walls": [{"name": "w", "mesh": {"file": "a.dat"}}],
    "packings": [{"inside": {"file": "b.dat"}}],
    "lattices": [{"inside": {"file": "c.dat"}}],
    "stages": [{"name": "s", "addWalls": [{"name": "x", "mesh": {"file": "d.dat"}}]}],
    "clumpShapes": [{"name": "t", "file": "e.txt"}]
  })");
  std::vector<std::string> files = spec::file_references(spec);
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files,
            (std::vector<std::string>{"clumpShapes[0].file", "lattices[0].inside.file", "packings[0].inside.file",
                                      "stages[0].addWalls[0].mesh.file", "walls[0].mesh.file"}));
}

}  // namespace
}  // namespace dem::test
