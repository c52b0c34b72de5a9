// dem chains: a run's force chains at chosen instants as a figure, each contact a line whose width
// follows its normal force, and every missing file or bad argument named.
#include <gtest/gtest.h>

#include <regex>
#include <set>

#include "study/chain_figure.hpp"
#include "support/command.hpp"

namespace dem::test::test_cli_chains {
namespace {

namespace fs = std::filesystem;

// Three spheres stacked on a plate, settled under damping: the lower contact carries the weight
// of two spheres, the upper one the weight of one.
const char* kStack = R"({
  "materials": [{"name": "glass", "density": 2500, "normalStiffness": 10000},
                {"name": "steel", "rigid": true}],
  "interactions": [{"a": "glass", "b": "glass", "restitution": 0.5, "friction": 0.3},
                   {"a": "glass", "b": "steel", "restitution": 0.5, "friction": 0.3}],
  "particles": [{"position": {"z": 0.01}, "radius": 0.01, "material": "glass"},
                {"position": {"z": 0.03}, "radius": 0.01, "material": "glass"},
                {"position": {"z": 0.05}, "radius": 0.01, "material": "glass"}],
  "walls": [{"name": "floor", "material": "steel", "plate": {
    "c1": {"x": -0.05, "y": -0.05}, "c2": {"x": 0.05, "y": -0.05},
    "c3": {"x": 0.05, "y": 0.05}, "c4": {"x": -0.05, "y": 0.05}}}],
  "gravity": {"z": -9.81},
  "numerics": {"localDamping": 0.7},
  "time": {"duration": 0.5},
  "outputs": {"interval": 0.1, "forceChains": true, "numberFormat": "FULL"}
})";

class CliChains : public DemCommandTest {
 protected:
  fs::path run_stack(const std::string& spec = kStack) {
    const fs::path run = dir_ / "run";
    const CommandResult r = run_dem("run " + shell_quoted(write_spec("stack.json", spec)) + " --out " +
                                    shell_quoted(run) + " --quiet --threads 1");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return run;
  }

  // The stroke widths of the chains' lines, in the order drawn.
  static std::vector<double> chain_widths(const std::string& svg) {
    std::vector<double> widths;
    const std::regex line("<line x1=\"[^\"]*\" y1=\"[^\"]*\" x2=\"[^\"]*\" y2=\"[^\"]*\" stroke-width=\"([^\"]*)\"");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), line); it != std::sregex_iterator(); ++it)
      widths.push_back(std::stod((*it)[1]));
    return widths;
  }
};

TEST_F(CliChains, ALineAContactItsWidthFollowingTheForce) {
  const fs::path run = run_stack();
  const fs::path out = dir_ / "chains.svg";
  const CommandResult r =
      run_dem("chains " + shell_quoted(run) + " --times 0,0.5 --unit m --title stack --out " + shell_quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string svg = read(out);
  EXPECT_NE(svg.find(">t = 0.000 s (step 0)<"), std::string::npos);
  EXPECT_NE(svg.find(">t = 0.500 s"), std::string::npos);
  // at rest: the lower contact carries 2 m g, the upper m g (m = 2500 4/3 pi 0.01^3 kg)
  const double weight = 2500 * 4.0 / 3 * M_PI * 1e-6 * 9.81;
  const std::vector<double> widths = chain_widths(svg);
  ASSERT_EQ(widths.size(), 2u) << "touching without force at t = 0: no line; two contacts at the end";
  EXPECT_NEAR(widths[1], 6.0, 1e-3) << "the strongest contact, drawn last";
  EXPECT_NEAR(widths[0], 0.4 + 5.6 * 0.5, 0.01) << "half its force";
  const std::smatch force = [&] {
    std::smatch m;
    std::regex_search(svg, m, std::regex("6 px at Fn = ([0-9.e+-]+) N"));
    return m;
  }();
  ASSERT_FALSE(force.empty());
  EXPECT_NEAR(std::stod(force[1]), 2 * weight, 1e-3 * weight);
  std::size_t discs = 0;
  for (std::size_t at = svg.find("<circle"); at != std::string::npos; at = svg.find("<circle", at + 1)) ++discs;
  EXPECT_EQ(discs, 6u) << "three spheres in each of the two panels";
  EXPECT_NE(svg.find("<polygon"), std::string::npos) << "the floor plate's outline";
  // the legend says how width follows force (an independent tester read "in proportion" as width ∝ Fn)
  EXPECT_NE(svg.find("line width 0.4 px + 5.6 px × Fn / Fmax"), std::string::npos) << svg;
}

// The panels' titles and scale bars need room, however narrow the scene: a column of three spheres
// (20 mm wide, 60 mm tall) drawn 140 px wide had its titles run into each other.
TEST_F(CliChains, ANarrowSceneKeepsItsPanelsApart) {
  std::string spec = kStack;  // on an infinite floor, which the files do not draw: the column alone
  const std::size_t plate = spec.find("\"plate\"");
  spec.replace(plate, spec.find("}}}]", plate) + 3 - plate, R"("plane": {"point": {"z": 0}, "normal": {"z": 1}}})");
  const fs::path run = run_stack(spec);
  const fs::path out = dir_ / "chains.svg";
  const CommandResult r = run_dem("chains " + shell_quoted(run) + " --times 0,0.5 --out " + shell_quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::vector<double> title_x;
  const std::string svg = read(out);
  const std::regex title("<text x=\"([0-9.]+)\" y=\"[0-9.]+\" font-size=\"13\">t = ");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), title); it != std::sregex_iterator(); ++it)
    title_x.push_back(std::stod((*it)[1]));
  ASSERT_EQ(title_x.size(), 2u);
  EXPECT_GE(title_x[1] - title_x[0], 200) << "a title is about 170 px long";
}

