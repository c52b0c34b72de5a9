// ParaView's files of a run (output/vtk_output.hpp), read back by VTK's own XML readers (Debian's
// python3-vtk9, the readers ParaView uses; tests/support/read_vtk.py) and checked against the
// legacy files the same run wrote.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "legacy/legacy_formats.hpp"
#include "output/vtk_files.hpp"
#include "output/vtk_output.hpp"
#include "support/command.hpp"

namespace dem::test {
namespace {

namespace fs = std::filesystem;

// A bonded cube of 27 spheres with weak bonds dropped onto a floor (a plane) under a rising roof (a
// plate): contacts, bonds that break, a wall that stays and one that moves.
const std::string kBlockSpec = R"({
  "name": "bonded block dropped on a floor",
  "materials": [{"name": "rock", "density": 2500, "youngsModulus": 1e7, "poissonRatio": 0.25},
                {"name": "steel", "rigid": true}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5, "friction": 0.5},
                   {"a": "rock", "b": "steel", "restitution": 0.5, "friction": 0.5}],
  "contact": {"normal": "HERTZ"},
  "lattices": [{"kind": "CUBIC", "min": {"x": 0, "y": 0, "z": 0.1}, "max": {"x": 0.06, "y": 0.06, "z": 0.16},
                "radius": 0.01, "spacing": 1.0, "material": "rock"}],
  "bonds": {"youngsModulus": 1e7, "tensileStrength": 2e4, "shearStrength": 2e4, "gapTolerance": 0.01},
  "walls": [{"name": "floor", "material": "steel", "plane": {"point": {"z": 0}, "normal": {"z": 1}}},
            {"name": "roof", "material": "steel", "plate": {"c1": {"x": -0.1, "y": -0.1, "z": 0.3},
             "c2": {"x": 0.1, "y": -0.1, "z": 0.3}, "c3": {"x": 0.1, "y": 0.1, "z": 0.3}, "c4": {"x": -0.1, "y": 0.1, "z": 0.3}},
             "motion": {"velocity": {"z": 0.5}}}],
  "gravity": {"z": -9.81},
  "time": {"duration": 0.2},
  "outputs": {"interval": 0.04, "forceChains": true, "lengthUnit": "mm", "numberFormat": "FULL"}
})";

class VtkOutput : public DemCommandTest {
 protected:
  // VTK's readers' account of each file (tests/support/read_vtk.py), by path.
  nlohmann::json read_back(const std::vector<fs::path>& files) {
    // Debian's python, whose python3-vtk9 scripts/install-deps installs (not one earlier on PATH).
    // Built by appending: GCC 12 warns falsely (-Wrestrict) about a literal + string.
    std::string command = "/usr/bin/python3 ";
    command += shell_quoted(fs::path(DEM_SOURCE_DIR) / "tests/support/read_vtk.py");
    for (const fs::path& f : files) {
      command += ' ';
      command += shell_quoted(f);
    }
    const CommandResult r = run_command(command);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    try {
      return nlohmann::json::parse(r.output);
    } catch (const std::exception& e) {
      ADD_FAILURE() << e.what() << ": " << r.output;
      return {};
    }
  }

  fs::path run_block(const std::string& spec, const std::string& name) {
    const fs::path out = dir_ / name;
    const CommandResult r =
        run_dem("run " + shell_quoted(write_spec(name + ".json", spec)) + " --out " + shell_quoted(out) + " --quiet");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return out;
  }
};

