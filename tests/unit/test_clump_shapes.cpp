// Clump shapes in the spec: spheres inline or from a template file (scaled), the subdivision's
// accuracy as asked, mass properties given by the user, the files a client inlines, and each bad
// input refused with its path.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "clumps/mass_properties.hpp"
#include "spec/referenced_files.hpp"
#include "spec/spec_loader.hpp"
#include "support/spec_problems.hpp"

namespace dem::test {
namespace {

namespace fs = std::filesystem;

// One clump of shape "stone" (the given JSON shape fields) of a rock of density 1000.
std::string spec_with_shape(const std::string& shape_fields) {
  return R"({"materials": [{"name": "rock", "density": 1000, "normalStiffness": 1e5}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5, "friction": 0.5}],
  "clumpShapes": [{"name": "stone", )" +
         shape_fields + R"(}],
  "clumps": [{"shape": "stone", "material": "rock", "position": {"z": 1}}],
  "time": {"steps": 10}})";
}

class ClumpShapes : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dem_clump_shapes_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }
  fs::path dir_;
};

// Two unit spheres one apart (in mm in the file, scale 0.001): the same clump as given inline in m.
TEST_F(ClumpShapes, ATemplateFileInMillimetresGivesTheInlineClump) {
  write("pair.txt", "# x y z r (mm)\n-0.5 0 0 1\n\n0.5, 0, 0, 1   # the second\n");
  const Scene from_file =
      spec::to_scene(spec::parse_json(spec_with_shape(R"("file": "pair.txt", "scale": 0.001)")), dir_.string());
  const Scene inline_m = spec::to_scene(spec::parse_json(spec_with_shape(
      R"("spheres": [{"center": {"x": -0.0005}, "radius": 0.001}, {"center": {"x": 0.0005}, "radius": 0.001}])")));
  ASSERT_EQ(from_file.clumps.size(), 1u);
  EXPECT_NEAR(from_file.clumps[0].mass, 1000 * 9 * std::numbers::pi / 4 * 1e-9, 1e-4 * from_file.clumps[0].mass);
  EXPECT_DOUBLE_EQ(from_file.clumps[0].mass, inline_m.clumps[0].mass);
  EXPECT_EQ(from_file.clumps[0].moments, inline_m.clumps[0].moments);
  ASSERT_EQ(from_file.particles.size(), 2u);
  EXPECT_DOUBLE_EQ(from_file.particles[1].radius, 0.001);
  EXPECT_NEAR((from_file.particles[0].position - from_file.particles[1].position).norm(), 0.001, 1e-15);
}

// The client inlines the template (spheres, scale kept): the scene is the same, and the spec no
// longer names a file.
TEST_F(ClumpShapes, TheClientInlinesTemplateFiles) {
  write("pair.txt", "-0.5 0 0 1\n0.5 0 0 1\n");
  api::JobSpec spec = spec::parse_json(spec_with_shape(R"("file": "pair.txt", "scale": 0.001)"));
  EXPECT_EQ(spec::file_references(spec), std::vector<std::string>{"clumpShapes[0].file"});
  const Scene before = spec::to_scene(spec, dir_.string());
  spec::inline_files(spec, dir_.string());
  EXPECT_TRUE(spec::file_references(spec).empty());
  EXPECT_EQ(spec.clump_shapes(0).spheres_size(), 2);
  const Scene after = spec::to_scene(spec);
  EXPECT_EQ(after.clumps[0].mass, before.clumps[0].mass);
  EXPECT_EQ(after.particles[0].position, before.particles[0].position);
}