// Lines no wider than the particles are drawn: 2,400 spheres 2 px across were buried under 6 px lines.
TEST(ChainFigure, LinesAreNoWiderThanTheParticlesAreDrawn) {
  study::ChainPanel panel;
  for (int k = 0; k < 300; ++k)  // a row 3 m long of spheres 1 cm across: 300 px for 3 m, 1 px each
    panel.discs.push_back({{0.01 * k, 0}, 0.005});
  for (int k = 0; k + 1 < 300; ++k) panel.chains.push_back({panel.discs[k].centre, panel.discs[k + 1].centre, 1.0 + k});
  const std::string svg = study::chain_figure_svg({"row", "x", "z", "m"}, {panel});
  double widest = 0;
  const std::regex width("stroke-width=\"([0-9.]+)\" stroke-opacity");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), width); it != std::sregex_iterator(); ++it)
    widest = std::max(widest, std::stod((*it)[1]));
  EXPECT_GT(widest, 0);
  EXPECT_LE(widest, 1.5) << "the spheres are 1 px across";
}

// A run's force-chain file may lack the frame nearest a time (a writer one frame behind, a cut
// file): the figure takes the nearest frame both files hold, and says when that is far from the time.
TEST_F(CliChains, TheNearestFrameBothFilesHoldAndAWordWhenItIsFar) {
  const fs::path run = run_stack();
  // drop the force-chain file's last frame (t = 0.5)
  const std::string chains = read(run / "ForceChain_3D.dat");
  std::ofstream(run / "ForceChain_3D.dat", std::ios::binary) << chains.substr(0, chains.rfind("3DF:"));
  const fs::path out = dir_ / "chains.svg";
  const CommandResult r = run_dem("chains " + shell_quoted(run) + " --times 0.5 --out " + shell_quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(read(out).find(">t = 0.400 s"), std::string::npos) << "the last frame both files hold";
  EXPECT_NE(r.output.find("t = 0.5 s: the nearest frame both files hold is t = 0.400 s"), std::string::npos)
      << r.output;
  const CommandResult late = run_dem("chains " + shell_quoted(run) + " --times 100 --out " + shell_quoted(out));
  ASSERT_EQ(late.exit_code, 0) << late.output;
  EXPECT_NE(late.output.find("t = 100 s: the nearest frame both files hold is t = 0.400 s"), std::string::npos)
      << late.output;
  const CommandResult near = run_dem("chains " + shell_quoted(run) + " --times 0.39 --out " + shell_quoted(out));
  ASSERT_EQ(near.exit_code, 0) << near.output;
  EXPECT_EQ(near.output.find("nearest frame"), std::string::npos) << "within a frame interval: no word";
}

// A 2D run's ANIMATION_2D.dat: its discs in the x-z plane.
TEST_F(CliChains, A2DRunsDiscs) {
  std::string spec = kStack;
  spec.replace(spec.find("\"gravity\""), 0, "\"dimension\": 2, \"discThickness\": 0.02,\n  ");
  const fs::path run = run_stack(spec);
  ASSERT_TRUE(fs::exists(run / "ANIMATION_2D.dat"));
  const fs::path out = dir_ / "chains.svg";
  const CommandResult r = run_dem("chains " + shell_quoted(run) + " --times 0.5 --out " + shell_quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(chain_widths(read(out)).size(), 2u);
  const CommandResult side =
      run_dem("chains " + shell_quoted(run) + " --times 0.5 --view z --out " + shell_quoted(out));
  EXPECT_EQ(side.exit_code, 2);
  EXPECT_NE(side.output.find("a 2D run is drawn in its x-z plane: --view y"), std::string::npos) << side.output;
}

TEST_F(CliChains, EveryMissingFileAndBadArgumentIsNamed) {
  const fs::path out = dir_ / "chains.svg";
  const CommandResult none = run_dem("chains " + shell_quoted(dir_) + " --times 0 --out " + shell_quoted(out));
  EXPECT_EQ(none.exit_code, 1);
  EXPECT_NE(none.output.find("ANIMATION_3D.dat: not there"), std::string::npos) << none.output;

  const fs::path run = run_stack();
  fs::remove(run / "ForceChain_3D.dat");
  const CommandResult no_chains = run_dem("chains " + shell_quoted(run) + " --times 0 --out " + shell_quoted(out));
  EXPECT_EQ(no_chains.exit_code, 1);
  EXPECT_NE(no_chains.output.find("ForceChain_3D.dat: not there (a run with outputs.forceChains writes it)"),
            std::string::npos)
      << no_chains.output;

  for (const auto& [args, problem] :
       std::vector<std::pair<std::string, std::string>>{{"--times 0,x", "--times: \"x\" is not a time in seconds"},
                                                        {"--times 0,,1", "--times: \"\" is not a time in seconds"},
                                                        {"--times 0.5,", "--times: \"\" is not a time in seconds"},
                                                        {"--times nan", "--times: \"nan\" is not a time in seconds"},
                                                        {"--times 0 --view w", "--view: x, y or z (got \"w\")"},
                                                        {"--times 0 --colour red", "unknown option --colour"},
                                                        {"--out x.svg", "give --times"}}) {
    const CommandResult r = run_dem("chains " + shell_quoted(run) + " " + args +
                                    (args.find("--out") == std::string::npos ? " --out " + shell_quoted(out) : ""));
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.output.find("dem chains: " + problem), std::string::npos) << args << "\n" << r.output;
  }
  EXPECT_FALSE(fs::exists(out)) << "no figure from a failed command";
}

}  // namespace
}  // namespace dem::test::test_cli_chains
