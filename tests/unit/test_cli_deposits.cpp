// dem deposits: several runs' particles side by side at one scale, coloured by the piece they belong
// to, over a terrain's contours; the contours are where the levels cut the mesh, and every missing
// file or bad argument is named.
#include <gtest/gtest.h>

#include <regex>

#include "study/deposit_figure.hpp"
#include "support/command.hpp"

namespace dem::test::test_cli_deposits {
namespace {

namespace fs = std::filesystem;

// Four touching spheres in a row along x on a floor; with `bonds` three of them are glued into one
// piece (the fourth is outside the bonds' region): two pieces, one of three spheres.
std::string row_spec(bool bonds) {
  return std::string(R"({
  "materials": [{"name": "rock", "density": 2500, "normalStiffness": 100000},
                {"name": "ground", "rigid": true}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5, "friction": 0.3},
                   {"a": "rock", "b": "ground", "restitution": 0.5, "friction": 0.3}],
  "particles": [{"position": {"x": 0.0, "z": 0.1}, "radius": 0.1, "material": "rock"},
                {"position": {"x": 0.2, "z": 0.1}, "radius": 0.1, "material": "rock"},
                {"position": {"x": 0.4, "z": 0.1}, "radius": 0.1, "material": "rock"},
                {"position": {"x": 0.6, "z": 0.1}, "radius": 0.1, "material": "rock"}],
  "walls": [{"name": "ground", "material": "ground", "plane": {"normal": {"z": 1}}}],
  "gravity": {"z": -9.81},
  )") +
         (bonds ? R"("bonds": {"youngsModulus": 1e7, "tensileStrength": 1e9, "shearStrength": 1e9,
            "region": {"min": {"x": -1, "y": -1, "z": -1}, "max": {"x": 0.5, "y": 1, "z": 1}}},
  )"
                : "") +
         R"("time": {"duration": 0.2},
  "outputs": {"interval": 0.1}
})";
}

// A tilted square 2 x 2 m, z = x, as a legacy mesh: its contours are the lines x = level.
const char* kRamp = "4 2\n0 0 0\n2 0 2\n2 2 2\n0 2 0\n1 2 3\n1 3 4\n";

class CliDeposits : public DemCommandTest {
 protected:
  fs::path run_row(const std::string& name, bool bonds) {
    const fs::path run = dir_ / name;
    const CommandResult r = run_dem("run " + shell_quoted(write_spec(name + ".json", row_spec(bonds))) + " --out " +
                                    shell_quoted(run) + " --quiet --threads 1");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return run;
  }

  // The fill colours of the discs in the panel whose title is `title`.
  static std::vector<std::string> disc_colours(const std::string& svg, const std::string& title) {
    const std::size_t at = svg.find(">" + title + "</text>");
    EXPECT_NE(at, std::string::npos) << title;
    const std::size_t end = svg.find("</g>", at);
    std::vector<std::string> colours;
    const std::regex fill("<circle [^>]*fill=\"(#[0-9a-f]{6})\"");
    const std::string panel = svg.substr(at, end - at);
    for (auto it = std::sregex_iterator(panel.begin(), panel.end(), fill); it != std::sregex_iterator(); ++it)
      colours.push_back((*it)[1]);
    return colours;
  }
};

