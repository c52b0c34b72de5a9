// Every bundled case (cases/NAME/spec.json, offered by the server's /api/cases and run by the
// README's main command) is a valid spec with a README whose first line is its title.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "spec/spec_loader.hpp"

namespace dem::test {
namespace {

namespace fs = std::filesystem;

TEST(BundledCases, EveryCaseIsAValidSpecWithATitledReadme) {
  int cases = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(fs::path(DEM_SOURCE_DIR) / "cases")) {
    if (!e.is_directory()) continue;
    ++cases;
    const fs::path spec = e.path() / "spec.json";
    SCOPED_TRACE(spec.string());
    ASSERT_TRUE(fs::exists(spec));
    try {
      const Scene scene = spec::to_scene(spec::read_json_file(spec.string()), e.path().string());
      EXPECT_FALSE(scene.particles.empty());
    } catch (const spec::SpecError& error) {
      std::string all;
      for (const std::string& p : error.problems()) all += p + "\n";
      ADD_FAILURE() << all;
    }
    std::ifstream readme(e.path() / "README.md");
    std::string title;
    std::getline(readme, title);
    EXPECT_EQ(title.rfind("# ", 0), 0u) << "README.md must start with its title";
  }
  EXPECT_GE(cases, 4);
}

}  // namespace
}  // namespace dem::test

namespace dem::test {
namespace {

// A case's studies (cases/NAME/*.json with a "base") plan, every run's spec valid (dem study --plan),
// and its other specs (a variant beside spec.json) are valid too (dem validate).
TEST(BundledCases, EveryCasesStudiesAndVariantsAreValid) {
  int studies = 0;
  for (const std::filesystem::directory_entry& e :
       std::filesystem::recursive_directory_iterator(std::filesystem::path(DEM_SOURCE_DIR) / "cases")) {
    const std::filesystem::path file = e.path();
    if (file.extension() != ".json" || file.filename() == "spec.json") continue;
    std::ifstream in(file);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.find("\"parameters\"") == std::string::npos && text.find("\"materials\"") == std::string::npos)
      continue;  // not a spec or a study (a mesh's or a table's JSON)
    const bool study = text.find("\"base\"") != std::string::npos;
    studies += study;
    const std::string command = "'" DEM_BINARY_DIR "/dem' " + std::string(study ? "study '" : "validate '") +
                                file.string() + "'" + (study ? " --plan" : "") + " > /dev/null 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
  }
  EXPECT_GE(studies, 3);
}

}  // namespace
}  // namespace dem::test
