// Tests of the dem command (cli/): exit codes, messages naming the bad field, and the files a run
// writes. They run the built binary on small spec files in a temporary folder; every run is a few
// particles for a few steps.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "legacy/legacy_formats.hpp"
#include "support/command.hpp"

namespace {

namespace fs = std::filesystem;

using dem::test::kDem;
using dem::test::shell_quoted;
using Result = dem::test::CommandResult;

// Runs `dem ARGS` through the shell, capturing both streams.
Result dem(const std::string& args) { return dem::test::run_command(shell_quoted(kDem) + " " + args); }

// Two glass spheres 0.1 mm apart closing at 2 m/s: they touch within the 12 steps.
const char* kGoodSpec = R"({
  "name": "cli test",
  "materials": [{"name": "glass", "density": 2500, "normalStiffness": 1e5}],
  "interactions": [{"a": "glass", "b": "glass", "restitution": 0.5, "friction": 0.3}],
  "contact": {"normal": "LINEAR", "rolling": "NONE"},
  "particles": [
    {"position": {"x": 0}, "radius": 0.01, "material": "glass", "velocity": {"x": 1}},
    {"position": {"x": 0.0201}, "radius": 0.01, "material": "glass", "velocity": {"x": -1}}
  ],
  "time": {"steps": 12},
  "outputs": {"everySteps": 5, "lengthUnit": "mm"}
})";

std::string good_with(const std::string& from, const std::string& to) {
  std::string text = kGoodSpec;
  const std::size_t at = text.find(from);
  if (at == std::string::npos) {
    ADD_FAILURE() << "test set-up: \"" << from << "\" is not in the spec";
    return text;
  }
  return text.replace(at, from.size(), to);
}

// A private folder per test (ctest may run tests in parallel), removed afterwards.
class Cli : public dem::test::DemCommandTest {};

// ---------------------------------------------------------------------------------------------
// dem validate

TEST_F(Cli, ValidateAcceptsAGoodSpec) {
  const Result r = dem("validate " + shell_quoted(write_spec("good.json", kGoodSpec)));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("valid; 2 particles"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("12 steps"), std::string::npos) << r.output;
}

TEST_F(Cli, ValidateNamesANegativeRadius) {
  const Result r =
      dem("validate " + shell_quoted(write_spec("bad.json", good_with(R"("radius": 0.01)", R"("radius": -0.01)"))));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("particles[0].radius"), std::string::npos) << r.output;
}

TEST_F(Cli, ValidateNamesAnUnknownField) {
  const Result r =
      dem("validate " + shell_quoted(write_spec("bad.json", good_with(R"("radius": 0.01)", R"("raduis": 0.01)"))));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("raduis"), std::string::npos) << r.output;
}

// A field name is the user's text: one holding ESC (a terminal's colour or screen-clearing
// sequence) is named with the escape visible, as a server's text is, and no raw control byte is
// printed (dem validate, dem run).
TEST_F(Cli, AFieldNameWithControlCharactersIsNamedWithThemVisible) {
  const std::string spec =
      shell_quoted(write_spec("bad.json", good_with(R"("radius": 0.01)", R"("radius": 0.01, "bad\u001b[2Jkey": 1)")));
  for (const std::string verb : {"validate ", "run "}) {
    const Result r = dem(verb + spec + (verb == "run " ? " --out " + shell_quoted(dir_ / "out") : ""));
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("bad\\x1b[2Jkey: unknown field"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find('\x1b'), std::string::npos) << verb << "printed a raw ESC";
  }
  // two problems of the file's JSON stay two lines (escaping the line break joined them with "\x0a")
  std::string twice = good_with(R"("name": "cli test")", R"("name": "cli test", "": 2)");
  twice.replace(twice.find(R"("radius": 0.01)"), 14, R"("radius": 0.01, "": 1)");
  const Result r = dem("validate " + shell_quoted(write_spec("twice.json", twice)));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("spec: a key is empty (\"\"): unknown field\n"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\n  particles[0]: a key is empty"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("\\x0a"), std::string::npos) << r.output;
  // a byte that is not UTF-8 (a lone 0x9B, an 8-bit terminal's CSI) in the JSON parser's "last read"
  const Result byte = dem("validate " + shell_quoted(write_spec("byte.json", good_with("cli test", "cli \x9b test"))));
  EXPECT_EQ(byte.exit_code, 1) << byte.output;
  EXPECT_NE(byte.output.find("\\x9b"), std::string::npos) << byte.output;
  EXPECT_EQ(byte.output.find('\x9b'), std::string::npos) << "printed the raw byte";
}

TEST_F(Cli, ValidateNamesADtAboveTheStableLimit) {
  // The pair's contact time is about 0.75 ms: a 1 ms step is far above t_c / 10.
  const Result r = dem("validate " +
                       shell_quoted(write_spec("bad.json", good_with(R"("steps": 12)", R"("steps": 12, "dt": 1e-3)"))));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("time.dt"), std::string::npos) << r.output;
}

TEST_F(Cli, ValidateOfAMissingFileNamesIt) {
  const Result r = dem("validate " + shell_quoted(dir_ / "missing.json"));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("missing.json"), std::string::npos) << r.output;
}