TEST_F(CliDeposits, APanelARunItsPiecesColouredLargestFirst) {
  const fs::path bonded = run_row("bonded", true), loose = run_row("loose", false);
  const fs::path out = dir_ / "deposits.svg";
  const CommandResult r = run_dem("deposits " + shell_quoted("C = 1 GPa=" + bonded.string()) + " " +
                                  shell_quoted(loose) + " --unit m --title rows --out " + shell_quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string svg = read(out);
  EXPECT_NE(svg.find("t = 0.200 s, 2 pieces"), std::string::npos) << "the bonded run: three glued, one alone";
  EXPECT_NE(svg.find("t = 0.200 s, 4 pieces"), std::string::npos) << "the loose run";
  std::vector<std::string> glued = disc_colours(svg, "C = 1 GPa");
  ASSERT_EQ(glued.size(), 4u);
  EXPECT_EQ(std::count(glued.begin(), glued.end(), "#1f77b4"), 3) << "the largest piece: the first colour";
  EXPECT_EQ(std::count(glued.begin(), glued.end(), "#8a8a8a"), 1) << "a sphere alone: grey";
  std::vector<std::string> apart = disc_colours(svg, "loose");
  EXPECT_EQ(std::count(apart.begin(), apart.end(), "#8a8a8a"), 4) << "four loose spheres";
  // one scale: the two rows' discs have one radius in pixels
  const std::regex radius("<circle [^>]*r=\"([0-9.]+)\" fill=\"#(1f77b4|8a8a8a)\"");
  std::set<std::string> radii;
  const std::string drawings = svg.substr(0, svg.find("pieces, largest first"));  // not the legend's dots
  for (auto it = std::sregex_iterator(drawings.begin(), drawings.end(), radius); it != std::sregex_iterator(); ++it)
    radii.insert((*it)[1]);
  EXPECT_EQ(radii.size(), 1u);
}

TEST_F(CliDeposits, TheTerrainsContoursUnderEveryPanelAndTheWholeTerrainShown) {
  const fs::path run = run_row("loose", false);
  const fs::path terrain = dir_ / "ramp.dat";
  std::ofstream(terrain) << kRamp;
  const fs::path out = dir_ / "deposits.svg";
  const CommandResult r = run_dem("deposits " + shell_quoted(run) + " " + shell_quoted(run) + " --terrain " +
                                  shell_quoted(terrain) + " --contour 0.5 --unit m --out " + shell_quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string svg = read(out);
  EXPECT_NE(svg.find("contours every 0.5 m"), std::string::npos);
  std::size_t uses = 0;
  for (std::size_t at = svg.find("<use "); at != std::string::npos; at = svg.find("<use ", at + 1)) ++uses;
  EXPECT_EQ(uses, 2u) << "the contours under each of the two panels";
  // the ramp's 2 m wide square sets the drawing's width (240 px at most): the spheres span 0.8 m
  const std::regex clip("<clipPath id=\"drawing\"><rect width=\"([0-9.]+)\" height=\"([0-9.]+)\"");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, clip));
  EXPECT_NEAR(std::stod(m[1]), 240, 0.5);
  EXPECT_NEAR(std::stod(m[2]), 240, 0.5) << "2 x 2 m at one scale";
}

// Marching triangles: the level z = L cuts the ramp z = x along x = L; a level through a corner only
// is no line; every fifth level is major.
TEST(DepositFigure, ContoursAreWhereTheLevelsCutTheTriangles) {
  const std::vector<study::MeshTriangle> ramp{{{{{0, 0, 0}, {10, 0, 10}, {0, 10, 0}}}}};
  const auto lines = study::contour_segments(ramp, 0, 1, 2, 2.0);
  ASSERT_EQ(lines.size(), 4u) << "levels 2, 4, 6 and 8 (0 and 10 touch corners only)";
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const double level = 2.0 * static_cast<double>(k + 1);
    for (const study::Point2& p : {lines[k].a, lines[k].b}) EXPECT_NEAR(p.x, level, 1e-12);
    EXPECT_NEAR(std::abs(lines[k].a.y - lines[k].b.y), 10 - level, 1e-12);
    EXPECT_FALSE(lines[k].major);
  }
  const auto every_one = study::contour_segments(ramp, 0, 1, 2, 1.0);
  ASSERT_EQ(every_one.size(), 9u);
  EXPECT_TRUE(every_one[4].major) << "level 5";
  EXPECT_EQ(study::contour_interval(1100), 100);
  EXPECT_EQ(study::contour_interval(50), 5);
  EXPECT_EQ(study::contour_interval(0), 1) << "a flat terrain";
}

