// `dem run --profile`: the loop's time phase by phase (PhaseProfile), and the peak memory in the
// summary line. A profiled run must time every phase its scene uses, nothing for the phases it does
// not use, add up to the loop, and write the same files as a run without the profile.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include "support/command.hpp"
#include "support/everything_spec.hpp"

namespace {

namespace fs = std::filesystem;

using dem::test::shell_quoted;

// Every kind of work but growth and sources, the lid pressing on the bed.
const std::string kEverything = dem::test::everything_spec(0.0238, 0.05, R"({"interval": 0.01})");

struct Row {
  double seconds = -1, share = -1, us_per_step = -1;
};

// The profile's rows by phase name ("total" among them).
std::map<std::string, Row> profile_rows(const std::string& output) {
  std::map<std::string, Row> rows;
  std::istringstream lines(output);
  const std::regex row(R"(^profile:  (\S+(?: \S+)?) +([0-9.]+) +([0-9.]+)% +([0-9.]+) +([0-9.]+)$)");
  std::smatch m;
  for (std::string line; std::getline(lines, line);)
    if (std::regex_match(line, m, row)) rows[m[1]] = {std::stod(m[2]), std::stod(m[3]), std::stod(m[4])};
  return rows;
}

class CliProfile : public dem::test::DemCommandTest {};

TEST_F(CliProfile, ARunTimesEveryPhaseItsSceneUsesAndNothingForTheOthers) {
  const fs::path spec = write_spec("everything.json", kEverything);
  const dem::test::CommandResult r =
      run_dem("run " + shell_quoted(spec) + " --out " + shell_quoted(dir_ / "out") + " --quiet --profile");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::map<std::string, Row> rows = profile_rows(r.output);
  for (const char* used : {"drift", "clumps", "pairs", "bonds", "walls", "meshes", "kick", "wall motion", "guard",
                           "outputs", "other", "total"}) {
    ASSERT_TRUE(rows.count(used)) << used << " is not in the profile:\n" << r.output;
    EXPECT_GT(rows.at(used).us_per_step, 0) << used << "\n" << r.output;
  }
  // Nothing grows and nothing is inserted: those phases are not even timed.
  for (const char* unused : {"growth", "sources"}) {
    ASSERT_TRUE(rows.count(unused)) << unused << " is not in the profile:\n" << r.output;
    EXPECT_EQ(rows.at(unused).seconds, 0) << unused << "\n" << r.output;
    EXPECT_EQ(rows.at(unused).us_per_step, 0) << unused << "\n" << r.output;
  }
  // The phases make up the loop that the summary line timed.
  double sum = 0, shares = 0;
  for (const auto& [name, row] : rows)
    if (name != "total") {
      sum += row.seconds;
      shares += row.share;
    }
  EXPECT_NEAR(sum, rows.at("total").seconds, 0.001 * static_cast<double>(rows.size())) << r.output;
  EXPECT_NEAR(shares, 100, 0.1 * static_cast<double>(rows.size())) << r.output;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.output, m, std::regex(R"(loop_seconds=([0-9.]+))"))) << r.output;
  EXPECT_NEAR(std::stod(m[1]), rows.at("total").seconds, 0.0011) << r.output;
}

// Two spheres and nothing else: no wall, so nothing is timed as wall motion either.
TEST_F(CliProfile, ASceneWithoutWallsHasNoWallTime) {
  const fs::path spec = write_spec("two.json", R"({
  "materials": [{"name": "glass", "density": 2500, "normalStiffness": 1e5}],
  "interactions": [{"a": "glass", "b": "glass", "restitution": 0.5, "friction": 0.3}],
  "particles": [{"position": {"x": 0}, "radius": 0.01, "material": "glass", "velocity": {"x": 1}},
                {"position": {"x": 0.0201}, "radius": 0.01, "material": "glass", "velocity": {"x": -1}}],
  "time": {"steps": 5000}, "outputs": {"everySteps": 1000}})");
  const auto r = run_dem("run " + shell_quoted(spec) + " --out " + shell_quoted(dir_ / "out") + " --quiet --profile");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::map<std::string, Row> rows = profile_rows(r.output);
  for (const char* unused : {"walls", "meshes", "wall motion", "bonds", "clumps", "growth", "sources"}) {
    ASSERT_TRUE(rows.count(unused)) << unused << "\n" << r.output;
    EXPECT_EQ(rows.at(unused).seconds, 0) << unused << "\n" << r.output;
  }
}