TEST_F(Cli, ValidateWithoutASpecIsAUsageError) { EXPECT_EQ(dem("validate").exit_code, 2); }

// ---------------------------------------------------------------------------------------------
// dem run

TEST_F(Cli, RunWritesTheAnimationFrames) {
  const fs::path out = dir_ / "out";
  const Result r =
      dem("run " + shell_quoted(write_spec("good.json", kGoodSpec)) + " --out " + shell_quoted(out) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(out / "ANIMATION_3D.dat");
  ASSERT_TRUE(in) << "no ANIMATION_3D.dat in " << out;
  const auto read = dem::legacy::read_animation(in);
  EXPECT_FALSE(read.truncated);
  EXPECT_EQ(read.problem, "");
  // Frames at the first step, every 5 steps, and the last: steps 0, 5, 10, 12.
  ASSERT_EQ(read.frames.size(), 4u);
  const std::int64_t steps[] = {0, 5, 10, 12};
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(read.frames[k].step, steps[k]);
    ASSERT_EQ(read.frames[k].particles.size(), 2u);
    EXPECT_EQ(read.frames[k].particles[0].id, 1);
    EXPECT_EQ(read.frames[k].particles[1].id, 2);
  }
  // The first frame is the initial state, in millimetres (outputs.lengthUnit).
  const auto& first = read.frames[0].particles;
  EXPECT_NEAR(first[1].position.x(), 20.1, 1e-5);
  EXPECT_NEAR(first[0].diameter, 20.0, 1e-5);
  EXPECT_NEAR(first[0].velocity.x(), 1000.0, 1e-3);
  // Apart at the start, touching from about step 3 (0.1 mm at 2 m/s, dt = t_c / 50 = 15 us) on.
  EXPECT_EQ(first[0].contacts, 0);
  EXPECT_EQ(read.frames[1].particles[0].contacts, 1);
  EXPECT_EQ(read.frames[1].particles[1].contacts, 1);
  // Force chains were not asked for.
  EXPECT_FALSE(fs::exists(out / "ForceChain_3D.dat"));
}

// Runs `spec` with each of `names` in its own output folder made a symlink to /dev/full (which
// refuses every write with ENOSPC): the run must fail naming that file and the reason.
class CliFullDisk : public Cli {
 protected:
  void expect_each_fails(const std::string& spec, std::initializer_list<const char*> names) {
    for (const char* name : names) {
      const fs::path out = dir_ / (std::string("full_") + name);
      fs::create_directories(out);
      fs::create_symlink("/dev/full", out / name);
      const Result r =
          dem("run " + shell_quoted(write_spec("spec.json", spec)) + " --out " + shell_quoted(out) + " --quiet");
      EXPECT_EQ(r.exit_code, 1) << name << ": " << r.output;
      EXPECT_NE(r.output.find(std::string("cannot write ") + (out / name).string()), std::string::npos) << r.output;
      EXPECT_NE(r.output.find("No space left on device"), std::string::npos) << r.output;
    }
  }
};

// Every write used to go unchecked: the run ended "done" with the file empty.
TEST_F(CliFullDisk, RunWhoseOutputFileCannotBeWrittenFailsNamingIt) {
  expect_each_fails(kGoodSpec, {"ANIMATION_3D.dat", "Energy.dat", "Masscenter.dat"});
}

// Frames larger than the file's buffer fail inside the frame, not at its flush (the reason was
// reported as an I/O error); the saved state said only "cannot write the saved state".
TEST_F(CliFullDisk, RunWhoseLargeFramesOrSavedStateCannotBeWrittenNamesTheFileAndTheReason) {
  std::string particles;
  for (int k = 0; k < 100; ++k)
    particles += std::string(k ? ", " : "") + R"({"position": {"x": )" + std::to_string(0.03 * k) +
                 R"(}, "radius": 0.01, "material": "glass"})";
  expect_each_fails(good_with(R"({"position": {"x": 0}, "radius": 0.01, "material": "glass", "velocity": {"x": 1}},
    {"position": {"x": 0.0201}, "radius": 0.01, "material": "glass", "velocity": {"x": -1}})",
                              particles),
                    {"ANIMATION_3D.dat", "restart.dat.part"});
}

