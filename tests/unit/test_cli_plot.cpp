// dem plot: a figure of a run's columns or of a JSON list's rows, each --y its panel, every bad
// argument named.
#include <gtest/gtest.h>

#include <regex>
#include <set>

#include "support/command.hpp"

namespace dem::test {
namespace {

namespace fs = std::filesystem;

class CliPlot : public DemCommandTest {
 protected:
  static std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
  }
};

TEST_F(CliPlot, ColumnsOfARunsFileOnePanelPerY) {
  const fs::path data =
      write_spec("Force_Displacement.dat", "# a header line is skipped\n0 0 0\n0.1 1.5 200\n0.2 3.0 410\n");
  const fs::path out = dir_ / "fd.svg";
  const CommandResult ok = run_dem("plot " + shell_quoted(data) +
                                   " --x '2:press travel (mm)' --y '3:force (N)' --y 1 --out " + shell_quoted(out));
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  const std::string svg = read(out);
  EXPECT_EQ(count(svg, "<polyline"), 2u);
  EXPECT_NE(svg.find(">force (N)<"), std::string::npos);
  EXPECT_NE(svg.find(">press travel (mm)<"), std::string::npos);
  EXPECT_NE(svg.find(">column 1<"), std::string::npos);
  // three rows: three points in each line
  const std::size_t at = svg.find("<polyline points=\"");
  const std::string points = svg.substr(at + 18, svg.find('"', at + 18) - at - 18);
  EXPECT_EQ(count(points, ","), 3u) << points;
}

TEST_F(CliPlot, RowsOfAJsonList) {
  const fs::path data = write_spec(
      "results.json",
      R"({"loadedWalls": [{"cycles": [{"cycle": 1, "settlement": 0.01}, {"cycle": 2, "settlement": 0.012}]}]})");
  const fs::path out = dir_ / "cycles.svg";
  const CommandResult r =
      run_dem("plot " + shell_quoted(data) + " --rows 'loadedWalls[0].cycles' --x cycle --y settlement --out " +
              shell_quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(count(read(out), "<circle"), 2u);
  // KEY:NAME labels an axis, as COLUMN:NAME does
  const CommandResult labelled = run_dem("plot " + shell_quoted(data) +
                                         " --rows 'loadedWalls[0].cycles' --x 'cycle:load cycle' --y "
                                         "'settlement:settlement (m)' --out " +
                                         shell_quoted(out));
  ASSERT_EQ(labelled.exit_code, 0) << labelled.output;
  EXPECT_NE(read(out).find("settlement (m)"), std::string::npos);
  EXPECT_NE(read(out).find("load cycle"), std::string::npos);
  const CommandResult missing = run_dem(
      "plot " + shell_quoted(data) + " --rows 'loadedWalls[0].cycles' --x cycle --y peak --out " + shell_quoted(out));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.output.find("has no number peak"), std::string::npos) << missing.output;
  const CommandResult not_list =
      run_dem("plot " + shell_quoted(data) + " --rows loadedWalls[1] --x cycle --y peak --out " + shell_quoted(out));
  EXPECT_EQ(not_list.exit_code, 1);
  EXPECT_NE(not_list.output.find("is not a list in it"), std::string::npos) << not_list.output;
  // one file named as an overlay's are, NAME=FILE: its line so named (it was "cannot open it")
  const CommandResult named =
      run_dem("plot " + shell_quoted("bed 1=" + data.string()) +
              " --rows 'loadedWalls[0].cycles' --x cycle --y settlement --out " + shell_quoted(out));
  ASSERT_EQ(named.exit_code, 0) << named.output;
  EXPECT_NE(read(out).find(">bed 1<"), std::string::npos);
}

TEST_F(CliPlot, SeveralRunsOverlaidALineEachNamedInTheLegend) {
  fs::create_directories(dir_ / "run-001");
  fs::create_directories(dir_ / "run-002");
  const fs::path a = write_spec("run-001/results.json", R"({"cycles": [{"cycle": 1, "s": 1}, {"cycle": 2, "s": 2}]})");
  const fs::path b = write_spec("run-002/results.json", R"({"cycles": [{"cycle": 1, "s": 3}, {"cycle": 2, "s": 5}]})");
  const fs::path out = dir_ / "overlay.svg";
  CommandResult r = run_dem("plot " + shell_quoted(a) + " " + shell_quoted(b) +
                            " --rows cycles --x cycle --y s --y cycle --out " + shell_quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::string svg = read(out);
  EXPECT_EQ(count(svg, "<polyline"), 4u) << "two panels, a line per file in each";
  EXPECT_EQ(count(svg, ">run-001<"), 1u) << "each line named by its run's folder, once in the figure's legend";
  EXPECT_EQ(count(svg, ">run-002<"), 1u);
  // NAME=FILE names a line; the second file's points are its own
  r = run_dem("plot 'clumped stones=" + a.string() + "' 'breakable stones=" + b.string() +
              "' --rows cycles --x cycle --y s --out " + shell_quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  svg = read(out);
  EXPECT_NE(svg.find(">clumped stones<"), std::string::npos);
  EXPECT_NE(svg.find(">breakable stones<"), std::string::npos);
  // two folders of one name: each line named by its path instead
  fs::create_directories(dir_ / "E" / "x");
  fs::create_directories(dir_ / "F" / "x");
  const fs::path e = write_spec("E/x/results.json", R"({"cycles": [{"cycle": 1, "s": 1}]})");
  const fs::path f = write_spec("F/x/results.json", R"({"cycles": [{"cycle": 1, "s": 2}]})");
  r = run_dem("plot " + shell_quoted(e) + " " + shell_quoted(f) + " --rows cycles --x cycle --y s --out " +
              shell_quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  svg = read(out);
  EXPECT_NE(svg.find(">" + e.string() + "<"), std::string::npos) << svg;
  EXPECT_NE(svg.find(">" + f.string() + "<"), std::string::npos);
  // one file: no legend
  r = run_dem("plot " + shell_quoted(a) + " --rows cycles --x cycle --y s --out " + shell_quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read(out).find(">run-001<"), std::string::npos);
  // a bad file among them is named; columns of text files take one file
  r = run_dem("plot " + shell_quoted(a) + " " + shell_quoted(dir_ / "none.json") +
              " --rows cycles --x cycle --y s --out " + shell_quoted(out));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("none.json: cannot open it"), std::string::npos) << r.output;
  r = run_dem("plot " + shell_quoted(a) + " " + shell_quoted(b) + " --x 1 --y 2 --out " + shell_quoted(out));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("one file only without --rows"), std::string::npos) << r.output;
}

// Twelve runs overlaid: twelve colours (the tester saw the seventh take the first's), and the legend
// under the panels, where it covers no line.
TEST_F(CliPlot, TwelveRunsTwelveColoursAndALegendClearOfTheLines) {
  std::vector<std::string> files;
  for (int k = 0; k < 12; ++k) {
    const std::string folder = "run-" + std::to_string(100 + k);
    fs::create_directories(dir_ / folder);
    files.push_back(
        shell_quoted(write_spec(folder + "/results.json", R"({"cycles": [{"cycle": 1, "s": )" + std::to_string(k) +
                                                              R"(}, {"cycle": 2, "s": 9}]})")));
  }
  std::string args;
  for (const std::string& f : files) args += f + " ";
  const fs::path out = dir_ / "twelve.svg";
  const CommandResult r = run_dem("plot " + args + "--rows cycles --x cycle --y s --out " + shell_quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string svg = read(out);
  std::set<std::string> looks;  // colour and dash of each line
  const std::regex line("<polyline points=\"[^\"]*\" fill=\"none\" stroke=\"([^\"]*)\"([^/]*)/>");
  double frame_bottom = 0;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), line); it != std::sregex_iterator(); ++it)
    looks.insert((*it)[1].str() + (*it)[2].str());
  EXPECT_EQ(looks.size(), 12u);
  std::smatch frame;
  ASSERT_TRUE(std::regex_search(
      svg, frame, std::regex("<rect x=\"[0-9]+\" y=\"([0-9]+)\" width=\"[0-9]+\" height=\"([0-9]+)\" fill=\"none\"")));
  frame_bottom = std::stod(frame[1]) + std::stod(frame[2]);
  const std::size_t entry = svg.find(">run-100<");
  ASSERT_NE(entry, std::string::npos);
  std::smatch y;
  const std::string before = svg.substr(svg.rfind("<text", entry), entry - svg.rfind("<text", entry));
  ASSERT_TRUE(std::regex_search(before, y, std::regex("y=\"([0-9.]+)\"")));
  EXPECT_GT(std::stod(y[1]), frame_bottom + 20) << "the legend is under the panel and its axis label";
}