// An independent tester: frames at 0.05, 0.15 and 0.25 s were labelled 0.1, 0.2 and 0.3 s; a time
// past the run drew the last frame without a word.
TEST_F(CliDeposits, ThePanelSaysWhichFrameItDrawsAndAFarTimeIsTold) {
  std::string spec = row_spec(false);
  spec.replace(spec.find("\"interval\": 0.1"), 15, "\"interval\": 0.05");
  const fs::path run = dir_ / "run";
  ASSERT_EQ(run_dem("run " + shell_quoted(write_spec("r.json", spec)) + " --out " + shell_quoted(run) +
                    " --quiet --threads 1")
                .exit_code,
            0);
  const fs::path out = dir_ / "deposits.svg";
  const CommandResult r = run_dem("deposits " + shell_quoted(run) + " --time 0.15 --out " + shell_quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(read(out).find("t = 0.150 s, 4 pieces"), std::string::npos);
  EXPECT_EQ(r.output.find("nearest frame"), std::string::npos) << r.output;
  const CommandResult late = run_dem("deposits " + shell_quoted(run) + " --time 100 --out " + shell_quoted(out));
  ASSERT_EQ(late.exit_code, 0) << late.output;
  EXPECT_NE(late.output.find("run: --time 100 s: the nearest frame is t = 0.200 s"), std::string::npos) << late.output;
}

// An independent tester: --contour 1e-9 on a 2 m ramp asked for two billion levels and ate the
// memory; a 2D run was told its ANIMATION_3D.dat was missing.
TEST_F(CliDeposits, TooManyContourLevelsAndA2DRunAreRefusedByName) {
  const fs::path run = run_row("loose", false);
  const fs::path terrain = dir_ / "ramp.dat";
  std::ofstream(terrain) << kRamp;
  const fs::path out = dir_ / "deposits.svg";
  const CommandResult fine = run_dem("deposits " + shell_quoted(run) + " --terrain " + shell_quoted(terrain) +
                                     " --contour 1e-9 --out " + shell_quoted(out));
  EXPECT_EQ(fine.exit_code, 2);
  EXPECT_NE(fine.output.find("--contour 1e-9 gives 2e+09 levels over the terrain's relief of 2: at most 1000"),
            std::string::npos)
      << fine.output;
  std::string flat = row_spec(false);
  flat.replace(flat.find("\"gravity\""), 0, "\"dimension\": 2, \"discThickness\": 0.2,\n  ");
  const fs::path planar = dir_ / "planar";
  const CommandResult made = run_dem("run " + shell_quoted(write_spec("planar.json", flat)) + " --out " +
                                     shell_quoted(planar) + " --quiet --threads 1");
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const CommandResult two_d = run_dem("deposits " + shell_quoted(planar) + " --out " + shell_quoted(out));
  EXPECT_EQ(two_d.exit_code, 1);
  EXPECT_NE(two_d.output.find("is a 2D run (ANIMATION_2D.dat): dem deposits draws 3D runs' deposits"),
            std::string::npos)
      << two_d.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(CliDeposits, EveryMissingFileAndBadArgumentIsNamed) {
  const fs::path out = dir_ / "deposits.svg";
  const CommandResult none = run_dem("deposits " + shell_quoted(dir_) + " --out " + shell_quoted(out));
  EXPECT_EQ(none.exit_code, 1);
  EXPECT_NE(none.output.find("ANIMATION_3D.dat: not there (a 3D run writes it)"), std::string::npos) << none.output;
  const fs::path run = run_row("loose", false);
  const CommandResult bad_mesh = run_dem("deposits " + shell_quoted(run) + " --terrain " +
                                         shell_quoted(dir_ / "nowhere.dat") + " --out " + shell_quoted(out));
  EXPECT_EQ(bad_mesh.exit_code, 1);
  EXPECT_NE(bad_mesh.output.find("nowhere.dat"), std::string::npos) << bad_mesh.output;
  std::string many;
  for (int k = 0; k < 21; ++k) (many += ' ') += shell_quoted(run);
  for (const auto& [args, problem] : std::vector<std::pair<std::string, std::string>>{
           {shell_quoted(run) + " --view w", "--view: x, y or z (got \"w\")"},
           {shell_quoted(run) + " --time soon", "--time: \"soon\" is not a number"},
           {shell_quoted(run) + " --contour 5", "--contour: needs --terrain MESH"},
           {shell_quoted(run) + " --terrain t.dat --contour -1", "--contour: must be above 0 (got -1)"},
           {shell_quoted(run) + " --colour red", "unknown option --colour"},
           {many, "at most 20 runs (got 21)"},
           {"", "missing the runs' folders"}}) {
    const CommandResult r = run_dem("deposits " + args + " --out " + shell_quoted(out));
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.output.find("dem deposits: " + problem), std::string::npos) << args << "\n" << r.output;
  }
  const CommandResult no_out = run_dem("deposits " + shell_quoted(run));
  EXPECT_EQ(no_out.exit_code, 2);
  EXPECT_NE(no_out.output.find("give --out FIGURE.svg"), std::string::npos) << no_out.output;
  EXPECT_FALSE(fs::exists(out)) << "no figure from a failed command";
}

}  // namespace
}  // namespace dem::test::test_cli_deposits