// A bed of 8 spheres on a floor given as an STL file, pressed by a cyclic plate (the ballast box
// in miniature): every wall file is written and reads back.
TEST_F(Cli, RunWithAMeshFloorAndALoadedPlateWritesTheWallFiles) {
  {
    std::ofstream stl(dir_ / "floor.stl");
    stl << "solid floor\n"
           "facet normal 0 0 1\nouter loop\nvertex -10 -10 0\nvertex 50 -10 0\nvertex 50 50 0\nendloop\nendfacet\n"
           "facet normal 0 0 1\nouter loop\nvertex -10 -10 0\nvertex 50 50 0\nvertex -10 50 0\nendloop\nendfacet\n"
           "endsolid floor\n";
  }
  const std::string spec = R"({
  "materials": [{"name": "stone", "density": 2600, "normalStiffness": 1e5}, {"name": "steel", "rigid": true}],
  "interactions": [{"a": "stone", "b": "stone", "restitution": 0.3, "friction": 0.5},
                   {"a": "stone", "b": "steel", "restitution": 0.3, "friction": 0.5}],
  "lattices": [{"kind": "CUBIC", "min": {"x": 0, "y": 0, "z": 0}, "max": {"x": 0.04, "y": 0.04, "z": 0.04},
                "radius": 0.01, "spacing": 1.0, "material": "stone"}],
  "walls": [
    {"name": "floor", "material": "steel", "mesh": {"file": "floor.stl", "scale": 0.001}},
    {"name": "sleeper", "material": "steel",
     "plate": {"c1": {"x": -0.01, "y": -0.01, "z": 0.04}, "c2": {"x": 0.05, "y": -0.01, "z": 0.04},
               "c3": {"x": 0.05, "y": 0.05, "z": 0.04}, "c4": {"x": -0.01, "y": 0.05, "z": 0.04}},
     "load": {"mass": 0.5, "cyclic": {"fMin": 10, "fMax": 100, "frequency": 50, "cycles": 1}}}
  ],
  "gravity": {"z": -9.81},
  "time": {"duration": 0.01},
  "outputs": {"interval": 0.002, "forceChains": true, "lengthUnit": "mm"}
})";
  const fs::path out = dir_ / "out";
  const Result r =
      dem("run " + shell_quoted(write_spec("box.json", spec)) + " --out " + shell_quoted(out) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* name : {"ANIMATION_3D.dat", "ForceChain_3D.dat", "Wall.dat", "Wall_Animation_3D.dat",
                           "Wall_ForceChain_3D.dat", "Force_Displacement.dat"})
    EXPECT_TRUE(fs::exists(out / name)) << name;
  // Wall.dat: the floor, in mm
  std::ifstream wall_in(out / "Wall.dat");
  std::string first;
  std::getline(wall_in, first);
  EXPECT_EQ(first, "4 2");
  // the plate moves: in every animation frame, with its displacement and force in the scalars
  std::ifstream anim(out / "ANIMATION_3D.dat");
  const auto frames = dem::legacy::read_animation(anim);
  ASSERT_TRUE(frames.problem.empty()) << frames.problem;
  ASSERT_GE(frames.frames.size(), 5u);
  const auto& last = frames.frames.back();
  ASSERT_EQ(last.plates.size(), 1u);
  EXPECT_GT(last.scalars[2], 5.0);                                           // the plate pushes the bed (N)
  EXPECT_NEAR(last.plates[0].corners[0].z(), 40.0 - last.scalars[1], 1e-3);  // displacement in mm, downwards
  std::ifstream wall_anim(out / "Wall_Animation_3D.dat");
  const auto wall_frames = dem::legacy::read_wall_frames(wall_anim);
  ASSERT_TRUE(wall_frames.problem.empty()) << wall_frames.problem;
  EXPECT_EQ(wall_frames.frames.size(), frames.frames.size());
  // the bed touches the floor (wall 1) and the plate (wall 2)
  std::ifstream chains_in(out / "Wall_ForceChain_3D.dat");
  const auto chains = dem::legacy::read_wall_force_chains(chains_in);
  ASSERT_TRUE(chains.problem.empty()) << chains.problem;
  int floor = 0, plate = 0;
  for (const auto& c : chains.frames.back().chains) (c.wall == 1 ? floor : plate) += c.wall <= 2;
  EXPECT_EQ(floor, 4);
  EXPECT_EQ(plate, 4);
  std::ifstream fd_in(out / "Force_Displacement.dat");
  const auto rows = dem::legacy::read_force_displacement(fd_in);
  ASSERT_TRUE(rows.problem.empty()) << rows.problem;
  EXPECT_EQ(rows.frames.size(), frames.frames.size());
  EXPECT_EQ(rows.frames.back().force, last.scalars[2]);
}