TEST_F(CliPlot, BadArgumentsAreNamed) {
  const fs::path data = write_spec("a.dat", "1 2\n3 4\n");
  EXPECT_EQ(run_dem("plot").exit_code, 2);
  CommandResult r = run_dem("plot " + shell_quoted(data) + " --x 0 --y 2 --out x.svg");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("a column is 1, 2, ... (got \"0\")"), std::string::npos) << r.output;
  r = run_dem("plot " + shell_quoted(data) + " --x 1 --y 5 --out " + shell_quoted(dir_ / "x.svg"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("no line of at least 5 numbers"), std::string::npos) << r.output;
  r = run_dem("plot " + shell_quoted(data) + " --x 1 --y 2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--out"), std::string::npos) << r.output;
  // not files to read whole: /dev/zero (an endless line: 8 GB once), a folder
  r = run_dem("plot /dev/zero --x 1 --y 2 --out " + shell_quoted(dir_ / "x.svg"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("/dev/zero: not a regular file"), std::string::npos) << r.output;
  r = run_dem("plot " + shell_quoted(dir_) + " --x 1 --y 2 --out " + shell_quoted(dir_ / "x.svg"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("a folder, not a file"), std::string::npos) << r.output;
  // values so large that the axis' span overflows are left out, not drawn at nan
  const fs::path huge = write_spec("huge.dat", "0 1e308\n1 -1e308\n2 5\n3 6\n");
  r = run_dem("plot " + shell_quoted(huge) + " --x 1 --y 2 --out " + shell_quoted(dir_ / "huge.svg"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read(dir_ / "huge.svg").find("nan"), std::string::npos);
  r = run_dem("plot " + shell_quoted(dir_ / "none.dat") + " --x 1 --y 2 --out " + shell_quoted(dir_ / "x.svg"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("none.dat: cannot open it"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace dem::test
