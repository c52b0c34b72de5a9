// dem study, run here: one command and one file give the runs, the table and the figure; a study
// run again keeps what it ran; a bad study or a bad value is refused before anything runs, by name.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support/command.hpp"

namespace dem::test {
namespace {

namespace fs = std::filesystem;

class CliStudy : public DemCommandTest {};

// Two spheres closing on each other: the faster they come, the more they overlap.
const char* kBase = R"({
  "name": "collision",
  "materials": [{"name": "glass", "density": 2500, "normalStiffness": 1e5}],
  "interactions": [{"a": "glass", "b": "glass", "restitution": 0.5, "friction": 0.3}],
  "contact": {"normal": "LINEAR"},
  "particles": [
    {"position": {"x": 0}, "radius": 0.01, "material": "glass", "velocity": {"x": 1}},
    {"position": {"x": 0.0201}, "radius": 0.01, "material": "glass", "velocity": {"x": -1}}
  ],
  "time": {"steps": 40},
  "outputs": {"everySteps": 20}
})";

const char* kStudy = R"({
  "name": "closing speed",
  "base": "base.json",
  "parameters": [{"path": "particles[0].velocity.x", "values": [0.5, 1, 2]}],
  "plot": ["energy.start", "energy.dissipated"]
})";

TEST_F(CliStudy, OneCommandRunsEveryValueAndWritesTheTableAndTheFigure) {
  write_spec("base.json", kBase);
  const fs::path study = write_spec("study.json", kStudy);
  const fs::path out = dir_ / "out";
  const CommandResult r = run_dem("study " + shell_quoted(study) + " --out " + shell_quoted(out) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("run 3 (particles[0].velocity.x=2): succeeded; energy.start = "), std::string::npos)
      << r.output;
  for (const char* run : {"run-001", "run-002", "run-003"}) {
    EXPECT_TRUE(fs::exists(out / run / "results.json")) << run;
    EXPECT_TRUE(fs::exists(out / run / "ANIMATION_3D.dat")) << run;
  }
  const nlohmann::json table = nlohmann::json::parse(read(out / "study.json"));
  ASSERT_EQ(table["rows"].size(), 3u);
  // the kinetic energy at the start, (1/2) m (v0^2 + 1)
  const double m = 2500 * 4.0 / 3 * 3.141592653589793 * 1e-6;
  for (int k = 0; k < 3; ++k) {
    const double v0 = table["rows"][k]["parameters"]["particles[0].velocity.x"];
    EXPECT_NEAR(table["rows"][k]["results"]["energy"]["start"].get<double>(), 0.5 * m * (v0 * v0 + 1), 1e-12);
    EXPECT_EQ(table["rows"][k]["state"], "succeeded");
  }
  const std::string csv = read(out / "study.csv");
  EXPECT_EQ(csv.substr(0, csv.find(',', 4)), "run,particles[0].velocity.x");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);
  const std::string svg = read(out / "study.svg");
  EXPECT_NE(svg.find(">energy.dissipated<"), std::string::npos);

  // run again: the three runs are kept, not run anew
  const CommandResult again = run_dem("study " + shell_quoted(study) + " --out " + shell_quoted(out) + " --quiet");
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(again.output.find("into"), std::string::npos) << again.output;
  EXPECT_NE(again.output.find("(done before, kept)"), std::string::npos) << again.output;
  // and the table still holds their results (it said "not run" when every run was kept)
  EXPECT_EQ(read(out / "study.csv"), csv);
  const nlohmann::json kept = nlohmann::json::parse(read(out / "study.json"));
  for (int k = 0; k < 3; ++k) EXPECT_EQ(kept["rows"][k]["state"], "succeeded") << k;

  // renamed, the study keeps them too: a run's name (the study's, with its values) is not its physics
  // (a study whose labels changed ran 40 minutes of runs again)
  std::string renamed = kStudy;
  renamed.replace(renamed.find("closing speed"), 13, "speeds");
  write_spec("study.json", renamed);
  const CommandResult third = run_dem("study " + shell_quoted(study) + " --out " + shell_quoted(out) + " --quiet");
  ASSERT_EQ(third.exit_code, 0) << third.output;
  EXPECT_EQ(third.output.find("into"), std::string::npos) << third.output;
}