// A run stopped at step 10 and continued from its restart.dat writes the same files as one run.
TEST_F(Cli, RunContinuedFromItsSavedStateWritesTheSameFiles) {
  const fs::path whole = dir_ / "whole", part = dir_ / "part";
  const std::string spec12 = good_with(R"("outputs": {)", R"("outputs": {"forceChains": true, )");
  std::string spec10 = spec12;
  spec10.replace(spec10.find(R"("steps": 12)"), 11, R"("steps": 10)");
  ASSERT_EQ(dem("run " + shell_quoted(write_spec("s12.json", spec12)) + " --out " + shell_quoted(whole) + " --quiet")
                .exit_code,
            0);
  ASSERT_EQ(dem("run " + shell_quoted(write_spec("s10.json", spec10)) + " --out " + shell_quoted(part) + " --quiet")
                .exit_code,
            0);
  ASSERT_TRUE(fs::exists(part / "restart.dat"));
  const Result r = dem("run " + shell_quoted(dir_ / "s12.json") + " --out " + shell_quoted(part) + " --restart " +
                       shell_quoted(part / "restart.dat") + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // the summary counts the steps this run took (10 -> 12), the ones its loop_seconds timed
  EXPECT_NE(r.output.find("done: steps=2 particles=2 "), std::string::npos) << r.output;
  auto bytes = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_EQ(bytes(whole / "ANIMATION_3D.dat"), bytes(part / "ANIMATION_3D.dat"));
  EXPECT_EQ(bytes(whole / "ForceChain_3D.dat"), bytes(part / "ForceChain_3D.dat"));
  EXPECT_EQ(bytes(whole / "restart.dat"), bytes(part / "restart.dat"));
  // ParaView's series lists the frames of both runs, each file as the one run wrote it
  for (const char* series : {"particles.pvd", "contacts.pvd", "walls.vtp"})
    EXPECT_EQ(bytes(whole / series), bytes(part / series)) << series;
  for (const fs::directory_entry& e : fs::directory_iterator(whole)) {
    if (e.path().extension() == ".vtu" || e.path().extension() == ".vtp") {
      EXPECT_EQ(bytes(e.path()), bytes(part / e.path().filename())) << e.path().filename();
    }
  }
  // a state from another job is refused, and the files are left as they were
  const std::string other = good_with(R"("radius": 0.01, "material": "glass", "velocity": {"x": -1})",
                                      R"("radius": 0.01, "material": "glass", "velocity": {"x": -1}},
    {"position": {"y": 0.1}, "radius": 0.01, "material": "glass")");
  const std::string before = bytes(part / "ANIMATION_3D.dat");
  const Result bad = dem("run " + shell_quoted(write_spec("other.json", other)) + " --out " + shell_quoted(part) +
                         " --restart " + shell_quoted(part / "restart.dat") + " --quiet");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.output.find("the saved state was written for another job: particles 2"), std::string::npos)
      << bad.output;
  EXPECT_EQ(bytes(part / "ANIMATION_3D.dat"), before);
}

// A staged run: Stages.dat lists each stage's start, every stage's last step is a frame, and the
// progress line names the stage.
TEST_F(Cli, RunOfAStagedJobLogsItsStagesAndWritesAFrameAtEachStagesEnd) {
  const std::string staged = good_with(R"("time": {"steps": 12},)", R"("stages": [{"name": "close", "steps": 7},
    {"name": "after impact", "steps": 5, "gravity": {"z": -9.81}}],)");
  const fs::path out = dir_ / "staged";
  const Result r = dem("run " + shell_quoted(write_spec("staged.json", staged)) + " --out " + shell_quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("stage after impact"), std::string::npos) << r.output;
  std::ifstream log(out / "Stages.dat");
  std::string header, first, second, rest;
  std::getline(log, header);
  std::getline(log, first);
  std::getline(log, second);
  EXPECT_EQ(header, "stage start_step start_time name");
  EXPECT_EQ(first, "1 0 0.0000000000000000e+00 close");
  EXPECT_EQ(second.substr(0, 4), "2 7 ");
  EXPECT_NE(second.find(" after impact"), std::string::npos) << second;
  EXPECT_FALSE(std::getline(log, rest));
  // frames at steps 0, 5, 7 (the first stage's end), 10, 12
  std::ifstream anim(out / "ANIMATION_3D.dat");
  const auto frames = dem::legacy::read_animation(anim);
  ASSERT_EQ(frames.frames.size(), 5u);
  EXPECT_EQ(frames.frames[2].step, 7);
}