TEST_F(ClumpShapes, BadTemplatesAreRefusedWithTheFieldTheFileAndTheLine) {
  write("bad.txt", "0 0 0 1\n1 0 zero 1\n");
  write("negative.txt", "0 0 0 -1\n");
  write("empty.txt", "# nothing\n");
  std::string all = spec_problems(spec_with_shape(R"("file": "bad.txt")"), dir_.string());
  EXPECT_NE(all.find("clumpShapes[0].file: " + (dir_ / "bad.txt").string() + " line 2: expected four numbers"),
            std::string::npos)
      << all;
  all = spec_problems(spec_with_shape(R"("file": "negative.txt")"), dir_.string());
  EXPECT_NE(all.find("line 1: the radius must be positive"), std::string::npos) << all;
  all = spec_problems(spec_with_shape(R"("file": "empty.txt")"), dir_.string());
  EXPECT_NE(all.find("has no spheres"), std::string::npos) << all;
  all = spec_problems(spec_with_shape(R"("file": "missing.txt")"), dir_.string());
  EXPECT_NE(all.find("clumpShapes[0].file: cannot open clump template"), std::string::npos) << all;
  all = spec_problems(spec_with_shape(R"("file": "bad.txt", "spheres": [{"radius": 1}])"), dir_.string());
  EXPECT_NE(all.find("clumpShapes[0]: give spheres or a template file, not both"), std::string::npos) << all;
  api::JobSpec spec = spec::parse_json(spec_with_shape(R"("file": "missing.txt")"));
  try {
    spec::inline_files(spec, dir_.string());
    ADD_FAILURE() << "expected a SpecError";
  } catch (const spec::SpecError& e) {
    EXPECT_NE(e.problems().at(0).find("clumpShapes[0].file: cannot open"), std::string::npos) << e.problems().at(0);
  }
  all = spec_problems(spec_with_shape(R"("spheres": [{"radius": 1}], "scale": -2, "accuracy": 0.5)"));
  EXPECT_NE(all.find("clumpShapes[0].scale: must be a positive number"), std::string::npos) << all;
  EXPECT_NE(all.find("clumpShapes[0].accuracy: must be in [1e-05, 0.1]"), std::string::npos) << all;
}

// The subdivision stops at the accuracy asked: the volume of two unit spheres one apart (9 pi / 4)
// within it, and finer when asked finer.
// A shape that no clump uses is checked (its problems are still named) but not integrated: a shape
// of 20 spheres at the finest accuracy took 4.7 s of set-up for nothing.
TEST(ClumpShapeUse, OnlyTheShapesClumpsUseAreIntegrated) {
  const std::string spec = R"({"materials": [{"name": "rock", "density": 1000, "normalStiffness": 1e5}],
    "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5, "friction": 0.5}],
    "clumpShapes": [{"name": "used", "spheres": [{"radius": 0.01}, {"center": {"x": 0.01}, "radius": 0.01}]},
                    {"name": "unused", "spheres": [{"radius": 0.01}, {"center": {"y": 0.01}, "radius": 0.01}]}],
    "clumps": [{"shape": "used", "material": "rock", "position": {"z": 1}},
               {"shape": "used", "material": "rock", "position": {"z": 2}}],
    "time": {"steps": 10}})";
  const std::uint64_t before = union_mass_property_integrations();
  const Scene scene = spec::to_scene(spec::parse_json(spec));
  EXPECT_EQ(scene.clumps.size(), 2u);
  EXPECT_EQ(union_mass_property_integrations() - before, 1u);  // "used", once for both clumps
  // an unused shape's problems are still problems
  const std::string problems =
      spec_problems(R"({"materials": [{"name": "rock", "density": 1000, "normalStiffness": 1e5}],
    "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5, "friction": 0.5}],
    "clumpShapes": [{"name": "unused", "spheres": [{"radius": -0.01}]}],
    "time": {"steps": 10}})");
  EXPECT_NE(problems.find("clumpShapes[0].spheres[0].radius"), std::string::npos) << problems;
}

// A scale that takes the shape's spheres past the radii a spec may give is refused at the scale,
// with the radius it would give (the spheres' own radii were within the limits).
TEST(ClumpShapeScale, AScaleBeyondTheRadiusLimitsIsRefusedAtTheScale) {
  const std::string spheres = R"("spheres": [{"radius": 0.01}, {"center": {"x": 0.01}, "radius": 0.01}], "scale": )";
  std::string problems = spec_problems(spec_with_shape(spheres + "1e12"));
  EXPECT_NE(problems.find("clumpShapes[0].scale: makes the radius of sphere 1 1e+10 m: must be at most 1e+06 m"),
            std::string::npos)
      << problems;
  problems = spec_problems(spec_with_shape(spheres + "1e-9"));
  EXPECT_NE(problems.find("clumpShapes[0].scale: makes the radius of sphere 1 1e-11 m: must be at least 1e-09 m"),
            std::string::npos)
      << problems;
  EXPECT_EQ(spec_problems(spec_with_shape(spheres + "1000")), "");  // 10 m spheres: fine
}