// --jobs 2: two runs at once, each with its lines in its folder's run.log; the table and every
// run's results are those of the same study run one after another (the runs are deterministic).
TEST_F(CliStudy, SeveralRunsAtOnceGiveTheTableOfOneAfterAnother) {
  write_spec("base.json", kBase);
  std::string five = kStudy;
  five.replace(five.find("[0.5, 1, 2]"), 11, "[0.5, 1, 2, 3, 4]");
  const fs::path study = write_spec("study.json", five);
  const fs::path serial = dir_ / "serial", parallel = dir_ / "parallel";
  const CommandResult one = run_dem("study " + shell_quoted(study) + " --out " + shell_quoted(serial) + " --quiet");
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const CommandResult two =
      run_dem("study " + shell_quoted(study) + " --out " + shell_quoted(parallel) + " --jobs 2 --threads 1");
  ASSERT_EQ(two.exit_code, 0) << two.output;
  // the same rows, but for the wall-clock time each run took
  auto rows_of = [&](const fs::path& out) {
    nlohmann::json rows = nlohmann::json::parse(read(out / "study.json"))["rows"];
    for (nlohmann::json& row : rows) row["results"].erase("runSeconds");
    return rows;
  };
  EXPECT_EQ(rows_of(parallel), rows_of(serial));
  for (const char* run : {"run-001", "run-002", "run-003", "run-004", "run-005"}) {
    nlohmann::json here = nlohmann::json::parse(read(parallel / run / "results.json"));
    nlohmann::json there = nlohmann::json::parse(read(serial / run / "results.json"));
    here.erase("runSeconds"), there.erase("runSeconds");
    EXPECT_EQ(here, there) << run;
    const std::string log = read(parallel / run / "run.log");
    EXPECT_NE(log.find("done: steps=40"), std::string::npos) << run << ": " << log;
    EXPECT_NE(two.output.find("its lines in " + (parallel / run / "run.log").string()), std::string::npos) << run;
  }
  EXPECT_EQ(two.output.find("done: steps"), std::string::npos) << "the runs' own lines are in their logs";
  EXPECT_NE(two.output.find("5 runs, 0 failed"), std::string::npos) << two.output;
  for (const std::string bad : {"0", "65", "two", "-1", "1.5"}) {
    const CommandResult r =
        run_dem("study " + shell_quoted(study) + " --out " + shell_quoted(dir_ / "bad") + " --jobs " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_NE(r.output.find("--jobs is a whole number from 1 to 64 (got \"" + bad + "\")"), std::string::npos)
        << r.output;
  }
  EXPECT_FALSE(fs::exists(dir_ / "bad"));
}

// A table that cannot be written (a full disk: /dev/full) is said so, the one written before stays,
// and no half-written file is left beside it (an independent tester found a 0-byte study.json.part).
TEST_F(CliStudy, ATableThatCannotBeWrittenKeepsTheOneBefore) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full here";
  write_spec("base.json", kBase);
  const fs::path study = write_spec("study.json", kStudy);
  const fs::path out = dir_ / "out";
  ASSERT_EQ(run_dem("study " + shell_quoted(study) + " --out " + shell_quoted(out) + " --quiet").exit_code, 0);
  const std::string before = read(out / "study.json");
  fs::create_symlink("/dev/full", out / "study.json.part");
  const CommandResult full = run_dem("study " + shell_quoted(study) + " --out " + shell_quoted(out) + " --quiet");
  EXPECT_EQ(full.exit_code, 1);
  EXPECT_NE(full.output.find("cannot write " + (out / "study.json").string() +
                             " (a full disk?); the one written before is kept"),
            std::string::npos)
      << full.output;
  EXPECT_EQ(read(out / "study.json"), before);
  EXPECT_FALSE(fs::exists(fs::symlink_status(out / "study.json.part")));
}