// A staged run's walls in the files: a mesh the second stage removes is drawn in the wall frames
// while it is there (and not in Wall.dat, which the viewer shows for the whole run), a plate given
// a load at the second stage starts Force_Displacement.dat's rows there.
TEST_F(Cli, RunOfAStagedJobDrawsAWallWhileItIsThereAndLogsALoadFromItsStage) {
  const std::string staged = good_with(R"("time": {"steps": 12},)", R"(
  "walls": [{"name": "cage", "material": "glass", "mesh": {"vertices": [{"z": 1}, {"x": 0.1, "z": 1}, {"y": 0.1, "z": 1}, {"z": 1.1}],
             "triangles": [{"i": 1, "j": 3, "k": 2}, {"i": 1, "j": 2, "k": 4}, {"i": 1, "j": 4, "k": 3}, {"i": 2, "j": 3, "k": 4}]}},
            {"name": "lid", "material": "glass", "plate": {"c1": {"x": -1, "y": -1, "z": 0.5}, "c2": {"x": 1, "y": -1, "z": 0.5},
             "c3": {"x": 1, "y": 1, "z": 0.5}, "c4": {"x": -1, "y": 1, "z": 0.5}}}],
  "stages": [{"name": "caged", "steps": 6},
             {"name": "freed", "steps": 6, "removeWalls": ["cage"],
              "wallChanges": [{"wall": "lid", "load": {"servo": {"target": 1, "gain": 1e-3, "maxSpeed": 0.1}}}]}],)");
  const fs::path out = dir_ / "walls";
  const Result r =
      dem("run " + shell_quoted(write_spec("walls.json", staged)) + " --out " + shell_quoted(out) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(fs::exists(out / "Wall.dat"));  // its only mesh comes and goes
  std::ifstream walls(out / "Wall_Animation_3D.dat");
  const auto frames = dem::legacy::read_wall_frames(walls);
  ASSERT_EQ(frames.frames.size(), 5u);  // steps 0, 5, 6 (the first stage's end), 10, 12
  EXPECT_EQ(frames.frames[2].triangles.size(), 4u);
  EXPECT_EQ(frames.frames[3].triangles.size(), 0u);
  EXPECT_EQ(frames.frames[3].plates.size(), 1u);
  std::ifstream force(out / "Force_Displacement.dat");
  int rows = 0;
  for (std::string line; std::getline(force, line);) rows += !line.empty();
  EXPECT_EQ(rows, 2);  // steps 10 and 12: the load began at step 6
}

// A staged run continued from the state saved at a stage's end (before the next stage's first
// frame) writes the same files as the whole run: Stages.dat gets no line twice.
TEST_F(Cli, RunOfAStagedJobContinuedAtAStageBoundaryWritesTheSameFiles) {
  const std::string staged = good_with(R"("time": {"steps": 12},)", R"("stages": [{"name": "close", "steps": 7},
    {"name": "on", "steps": 5}],)");
  const fs::path whole = dir_ / "whole", part = dir_ / "part";
  ASSERT_EQ(dem("run " + shell_quoted(write_spec("whole.json", staged)) + " --out " + shell_quoted(whole) + " --quiet")
                .exit_code,
            0);
  // the first stage alone, then the whole spec continued from its saved state (step 7)
  const std::string first = good_with(R"("time": {"steps": 12},)", R"("stages": [{"name": "close", "steps": 7}],)");
  ASSERT_EQ(dem("run " + shell_quoted(write_spec("first.json", first)) + " --out " + shell_quoted(part) + " --quiet")
                .exit_code,
            0);
  const Result r = dem("run " + shell_quoted(dir_ / "whole.json") + " --out " + shell_quoted(part) + " --restart " +
                       shell_quoted(part / "restart.dat") + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto bytes = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  for (const char* name : {"Stages.dat", "ANIMATION_3D.dat", "Energy.dat"})
    EXPECT_EQ(bytes(whole / name), bytes(part / name)) << name;
}

// Bonds glued by a stage: the bond statistics files are written from the start of the run.
TEST_F(Cli, RunOfAJobWhoseStageGluesBondsWritesTheBondStatistics) {
  const std::string staged = good_with(R"("time": {"steps": 12},)", R"(
  "bonds": {"youngsModulus": 1e7, "tensileStrength": 1e5, "shearStrength": 1e5, "gapTolerance": 0.05},
  "stages": [{"name": "close", "steps": 6}, {"name": "glue", "steps": 6, "bond": true}],)");
  const fs::path out = dir_ / "glued";
  const Result r =
      dem("run " + shell_quoted(write_spec("glued.json", staged)) + " --out " + shell_quoted(out) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* name : {"Fragments.dat", "Fragment_Sizes.dat", "Bond_Breaks.dat"})
    EXPECT_TRUE(fs::exists(out / name)) << name;
}

// A bonded 2 x 2 x 2 block dropped on a floor: the statistics files have a row per frame, and the
// animation's part column names the block's fragment.
TEST_F(Cli, RunOfABondedBlockWritesTheStatistics) {
  const std::string spec = R"({
  "materials": [{"name": "rock", "density": 2600, "normalStiffness": 1e5}, {"name": "ground", "rigid": true}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5, "friction": 0.5},
                   {"a": "rock", "b": "ground", "restitution": 0.5, "friction": 0.5}],
  "lattices": [{"kind": "CUBIC", "min": {"x": 0, "y": 0, "z": 0.001}, "max": {"x": 0.04, "y": 0.04, "z": 0.041},
                "radius": 0.01, "spacing": 0.999, "material": "rock"}],
  "walls": [{"material": "ground", "plane": {"normal": {"z": 1}}}],
  "bonds": {"youngsModulus": 1e7, "tensileStrength": 1e9, "shearStrength": 1e9},
  "gravity": {"z": -9.81},
  "time": {"duration": 0.05},
  "outputs": {"interval": 0.01}
})";
  const fs::path out = dir_ / "out";
  const Result r =
      dem("run " + shell_quoted(write_spec("block.json", spec)) + " --out " + shell_quoted(out) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto rows = [&](const char* name, std::size_t columns) {
    std::ifstream in(out / name);
    const auto read = dem::legacy::read_rows(in, columns);
    EXPECT_TRUE(read.problem.empty()) << name << ": " << read.problem;
    return read.frames;
  };
  const auto centre = rows("Masscenter.dat", 4), moved = rows("Disp_Max.dat", 2), coord = rows("Coord_OL.dat", 3),
             parts = rows("Fragments.dat", 6);
  ASSERT_EQ(centre.size(), 6u);  // t = 0, 0.01, ..., 0.05
  EXPECT_EQ(moved.size(), 6u);
  EXPECT_EQ(coord.size(), 6u);
  ASSERT_EQ(parts.size(), 6u);
  EXPECT_NEAR(centre[0][1], 0.01 + 0.00999, 1e-6);  // the block's centre, x
  EXPECT_LT(centre.back()[3], centre.front()[3]);   // it fell
  EXPECT_EQ(moved[0][1], 0.0);
  EXPECT_GT(moved.back()[1], 0.0);
  EXPECT_NEAR(coord[0][1], 3.0, 1e-12);   // 12 touching pairs among 8 spheres (none on the floor yet)
  EXPECT_NEAR(coord[0][2], 0.001, 1e-9);  // overlap 0.001 d over r_i + r_j = d
  EXPECT_EQ(parts.back()[1], 1.0);        // one fragment
  EXPECT_EQ(parts.back()[2], 8.0);        // of all 8
  EXPECT_EQ(parts.back()[3], 12.0);       // 12 intact bonds
  std::ifstream anim(out / "ANIMATION_3D.dat");
  const auto frames = dem::legacy::read_animation(anim);
  ASSERT_FALSE(frames.frames.empty());
  for (const auto& particle : frames.frames.back().particles) EXPECT_EQ(particle.part, 1);
  const auto sizes = rows("Fragment_Sizes.dat", 3);
  ASSERT_EQ(sizes.size(), 6u);  // one size (8 particles, 1 fragment) per frame
  EXPECT_EQ(sizes.back()[1], 8.0);
  EXPECT_EQ(sizes.back()[2], 1.0);
  EXPECT_TRUE(rows("Bond_Breaks.dat", 4).empty());

  // with no strength every bond breaks at once: 12 breaks at t = 0, then 8 loose grains
  std::string weak = spec;
  const std::string strong = R"("tensileStrength": 1e9, "shearStrength": 1e9)";
  weak.replace(weak.find(strong), strong.size(), R"("tensileStrength": 0, "shearStrength": 0)");
  const fs::path loose = dir_ / "loose";
  ASSERT_EQ(dem("run " + shell_quoted(write_spec("weak.json", weak)) + " --out " + shell_quoted(loose) + " --quiet")
                .exit_code,
            0);
  std::ifstream breaks_in(loose / "Bond_Breaks.dat");
  const auto breaks = dem::legacy::read_rows(breaks_in, 4).frames;
  ASSERT_EQ(breaks.size(), 12u);
  for (const auto& b : breaks) {
    EXPECT_EQ(b[0], 0.0);
    EXPECT_LT(b[1], b[2]);
    EXPECT_EQ(b[3], 1.0);  // in tension (sigma = 0 reaches a strength of 0 first)
  }
  std::ifstream sizes_in(loose / "Fragment_Sizes.dat");
  const auto loose_sizes = dem::legacy::read_rows(sizes_in, 3).frames;
  ASSERT_FALSE(loose_sizes.empty());
  EXPECT_EQ(loose_sizes.back()[1], 1.0);
  EXPECT_EQ(loose_sizes.back()[2], 8.0);
}