TEST_F(VtkOutput, ParaViewsReadersReadEachFrameAsTheLegacyFilesHaveIt) {
  const fs::path out = run_block(kBlockSpec, "block");
  std::ifstream animation_in(out / "ANIMATION_3D.dat");
  const auto animation = legacy::read_animation(animation_in);
  ASSERT_TRUE(animation.problem.empty()) << animation.problem;
  std::ifstream chains_in(out / "ForceChain_3D.dat");
  const auto chains = legacy::read_force_chains(chains_in);
  ASSERT_TRUE(chains.problem.empty()) << chains.problem;
  ASSERT_GE(animation.frames.size(), 6u);  // t = 0, 0.04, ..., 0.2 (and the last step)

  const nlohmann::json series =
      read_back({out / "particles.pvd", out / "contacts.pvd", out / "bonds.pvd", out / "walls.pvd"});
  for (const char* kind : {"particles", "contacts", "bonds", "walls"}) {
    const nlohmann::json& s = series[(out / (std::string(kind) + ".pvd")).string()]["series"];
    ASSERT_EQ(s.size(), animation.frames.size()) << kind;
    for (std::size_t k = 0; k < s.size(); ++k) {
      EXPECT_NEAR(s[k]["time"].get<double>(), animation.frames[k].scalars[0], 1e-12) << kind << " frame " << k;
      EXPECT_TRUE(fs::exists(out / s[k]["file"].get<std::string>())) << s[k]["file"];
    }
  }

  const nlohmann::json& particle_series = series[(out / "particles.pvd").string()]["series"];
  for (std::size_t k = 0; k < animation.frames.size(); ++k) {
    const legacy::AnimationFrame& legacy_frame = animation.frames[k];
    const std::string step = std::to_string(legacy_frame.step);
    const fs::path particles = out / particle_series[k]["file"].get<std::string>();
    EXPECT_EQ(particles.filename(), VtkWriter::frame_name("particles", legacy_frame.step));
    const fs::path contacts = out / VtkWriter::frame_name("contacts", legacy_frame.step);
    const fs::path bonds = out / VtkWriter::frame_name("bonds", legacy_frame.step);
    const fs::path walls = out / VtkWriter::frame_name("walls", legacy_frame.step);
    const nlohmann::json files = read_back({particles, contacts, bonds, walls});
    const nlohmann::json& p = files[particles.string()];
    ASSERT_FALSE(p.contains("error")) << p.dump();
    const std::size_t n = legacy_frame.particles.size();
    ASSERT_EQ(n, 27u);
    EXPECT_EQ(p["points"], n);
    EXPECT_EQ(p["cells"], n);
    EXPECT_EQ(p["cellTypes"], nlohmann::json::array({1})) << "each sphere a vertex cell";
    EXPECT_NEAR(p["fieldData"]["TimeValue"]["first"][0].get<double>(), legacy_frame.scalars[0], 1e-12);
    const nlohmann::json& data = p["pointData"];
    for (const auto& [name, components] : std::vector<std::pair<std::string, int>>{{"id", 1},
                                                                                   {"radius", 1},
                                                                                   {"mass", 1},
                                                                                   {"material", 1},
                                                                                   {"velocity", 3},
                                                                                   {"angularVelocity", 3},
                                                                                   {"displacement", 3},
                                                                                   {"force", 3},
                                                                                   {"contacts", 1},
                                                                                   {"fragment", 1}}) {
      ASSERT_TRUE(data.contains(name)) << name << " missing at step " << step;
      EXPECT_EQ(data[name]["components"], components) << name;
      EXPECT_EQ(data[name]["tuples"], n) << name;
    }
    // the legacy file in mm with every digit: the same particles, in the same order, where VTK has them in m
    for (std::size_t i = 0; i < n; ++i) {
      const legacy::AnimationParticle& lp = legacy_frame.particles[i];
      EXPECT_EQ(data["id"]["all"][i][0].get<double>(), lp.id);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(p["coordinates"][i][c].get<double>(), lp.position[c] * 1e-3, 1e-15) << "particle " << lp.id;
        EXPECT_NEAR(data["velocity"]["all"][i][c].get<double>(), lp.velocity[c] * 1e-3, 1e-15);
      }
      EXPECT_NEAR(data["radius"]["all"][i][0].get<double>(), 0.5e-3 * lp.diameter, 1e-15);
      EXPECT_EQ(data["contacts"]["all"][i][0].get<double>(), lp.contacts) << "particle " << lp.id;
    }

    // the force chains: a line per touching pair, its forces those of ForceChain_3D.dat
    const nlohmann::json& c = files[contacts.string()];
    const legacy::ForceChainFrame& chain_frame = chains.frames[k];
    ASSERT_EQ(c["cells"], chain_frame.chains.size()) << "step " << step;
    EXPECT_EQ(c["points"], 2 * chain_frame.chains.size());
    if (!chain_frame.chains.empty()) {
      EXPECT_EQ(c["cellTypes"], nlohmann::json::array({3})) << "lines";
      for (std::size_t l = 0; l < chain_frame.chains.size(); ++l) {
        EXPECT_EQ(c["cellData"]["normalForce"]["all"][l][0].get<double>(), chain_frame.chains[l].normal_force);
        EXPECT_EQ(c["cellData"]["tangentialForce"]["all"][l][0].get<double>(), chain_frame.chains[l].tangential_force);
      }
    }

    // the bonds: every bond glued at the start, broken or not, as a line with its state
    const nlohmann::json& b = files[bonds.string()];
    EXPECT_EQ(b["cells"], 54) << "a cube of 3 x 3 x 3 has 54 neighbour pairs";
    const std::vector<double> range = b["cellData"]["state"]["range"];
    EXPECT_GE(range[0], 0);
    EXPECT_LE(range[1], 2);

    // the moving walls in each frame: the roof's four corners where it has risen to
    const nlohmann::json& w = files[walls.string()];
    EXPECT_EQ(w["cells"], 1);
    EXPECT_EQ(w["cellData"]["wall"]["all"], nlohmann::json::parse("[[2.0]]"));
    EXPECT_NEAR(w["coordinates"][0][0].get<double>(), -0.1, 1e-15);
    EXPECT_NEAR(w["coordinates"][0][2].get<double>(), 0.3 + 0.5 * legacy_frame.scalars[0], 1e-12);
  }
  // the floor, which never moves, once: a square about the particles where they start
  const nlohmann::json fixed = read_back({out / "walls.vtp"}).begin().value();
  EXPECT_EQ(fixed["cells"], 1);
  EXPECT_EQ(fixed["cellData"]["wall"]["all"], nlohmann::json::parse("[[1.0]]"));
  for (int corner = 0; corner < 4; ++corner) EXPECT_EQ(fixed["coordinates"][corner][2], 0.0) << "the floor's plane";
  // the block hit the floor and its weak bonds broke: some state is 1 or 2 at the end
  const nlohmann::json last = read_back({out / VtkWriter::frame_name("bonds", animation.frames.back().step)});
  EXPECT_GT(last.begin().value()["cellData"]["state"]["range"][1].get<double>(), 0) << "no bond broke";
}