// A run's folder keeps its spec standing alone, the mesh it names inline: it runs again from there,
// and a mesh changed since is a changed spec, run anew (it was kept: an independent tester). A
// results.json that cannot be read is a run to do again, not a study that cannot go on.
TEST_F(CliStudy, ARunsFolderStandsAloneAndAChangedMeshOrADamagedResultIsRunAgain) {
  const std::string mesh = "4 2\n-1 -1 0\n1 -1 0\n1 1 0\n-1 1 0\n1 2 3\n1 3 4\n";
  fs::create_directories(dir_ / "meshes");
  write_spec("meshes/floor.dat", mesh);
  write_spec("base.json", R"({
  "materials": [{"name": "glass", "density": 2500, "normalStiffness": 1e5}, {"name": "steel", "rigid": true}],
  "interactions": [{"a": "glass", "b": "glass", "restitution": 0.5, "friction": 0.3},
                   {"a": "glass", "b": "steel", "restitution": 0.5, "friction": 0.3}],
  "contact": {"normal": "LINEAR"},
  "particles": [{"position": {"z": 0.02}, "radius": 0.01, "material": "glass"}],
  "walls": [{"name": "floor", "material": "steel", "mesh": {"file": "meshes/floor.dat"}}],
  "gravity": {"z": -9.81},
  "time": {"steps": 200}
})");
  const fs::path study =
      write_spec("study.json",
                 R"({"base": "base.json", "parameters": [{"path": "particles[0].radius", "values": [0.01, 0.012]}]})");
  const fs::path out = dir_ / "out";
  const std::string command = "study " + shell_quoted(study) + " --out " + shell_quoted(out) + " --quiet";
  ASSERT_EQ(run_dem(command).exit_code, 0);
  // the run's folder runs again on its own, from anywhere
  const CommandResult alone =
      run_command("cd / && " + shell_quoted(kDem) + " run " + shell_quoted(out / "run-001" / "spec.json") + " --out " +
                  shell_quoted(dir_ / "again") + " --quiet");
  EXPECT_EQ(alone.exit_code, 0) << alone.output;
  // the same: kept; the mesh moved: run again
  EXPECT_NE(run_dem(command).output.find("(done before, kept)"), std::string::npos);
  write_spec("meshes/floor.dat", "4 2\n-1 -1 -0.01\n1 -1 -0.01\n1 1 -0.01\n-1 1 -0.01\n1 2 3\n1 3 4\n");
  CommandResult moved = run_dem(command);
  ASSERT_EQ(moved.exit_code, 0) << moved.output;
  EXPECT_EQ(moved.output.find("(done before, kept)"), std::string::npos) << moved.output;
  // a damaged results.json: that run again, the other kept
  write_spec("out/run-002/results.json", "garbage");
  const CommandResult damaged = run_dem(command);
  ASSERT_EQ(damaged.exit_code, 0) << damaged.output;
  EXPECT_NE(damaged.output.find("run 1 (particles[0].radius=0.01): succeeded"), std::string::npos) << damaged.output;
  EXPECT_NE(damaged.output.find("run 2 of 2"), std::string::npos) << damaged.output;
  const std::string csv = read(out / "study.csv");
  EXPECT_EQ(csv.find("not run"), std::string::npos) << csv;
}