// A run the guard stops says how far it went, its memory and its profile: when they are most wanted.
TEST_F(CliProfile, AStoppedRunStillGivesItsSummaryAndItsProfile) {
  const fs::path spec = write_spec("fast.json", R"({
  "materials": [{"name": "glass", "density": 2500, "normalStiffness": 1e3}],
  "interactions": [{"a": "glass", "b": "glass", "restitution": 0.5, "friction": 0.3}],
  "particles": [{"position": {"x": 0}, "radius": 0.01, "material": "glass", "velocity": {"x": 20}},
                {"position": {"x": 0.0201}, "radius": 0.01, "material": "glass", "velocity": {"x": -20}}],
  "time": {"steps": 2000}})");
  const auto r = run_dem("run " + shell_quoted(spec) + " --out " + shell_quoted(dir_ / "out") + " --quiet --profile");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("dem run: unstable"), std::string::npos) << r.output;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.output, m, std::regex(R"(stopped: steps=([0-9]+) .* peak_memory_mb=[0-9.]+)")))
      << r.output;
  EXPECT_EQ(m[1], "1") << r.output;
  const std::map<std::string, Row> rows = profile_rows(r.output);
  ASSERT_TRUE(rows.count("total")) << r.output;
  EXPECT_GT(rows.at("total").us_per_step, 0) << r.output;  // per the step it took
}

// A run that ends with no particle (its source's first not due yet) has no memory per particle.
TEST_F(CliProfile, AnEmptyRunGivesItsMemoryButNoShareOfIt) {
  const fs::path spec = write_spec("empty.json", R"({
  "materials": [{"name": "sand", "density": 2650, "normalStiffness": 1e5}],
  "interactions": [{"a": "sand", "b": "sand", "restitution": 0.5, "friction": 0.5}],
  "sources": [{"min": {"x": 0, "y": 0, "z": 0}, "max": {"x": 0.1, "y": 0.1, "z": 0.1}, "material": "sand",
               "sizes": {"kind": "UNIFORM", "dMin": 0.01, "dMax": 0.01}, "countRate": 10, "start": 0.5}],
  "time": {"dt": 1e-5, "steps": 100}})");
  const auto r = run_dem("run " + shell_quoted(spec) + " --out " + shell_quoted(dir_ / "out") + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::regex_search(r.output, std::regex(R"(done: steps=100 particles=0 .* peak_memory_mb=[0-9.]+\n)")))
      << r.output;
  EXPECT_EQ(r.output.find("bytes_per_particle"), std::string::npos) << r.output;
}

TEST_F(CliProfile, AProfiledRunWritesTheSameFilesAsOneWithout) {
  const fs::path spec = write_spec("everything.json", kEverything);
  const auto plain = run_dem("run " + shell_quoted(spec) + " --out " + shell_quoted(dir_ / "plain") + " --quiet");
  const auto timed =
      run_dem("run " + shell_quoted(spec) + " --out " + shell_quoted(dir_ / "timed") + " --quiet --profile");
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  ASSERT_EQ(timed.exit_code, 0) << timed.output;
  EXPECT_EQ(plain.output.find("profile:"), std::string::npos) << plain.output;
  int compared = 0;
  for (const auto& entry : fs::directory_iterator(dir_ / "plain")) {
    const std::string name = entry.path().filename().string();
    if (name == "results.json") continue;  // holds the run's own time
    EXPECT_EQ(read(entry.path()), read(dir_ / "timed" / name)) << name;
    ++compared;
  }
  EXPECT_GE(compared, 10);
}

TEST_F(CliProfile, TheSummaryGivesThePeakMemoryAndItsSharePerParticle) {
  const fs::path spec = write_spec("everything.json", kEverything);
  const auto r = run_dem("run " + shell_quoted(spec) + " --out " + shell_quoted(dir_ / "out") + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(
      r.output, m, std::regex(R"(particles=([0-9]+) .* peak_memory_mb=([0-9.]+) bytes_per_particle=([0-9]+))")))
      << r.output;
  const double particles = std::stod(m[1]), megabytes = std::stod(m[2]), per_particle = std::stod(m[3]);
  EXPECT_EQ(particles, 6);
  EXPECT_GT(megabytes, 1);     // a process holds its program and libraries at least
  EXPECT_LT(megabytes, 1000);  // six particles
  EXPECT_NEAR(per_particle, megabytes * 1e6 / particles, 0.01 * per_particle);
}

}  // namespace