// A run into a folder another run wrote: none of the other's frames stays, and a continued run's
// series is the uninterrupted run's (the earlier run's frames were listed in it, with the wrong times).
TEST_F(VtkOutput, AnEarlierRunsFramesAreNotThisRunsEvenWhenContinued) {
  auto with = [](std::string steps, std::string every) {  // steps and frames, not seconds (the end a frame)
    std::string spec = kBlockSpec;
    spec.replace(spec.find(R"("duration": 0.2)"), 15, R"("steps": )" + steps);
    spec.replace(spec.find(R"("interval": 0.04)"), 16, R"("everySteps": )" + every);
    return spec;
  };
  const std::string full = with("8000", "1000");
  const fs::path out = run_block(full, "block");
  std::ofstream(out / "particles_0000000001.vtu") << "not a frame of this run";
  fs::create_directory(out / "particles_0000000005.vtu");
  const fs::path whole = run_block(full, "whole");
  run_block(with("8000", "500"), "block");   // every frame of another interval
  run_block(with("4000", "1000"), "block");  // the run to continue, stopped at a frame
  EXPECT_FALSE(fs::exists(out / "particles_0000000001.vtu"));
  EXPECT_TRUE(fs::is_directory(out / "particles_0000000005.vtu")) << "only files of ours are removed";
  const CommandResult r = run_dem("run " + shell_quoted(write_spec("full.json", full)) + " --out " + shell_quoted(out) +
                                  " --restart " + shell_quoted(out / "restart.dat") + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* series : {"particles.pvd", "contacts.pvd", "bonds.pvd", "walls.pvd"})
    EXPECT_EQ(read(out / series), read(whole / series)) << series;
  for (const fs::directory_entry& e : fs::directory_iterator(out)) {
    const std::string ext = e.path().extension().string();
    if ((ext == ".vtu" || ext == ".vtp" || ext == ".pvd") && !e.is_directory()) {
      EXPECT_TRUE(fs::exists(whole / e.path().filename())) << e.path().filename() << " is stale";
      EXPECT_EQ(read(e.path()), read(whole / e.path().filename())) << e.path().filename();
    }
  }
}

TEST_F(VtkOutput, NoneWhenTheSpecTurnsThemOff) {
  std::string spec = kBlockSpec;
  spec.replace(spec.find(R"("outputs": {)"), 12, R"("outputs": {"vtk": false, )");
  const fs::path out = run_block(kBlockSpec, "off");
  run_block(spec, "off");  // into the folder of a run that wrote them: none of those stays either
  ASSERT_TRUE(fs::exists(out / "ANIMATION_3D.dat"));
  for (const fs::directory_entry& e : fs::directory_iterator(out)) {
    const std::string ext = e.path().extension().string();
    EXPECT_TRUE(ext != ".vtu" && ext != ".vtp" && ext != ".pvd") << e.path();
  }
}

TEST(VtkFiles, AFullDiskIsAnErrorNamingTheFile) {
  vtk::Dataset d;
  d.type = "PolyData";
  d.points = vtk::vectors("Points", std::vector<Vec3>(10000, Vec3(1, 2, 3)));
  try {
    vtk::write("/dev/full", d, 0);
    FAIL() << "a full disk was taken for a written file";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "cannot write /dev/full: No space left on device");
  }
  EXPECT_THROW(vtk::SeriesFile("/nonexistent-folder/particles.pvd", {}), std::runtime_error);
}

}  // namespace
}  // namespace dem::test