// --out the study file's own folder: the table (study.json) would be written over the study (the
// bundled cases name theirs study.json): refused, the file kept (an independent tester lost one).
// And a second dem study writing into a folder another one writes into is refused: both ran the
// same runs into the same folders, and one died renaming the other's table.
TEST_F(CliStudy, AStudyWritesOverNoInputAndNoOtherStudysFolder) {
  write_spec("base.json", kBase);
  const fs::path study = write_spec("study.json", kStudy);
  CommandResult r = run_dem("study " + shell_quoted(study) + " --out " + shell_quoted(dir_) + " --quiet");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--out " + (dir_ / "study.json").string() +
                          " is the study file itself: the study's table would be written over it"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(read(study), kStudy);
  fs::create_directories(dir_ / "tables");
  const fs::path base_named_as_table = write_spec("tables/study.csv", kBase);
  write_spec("tables/s.json", R"({"base": "study.csv", "parameters": [{"path": "time.steps", "values": [10]}]})");
  r = run_dem("study " + shell_quoted(dir_ / "tables" / "s.json") + " --out " + shell_quoted(dir_ / "tables"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("is its base spec itself"), std::string::npos) << r.output;
  EXPECT_EQ(read(base_named_as_table), kBase);

  // a number past a double's range in the study file: named with its place, as dem validate does
  const fs::path far = write_spec("far.json", R"({"base": "base.json",
 "parameters": [{"path": "time.steps", "values": [10, 1e400]}]})");
  r = run_dem("study " + shell_quoted(far) + " --out " + shell_quoted(dir_ / "far") + " --plan");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("line 2, column 55: the number 1e400 is out of a double's range"), std::string::npos)
      << r.output;

  // --out a file: named, the file kept (it was the filesystem library's "Not a directory [FILE]")
  const fs::path notes = write_spec("notes.txt", "kept");
  r = run_dem("study " + shell_quoted(study) + " --out " + shell_quoted(notes) + " --quiet");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find(notes.string() + " is a file, not a folder"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("filesystem error"), std::string::npos) << r.output;
  EXPECT_EQ(read(notes), "kept");

  const fs::path out = dir_ / "out";
  fs::create_directories(out);
  r = run_command("flock " + shell_quoted(out / ".dem-study.lock") + " " + shell_quoted(kDem) + " study " +
                  shell_quoted(study) + " --out " + shell_quoted(out) + " --quiet");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("another dem study is writing into " + out.string()), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "run-001")) << "ran beside the other";
  EXPECT_EQ(run_dem("study " + shell_quoted(study) + " --out " + shell_quoted(out) + " --quiet").exit_code, 0);

  // nor over a file of that name that is not a study's table: another study file beside this one
  // (--out .), or the user's study.json where --id downloads a table (both written over, silently:
  // an independent tester's second round); nor into the run folder that holds an input
  const fs::path other = write_spec("other.json", kStudy);
  r = run_dem("study " + shell_quoted(other) + " --out " + shell_quoted(dir_));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("is there and is not a study's table or figure (a study file?)"), std::string::npos)
      << r.output;
  r = run_dem("study --id 1 --out " + shell_quoted(dir_) + " --server http://127.0.0.1:1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(read(study), kStudy);
  fs::create_directories(out / "run-002");
  const fs::path inside = write_spec("out/run-002/base.json", kBase);
  write_spec("inside.json",
             R"({"base": "out/run-002/base.json", "parameters": [{"path": "time.steps", "values": [10, 20]}]})");
  r = run_dem("study " + shell_quoted(dir_ / "inside.json") + " --out " + shell_quoted(out) + " --quiet");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("a run's folder, which the study writes"), std::string::npos) << r.output;
  EXPECT_EQ(read(inside), kBase);
}

