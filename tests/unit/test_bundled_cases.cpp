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

// A case's study (cases/NAME/study.json) plans, and every run's spec is valid: dem study --plan.
TEST(BundledCases, EveryCasesStudyPlansWithValidSpecs) {
  int studies = 0;
  for (const std::filesystem::directory_entry& e :
       std::filesystem::directory_iterator(std::filesystem::path(DEM_SOURCE_DIR) / "cases")) {
    const std::filesystem::path study = e.path() / "study.json";
    if (!std::filesystem::exists(study)) continue;
    ++studies;
    const std::string command = "'" DEM_BINARY_DIR "/dem' study '" + study.string() + "' --plan > /dev/null 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
  }
  EXPECT_GE(studies, 1);
}

}  // namespace
}  // namespace dem::test