TEST(ClumpShapeAccuracy, TheSubdivisionMeetsTheAccuracyAsked) {
  const double exact = 1000 * 9 * std::numbers::pi / 4;
  double previous = 1;
  for (const double accuracy : {1e-2, 1e-3, 1e-5}) {
    std::ostringstream fields;
    fields << R"("spheres": [{"center": {"x": -0.5}, "radius": 1}, {"center": {"x": 0.5}, "radius": 1}], "accuracy": )"
           << accuracy;
    const Scene s = spec::to_scene(spec::parse_json(spec_with_shape(fields.str())));
    const double error = std::abs(s.clumps[0].mass - exact) / exact;
    std::printf("accuracy %.0e: volume error %.2e\n", accuracy, error);
    EXPECT_LE(error, accuracy);
    EXPECT_LE(error, previous);
    previous = error;
  }
}

// Given mass properties replace the subdivision: the mass whatever the density, the principal
// moments of the given tensor, the members placed about the given centroid.
TEST(ClumpShapeGiven, GivenMassPropertiesAreUsedAsGiven) {
  // a tensor with principal moments 1, 2, 2.5 about axes turned 30 degrees about z
  const double c = std::cos(std::numbers::pi / 6), s = std::sin(std::numbers::pi / 6);
  const double xx = 1 * c * c + 2 * s * s, yy = 1 * s * s + 2 * c * c, xy = (1 - 2) * c * s;
  std::ostringstream fields;
  fields.precision(17);
  fields << R"("spheres": [{"center": {"x": 0.1}, "radius": 0.2}, {"center": {"x": -0.1}, "radius": 0.2}],
     "given": {"mass": 7.5, "centroid": {"x": 0.02}, "inertia": {"xx": )"
         << xx << R"(, "yy": )" << yy << R"(, "zz": 2.5, "xy": )" << xy << "}}";
  const Scene scene = spec::to_scene(spec::parse_json(spec_with_shape(fields.str())));
  ASSERT_EQ(scene.clumps.size(), 1u);
  EXPECT_EQ(scene.clumps[0].mass, 7.5);
  EXPECT_NEAR(scene.clumps[0].moments[0], 1.0, 1e-12);
  EXPECT_NEAR(scene.clumps[0].moments[1], 2.0, 1e-12);
  EXPECT_NEAR(scene.clumps[0].moments[2], 2.5, 1e-12);
  // the first principal axis (moment 1) is x turned 30 degrees about z, up to sign
  const Vec3 axis = scene.clumps[0].orientation * Vec3::UnitX();
  EXPECT_NEAR(std::abs(axis.dot(Vec3(c, s, 0))), 1.0, 1e-12);
  // members about the given centroid: the clump's position is the centroid, at z = 1
  EXPECT_NEAR(scene.particles[0].position.x(), 0.1 - 0.02, 1e-12);
  EXPECT_NEAR(scene.particles[1].position.x(), -0.1 - 0.02, 1e-12);

  std::string all = spec_problems(
      spec_with_shape(R"("spheres": [{"radius": 1}], "given": {"mass": 1, "inertia": {"xx": 1, "yy": 1, "zz": 3}})"));
  EXPECT_NE(all.find("clumpShapes[0].given.inertia: is not a body's: the largest principal moment 3 exceeds the sum"),
            std::string::npos)
      << all;
  all = spec_problems(spec_with_shape(
      R"("spheres": [{"radius": 1}], "given": {"mass": 0, "inertia": {"xx": 1, "yy": 1, "zz": 1, "xy": 2}})"));
  EXPECT_NE(all.find("clumpShapes[0].given.mass: must be a positive number"), std::string::npos) << all;
  EXPECT_NE(all.find("clumpShapes[0].given.inertia: is not positive definite"), std::string::npos) << all;
}

}  // namespace
}  // namespace dem::test