// A key given twice in a study or its base is refused, naming it, as dem validate refuses it in a
// spec (a study took the last one silently: an independent tester).
TEST_F(CliStudy, AKeyGivenTwiceIsRefusedByName) {
  write_spec("base.json", R"({"materials": [{"name": "glass", "density": 2500, "normalStiffness": 1e5,
    "normalStiffness": 3e5}], "particles": [{"radius": 0.01, "material": "glass"}], "time": {"steps": 10}})");
  const fs::path study = write_spec("study.json", kStudy);
  CommandResult r = run_dem("study " + shell_quoted(study) + " --plan");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("base.json: materials[0].normalStiffness: is given twice in its object"), std::string::npos)
      << r.output;
  write_spec("base.json", kBase);
  const fs::path twice = write_spec("twice.json", R"({"name": "a", "name": "b", "base": "base.json",
    "parameters": [{"path": "time.steps", "values": [10]}]})");
  r = run_dem("study " + shell_quoted(twice) + " --plan");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("twice.json: name: is given twice in its object"), std::string::npos) << r.output;
}

TEST_F(CliStudy, PlanListsTheRunsWithoutRunningThem) {
  write_spec("base.json", kBase);
  const fs::path study = write_spec("study.json", kStudy);
  const CommandResult r = run_dem("study " + shell_quoted(study) + " --plan");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("study \"closing speed\": 3 runs (grid), every spec valid"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("run 2: particles[0].velocity.x=1"), std::string::npos) << r.output;
}

TEST_F(CliStudy, ABadStudyOrABadValueIsRefusedByNameBeforeAnythingRuns) {
  write_spec("base.json", kBase);
  const fs::path out = dir_ / "out";
  const fs::path bad_path = write_spec(
      "bad_path.json", R"({"base": "base.json", "parameters": [{"path": "bonds.tensileStrength", "values": [1]}]})");
  CommandResult r = run_dem("study " + shell_quoted(bad_path) + " --out " + shell_quoted(out));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("parameters[0].path: \"bonds.tensileStrength\": the base spec has no \"/bonds\""),
            std::string::npos)
      << r.output;
  // the third value is bad: nothing runs, the problem names the run, its value and the field
  const fs::path bad_value = write_spec(
      "bad_value.json",
      R"({"base": "base.json", "parameters": [{"path": "particles[1].radius", "values": [0.01, 0.011, -1]}]})");
  r = run_dem("study " + shell_quoted(bad_value) + " --out " + shell_quoted(out));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("run 3 (particles[1].radius=-1): particles[1].radius"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  const fs::path missing = write_spec("missing.json", R"({"base": "nothere.json", "parameters": []})");
  r = run_dem("study " + shell_quoted(missing) + " --out " + shell_quoted(out));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("nothere.json: cannot open the base spec"), std::string::npos) << r.output;
  const fs::path not_json = write_spec("not_json.json", "{");
  r = run_dem("study " + shell_quoted(not_json) + " --out " + shell_quoted(out));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("not_json.json: the study file is not JSON"), std::string::npos) << r.output;
  // where it is not (a trailing comma on line 2 was only "not JSON")
  const fs::path comma = write_spec("comma.json", "{\"base\": \"base.json\",\n \"parameters\": [],\n}");
  r = run_dem("study " + shell_quoted(comma) + " --out " + shell_quoted(out));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("comma.json: the study file is not JSON: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("line 3, column 1"), std::string::npos) << r.output;
  EXPECT_EQ(run_dem("study").exit_code, 2);
  EXPECT_EQ(run_dem("study " + shell_quoted(bad_path)).exit_code, 2);  // no --out
}

TEST_F(CliStudy, DemRunEndsWithItsResults) {
  const fs::path spec = write_spec("spec.json", kBase);
  const fs::path out = dir_ / "run";
  const CommandResult r = run_dem("run " + shell_quoted(spec) + " --out " + shell_quoted(out) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("results: " + (out / "results.json").string()), std::string::npos) << r.output;
  const nlohmann::json results = nlohmann::json::parse(read(out / "results.json"));
  EXPECT_EQ(results["status"], "completed");
  EXPECT_EQ(results["steps"], 40);
  EXPECT_EQ(results["particles"], 2);
  EXPECT_TRUE(results.contains("motion"));
  EXPECT_FALSE(results.contains("fragments"));  // no bonds
}

}  // namespace
}  // namespace dem::test
