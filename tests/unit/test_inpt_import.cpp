// `dem import` (import/inpt_import.hpp, engine/legacy/inpt_file.hpp): both manuals' INPT.inp files, as
// their figures 4.14 and 5.2 print them, become specs that load and run, with every line's fate;
// malformed files are refused naming the line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "import/inpt_import.hpp"
#include "legacy/inpt_file.hpp"
#include "sim/simulation.hpp"
#include "spec/spec_loader.hpp"

namespace dem::test {
namespace {

const std::filesystem::path kData = std::filesystem::path(DEM_SOURCE_DIR) / "tests" / "data" / "inpt";

std::string read(const std::string& name) {
  std::ifstream in(kData / name, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string error_of(const std::string& text, const import::ImportOptions& options = {}) {
  try {
    import::import_inpt(text, options);
  } catch (const legacy::InptError& e) {
    return e.what();
  }
  return "";
}

// The text with line `number` (1-based) replaced.
std::string with_line(const std::string& text, int number, const std::string& line) {
  std::istringstream in(text);
  std::string out, l;
  for (int k = 1; std::getline(in, l); ++k) out += (k == number ? line : l) + "\n";
  return out;
}

TEST(InptImport, PdemEgdsFigureBecomesAStagedKeyBlockThatLoadsAndRuns) {
  import::ImportOptions options;
  options.meshes = {"terrain.dat", "funnel.dat"};
  const import::Imported imported = import::import_inpt(read("pdem_egd_figure_4_14.inp"), options);
  EXPECT_EQ(imported.program, import::Program::PdemEgd);
  ASSERT_EQ(imported.lines.size(), 32u);
  for (const import::LineFate& line : imported.lines) EXPECT_FALSE(line.fate.empty()) << line.number;
  EXPECT_EQ(imported.lines[13].name, "D");
  EXPECT_EQ(imported.lines[29].fate.rfind("dropped: ", 0), 0u) << imported.lines[29].fate;  // BRATIO
  const auto& spec = imported.spec;
  EXPECT_EQ(spec["lattices"][0]["kind"], "HEX");
  EXPECT_EQ(spec["lattices"][0]["countX"], 11);
  EXPECT_EQ(spec["lattices"][0]["countZ"], 42);
  EXPECT_EQ(spec["lattices"][0]["sizes"]["kind"], "UNIFORM");
  EXPECT_DOUBLE_EQ(spec["lattices"][0]["sizes"]["dMax"].get<double>(), 1.05 * 15);
  EXPECT_EQ(spec["bonds"]["model"], "PARALLEL");
  EXPECT_DOUBLE_EQ(spec["bonds"]["tensileStrength"].get<double>(), 16e6);
  EXPECT_DOUBLE_EQ(spec["gravity"]["z"].get<double>(), -9.8);
  EXPECT_EQ(spec["outputs"]["everySteps"], 2000);
  EXPECT_EQ(spec["outputs"]["lastFrames"], 50);
  EXPECT_EQ(spec["contact"]["normal"], "LINEAR");
  // the stages add up to nstep: fill, grow, bond, release (the funnel removed)
  long long steps = 0;
  for (const auto& stage : spec["stages"]) steps += stage["steps"].get<long long>();
  EXPECT_EQ(steps, 200000);
  EXPECT_EQ(spec["stages"][0]["steps"], 150000);
  EXPECT_EQ(spec["stages"][2]["bond"], true);
  EXPECT_EQ(spec["stages"][3]["removeWalls"][0], "funnel");

  const Scene scene = spec::to_scene(spec::parse_json(spec.dump()), kData.string());
  EXPECT_GT(scene.particles.size(), 100u);
  EXPECT_EQ(scene.walls.size(), 2u);
  Simulation sim(scene);
  EXPECT_EQ(sim.total_steps(), 200000);
  for (int k = 0; k < 20; ++k) sim.step();
  EXPECT_FALSE(sim.first_non_finite());
}

TEST(InptImport, BallastDemsFigureBecomesASettledBoxLoadedCyclically) {
  const import::Imported imported = import::import_inpt(read("ballastdem_figure_5_2.inp"), {});
  EXPECT_EQ(imported.program, import::Program::BallastDem);
  ASSERT_EQ(imported.lines.size(), 36u);
  for (const import::LineFate& line : imported.lines) EXPECT_FALSE(line.fate.empty()) << line.number;
  const auto& spec = imported.spec;
  EXPECT_DOUBLE_EQ(spec["ballastStones"][0]["massMax"].get<double>(), 0.3);
  EXPECT_DOUBLE_EQ(spec["ballastStones"][0]["massMin"].get<double>(), 0.1);
  EXPECT_EQ(spec["ballastStones"][0]["maxSpheres"], 20);
  const auto& load = spec["stages"][2]["wallChanges"][0]["load"];
  EXPECT_DOUBLE_EQ(load["cyclic"]["fMax"].get<double>(), 51840);
  EXPECT_DOUBLE_EQ(load["cyclic"]["fMin"].get<double>(), 1500);
  EXPECT_EQ(load["cyclic"]["cycles"], 15);
  EXPECT_DOUBLE_EQ(spec["stages"][2]["duration"].get<double>(), 5.0);  // 15 cycles at 3 Hz
  EXPECT_DOUBLE_EQ(spec["gravity"]["z"].get<double>(), -9.8);

  const Scene scene = spec::to_scene(spec::parse_json(spec.dump()));
  EXPECT_GT(scene.clumps.size(), 10u);
  Simulation sim(scene);
  for (int k = 0; k < 20; ++k) sim.step();
  EXPECT_FALSE(sim.first_non_finite());
}

TEST(InptImport, FortranNumbersAndWholeNumbersWrittenAsRealsAreRead) {
  std::string text = read("pdem_egd_figure_4_14.inp");
  text = with_line(text, 16, "1.0D9, 3.0E-1 (YoungM: Young's Modulus, PoissonR)");
  text = with_line(text, 4, "2.0E5 (nstep)");
  const import::Imported imported = import::import_inpt(text, {});
  EXPECT_DOUBLE_EQ(imported.spec["materials"][0]["youngsModulus"].get<double>(), 1e9);
  EXPECT_DOUBLE_EQ(imported.spec["materials"][0]["poissonRatio"].get<double>(), 0.3);
}

TEST(InptImport, AMalformedFileIsRefusedNamingTheLine) {
  const std::string pdem = read("pdem_egd_figure_4_14.inp");
  const std::pair<std::string, std::string> cases[] = {
      {with_line(pdem, 14, "abc (D: particle diameter)"), "INPT.inp line 14: D must be a number (got \"abc\")"},
      {with_line(pdem, 14, "(D: particle diameter)"), "INPT.inp line 14: has no value before its comment"},
      {with_line(pdem, 9, ""), "INPT.inp line 9: is blank"},
      {with_line(pdem, 2, "XYZ (pattern)"), "INPT.inp line 2 (pattern): must be HEX, FCC or LOS (got \"XYZ\")"},
      {with_line(pdem, 12, "1.05 (Dmax/D, Dmin/D)"),
       "INPT.inp line 12 (Dmax/D, Dmin/D): has 1 value where it holds 2: \"1.05\""},
      {with_line(pdem, 19, "0.5, 0.2 (amu, eps: restitution"), "INPT.inp line 19: its comment's \"(\" is not closed"},
      {with_line(pdem, 5, "250000, 100 (NFILL, NGROWTH)"), "INPT.inp line 5 (NFILL, NGROWTH): NFILL + NGROWTH + 1"},
      {with_line(pdem, 1, "maybe (restart)"), "INPT.inp line 1: restart must be .true. or .false. (got \"maybe\")"},
      {with_line(pdem, 3, "X (BOND_MODEL)"), "INPT.inp line 3 (BOND_MODEL): must be P (parallel bond) or C"},
      {pdem.substr(0, pdem.rfind("1 (TContact")),
       "INPT.inp has 31 lines, and PDEM-EGD's has 32: it ends before line 32 (TContact)"},
      {pdem + "7 (more)\n", "INPT.inp line 33: PDEM-EGD's INPT.inp has 32 lines, and this one has 33"},
      {"", "INPT.inp is empty"},
      {"1\n2\n", "INPT.inp has 2 lines: too few"},
      {with_line(pdem, 3, "??? (what)"), "INPT.inp line 3: \"???\" is neither"},
      {with_line(pdem, 7, "1\x01 (MPrint)"), "INPT.inp line 7: holds a control character"},
      // what an independent tester found accepted in silence
      {with_line(pdem, 14, "15.0, 16.0 (D: particle diameter)"), "INPT.inp line 14 (D): has 2 values where it holds 1"},
      {with_line(pdem, 14, "15.0 (D: particle diameter) 16"), "INPT.inp line 14: text follows its comment: \"16\""},
      {with_line(pdem, 12, "1.05,, 0.95 (Dmax/D, Dmin/D)"), "INPT.inp line 12: an empty value between two commas"},
      {with_line(pdem, 26, "-9.8 (gz)"),
       "INPT.inp line 26 (gz): the size of gravity, which pulls down: must be >= 0 (got -9.8)"},
  };
  for (const auto& [text, message] : cases) {
    const std::string error = error_of(text);
    EXPECT_NE(error.find(message), std::string::npos) << "expected: " << message << "\ngot: " << error;
  }
  const std::string ballast = read("ballastdem_figure_5_2.inp");
  EXPECT_NE(error_of(with_line(ballast, 12, "2,2 (IPATTERN)")).find("INPT.inp line 12 (IPATTERN): only 4"),
            std::string::npos);
  import::ImportOptions with_mesh;
  with_mesh.meshes = {"terrain.dat"};
  EXPECT_NE(error_of(ballast, with_mesh).find("takes no mesh files"), std::string::npos);
  EXPECT_NE(error_of(with_line(ballast, 13, "100.5, 0.0 (Nparticle)"))
                .find("INPT.inp line 13: Nparticle must be a whole number (got \"100.5\")"),
            std::string::npos);
  // found by the fuzz target: a density of 0 made the stones' count and stiffness infinite
  EXPECT_NE(error_of(with_line(ballast, 19, ".0,2545.0 (dens)"))
                .find("INPT.inp line 19 (dens_1, dens_2): dens_1 must be positive"),
            std::string::npos);
  EXPECT_NE(error_of(with_line(pdem, 16, "1.0E308, 0.3 (YoungM)"))
                .find("INPT.inp line 16 (YoungM, PoissonR): materials[0].normalStiffness: is not a finite number"),
            std::string::npos)
      << error_of(with_line(pdem, 16, "1.0E308, 0.3 (YoungM)"));
  // from a second round of attack: each named by its own line
  EXPECT_NE(
      error_of(with_line(pdem, 14, "1e300 (D)")).find("INPT.inp line 14 (D): must be a diameter from 1e-9 m to 1000 m"),
      std::string::npos);
  EXPECT_NE(error_of(with_line(ballast, 13, "-100, 0.0 (Nparticle)"))
                .find("INPT.inp line 13 (Nparticle): must be >= 0 (got -100)"),
            std::string::npos);
  EXPECT_NE(error_of(with_line(ballast, 19, "2545.0,0 (dens)"))
                .find("INPT.inp line 19 (dens_1, dens_2): dens_2 must be positive"),
            std::string::npos);
  import::ImportOptions three;
  three.meshes = {"terrain.dat", "funnel.dat", "funnel.dat"};
  EXPECT_NE(error_of(pdem, three).find("PDEM-EGD takes at most two mesh files (the terrain, then the funnel): got 3"),
            std::string::npos);
}

// A value the spec then refuses is named by the INPT line it came from, not only the spec field.
TEST(InptImport, ASpecProblemIsTracedToItsInptLine) {
  const import::Imported imported =
      import::import_inpt(with_line(read("pdem_egd_figure_4_14.inp"), 15, "0.0 (dens)"), {});
  std::vector<std::string> problems;
  try {
    spec::to_scene(spec::parse_json(imported.spec.dump()));
  } catch (const spec::SpecError& e) {
    problems = e.problems();
  }
  ASSERT_FALSE(problems.empty());
  const std::vector<std::string> located = import::locate(imported, problems);
  ASSERT_EQ(located.size(), problems.size());
  EXPECT_EQ(located[0].rfind("INPT.inp line 15 (dens): materials[0].density: ", 0), 0u) << located[0];
}

TEST(InptImport, WindowsLineEndsAndTrailingBlankLinesAreRead) {
  std::string text = read("pdem_egd_figure_4_14.inp");
  std::string crlf;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  EXPECT_EQ(error_of(crlf + "\r\n\r\n"), "");
}

TEST(InptImport, ALooseKeyBlockIsPlacedLooserAndGrownToItsConcentration) {
  std::string text = with_line(read("pdem_egd_figure_4_14.inp"), 2, "LOS (pattern)");
  import::ImportOptions options;
  options.meshes = {"terrain.dat", "funnel.dat"};
  const import::Imported imported = import::import_inpt(text, options);
  EXPECT_DOUBLE_EQ(imported.spec["packings"][0]["solidFraction"].get<double>(), 0.25);
  EXPECT_NEAR(imported.spec["stages"][1]["growthFactor"].get<double>(), std::cbrt(0.4 / 0.25), 1e-12);
  const Scene scene = spec::to_scene(spec::parse_json(imported.spec.dump()), kData.string());
  EXPECT_GT(scene.particles.size(), 10u);
}

}  // namespace
}  // namespace dem::test