TEST_F(Cli, RunOfALatticeWritesEveryParticle) {
  // An fcc lattice of 2 x 2 x 2 cells (32 spheres, see test_lattice.cpp) at spacing 1.1, at rest,
  // 1 m away from the two listed spheres. The box holds 4 half-cell layers of h per axis plus a
  // margin smaller than a layer.
  const double h = 1.1 * 0.02 / std::sqrt(2.0), side = 0.02 + 3.5 * h;
  char lattice[400];
  std::snprintf(lattice, sizeof lattice,
                R"("lattices": [{"kind": "FCC", "min": {"x": 1, "y": 1, "z": 1},
                   "max": {"x": %.9f, "y": %.9f, "z": %.9f}, "radius": 0.01, "spacing": 1.1, "material": "glass"}],)",
                1 + side, 1 + side, 1 + side);
  std::string spec = good_with(R"("particles": [)", std::string(lattice) + R"("particles": [)");
  const fs::path out = dir_ / "out";
  const Result r =
      dem("run " + shell_quoted(write_spec("lattice.json", spec)) + " --out " + shell_quoted(out) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(out / "ANIMATION_3D.dat");
  const auto read = dem::legacy::read_animation(in);
  ASSERT_EQ(read.frames.size(), 4u) << read.problem;
  for (const auto& frame : read.frames) EXPECT_EQ(frame.particles.size(), 34u);  // 2 listed + 32
}

