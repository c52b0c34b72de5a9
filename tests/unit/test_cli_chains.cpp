// dem chains: a run's force chains at chosen instants as a figure, each contact a line whose width
// follows its normal force, and every missing file or bad argument named.
#include <gtest/gtest.h>

#include <regex>

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
  fs::path run_stack() {
    const fs::path run = dir_ / "run";
    const CommandResult r = run_dem("run " + shell_quoted(write_spec("stack.json", kStack)) + " --out " +
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
    std::regex_search(svg, m, std::regex("normal force ([0-9.e+-]+) N"));
    return m;
  }();
  ASSERT_FALSE(force.empty());
  EXPECT_NEAR(std::stod(force[1]), 2 * weight, 1e-3 * weight);
  std::size_t discs = 0;
  for (std::size_t at = svg.find("<circle"); at != std::string::npos; at = svg.find("<circle", at + 1)) ++discs;
  EXPECT_EQ(discs, 6u) << "three spheres in each of the two panels";
  EXPECT_NE(svg.find("<polygon"), std::string::npos) << "the floor plate's outline";
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