TEST_F(Cli, RunOfABadSpecFailsAndWritesNothing) {
  const fs::path out = dir_ / "out";
  const Result r =
      dem("run " + shell_quoted(write_spec("bad.json", good_with(R"("radius": 0.01)", R"("radius": -0.01)"))) +
          " --out " + shell_quoted(out) + " --quiet");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("particles[0].radius"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out)) << "a failed run created " << out;
}

TEST_F(Cli, RunWithAnUnstableDtFailsAndWritesNothing) {
  const fs::path out = dir_ / "out";
  const Result r =
      dem("run " + shell_quoted(write_spec("bad.json", good_with(R"("steps": 12)", R"("steps": 12, "dt": 1e-3)"))) +
          " --out " + shell_quoted(out) + " --quiet");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("time.dt"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

// --out naming a file, or a folder inside one: the option and the file are named, not the
// filesystem library's "cannot create directories: Not a directory [afile]"; the file is kept.
TEST_F(Cli, RunWhoseOutIsAFileOrInsideOneNamesItAndKeepsTheFile) {
  const fs::path file = dir_ / "notes.txt";
  std::ofstream(file) << "kept\n";
  const std::string spec = shell_quoted(write_spec("good.json", kGoodSpec));
  for (const fs::path& out : {file, file / "run"}) {
    const Result r = dem("run " + spec + " --out " + shell_quoted(out) + " --quiet");
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("--out " + out.string() + ": "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(file.string() + " is a file, not a folder"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("filesystem error"), std::string::npos) << r.output;
  }
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "kept");
  // a link to nothing: named as such (it was "cannot make the folder: File exists")
  fs::create_symlink(dir_ / "nowhere", dir_ / "dangling");
  const Result r = dem("run " + spec + " --out " + shell_quoted(dir_ / "dangling") + " --quiet");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("dangling is a link to " + (dir_ / "nowhere").string() + ", which is not there"),
            std::string::npos)
      << r.output;
}

TEST_F(Cli, RunWithoutOutIsAUsageError) {
  const Result r = dem("run " + shell_quoted(write_spec("good.json", kGoodSpec)));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--out"), std::string::npos) << r.output;
}

TEST_F(Cli, RunWithOutButNoValueIsAUsageError) {
  EXPECT_EQ(dem("run " + shell_quoted(write_spec("good.json", kGoodSpec)) + " --out").exit_code, 2);
}

TEST_F(Cli, RunWithAnUnknownOptionIsAUsageError) {
  const fs::path out = dir_ / "out";
  const Result r =
      dem("run " + shell_quoted(write_spec("good.json", kGoodSpec)) + " --out " + shell_quoted(out) + " --fast");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--fast"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, RunWithNegativeThreadsIsAUsageError) {
  const fs::path out = dir_ / "out";
  EXPECT_EQ(
      dem("run " + shell_quoted(write_spec("good.json", kGoodSpec)) + " --out " + shell_quoted(out) + " --threads -1")
          .exit_code,
      2);
}

// --threads past the spec's limit (numerics.threads, 256) was taken: 1,000 threads ran a scene 100 times
// slower (an independent tester's find)
TEST_F(Cli, RunWithMoreThreadsThanASpecMayAskIsAUsageError) {
  const fs::path out = dir_ / "out";
  const Result r =
      dem("run " + shell_quoted(write_spec("good.json", kGoodSpec)) + " --out " + shell_quoted(out) + " --threads 257");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--threads must be a whole number in [0, 256]"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, UnknownCommandIsAUsageError) { EXPECT_EQ(dem("frobnicate").exit_code, 2); }

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Bonded spheres on a mesh floor under a plate with a cyclic load, and a plane: every kind of record
// the saved state holds (bonds, mesh contacts, wall drivers and loads).
const char* kEveryRecordSpec = R"({
  "materials": [{"name": "rock", "density": 2600, "normalStiffness": 1e5}, {"name": "steel", "rigid": true}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.4, "friction": 0.5},
                   {"a": "rock", "b": "steel", "restitution": 0.4, "friction": 0.5}],
  "lattices": [{"kind": "FCC", "min": {"x": 0, "y": 0, "z": 0.0052}, "max": {"x": 0.03, "y": 0.03, "z": 0.03},
                "radius": 0.005, "material": "rock"}],
  "bonds": {"youngsModulus": 1e7, "tensileStrength": 2e4, "shearStrength": 2e4},
  "walls": [
    {"name": "floor", "material": "steel", "mesh": {
      "vertices": [{"x": -0.05, "y": -0.05}, {"x": 0.1, "y": -0.05}, {"x": 0.1, "y": 0.1}, {"x": -0.05, "y": 0.1}],
      "triangles": [{"i": 1, "j": 2, "k": 3}, {"i": 1, "j": 3, "k": 4}]}},
    {"name": "side", "material": "steel", "plane": {"point": {"x": -0.01}, "normal": {"x": 1}}},
    {"name": "press", "material": "steel",
     "plate": {"c1": {"x": -0.02, "y": -0.02, "z": 0.045}, "c2": {"x": 0.06, "y": -0.02, "z": 0.045},
               "c3": {"x": 0.06, "y": 0.06, "z": 0.045}, "c4": {"x": -0.02, "y": 0.06, "z": 0.045}},
     "load": {"mass": 0.05, "cyclic": {"fMin": 1, "fMax": 10, "frequency": 20, "cycles": 2}}}],
  "gravity": {"z": -9.81},
  "time": {"steps": 300},
  "outputs": {"everySteps": 100}
})";

// A saved state is its values' bytes and nothing else: two runs of one spec write the same
// restart.dat (an independent tester found 1 to 16 bytes differing, the padding inside the wall
// drivers' records, loads, bonds and mesh slots; then, under AddressSanitizer's allocator, a plane's corners,
// which Eigen left unset).
TEST_F(Cli, TwoRunsOfOneSpecSaveTheSameBytes) {
  const fs::path spec = write_spec("every.json", kEveryRecordSpec);
  for (const char* out : {"a", "b"}) {
    const Result r = dem("run " + shell_quoted(spec) + " --out " + shell_quoted(dir_ / out) + " --quiet");
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  const std::string a = file_bytes(dir_ / "a" / "restart.dat"), b = file_bytes(dir_ / "b" / "restart.dat");
  ASSERT_EQ(a.size(), b.size());
  std::size_t differing = 0, first = a.size();
  for (std::size_t k = 0; k < a.size(); ++k)
    if (a[k] != b[k]) {
      ++differing;
      first = std::min(first, k);
    }
  EXPECT_EQ(differing, 0u) << "the first at byte " << first << " of " << a.size();
}

}  // namespace
