// The CSV twins of the time-series files: a header row of names with units, then the .dat's rows
// with every number in full; appended to by a continued run without a second header; none when the
// spec turns them off.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "support/command.hpp"

namespace dem::test {
namespace {

namespace fs = std::filesystem;

// A bonded cube of 27 spheres dropped onto a floor under a plate pressing down with a load: bonds
// that break, wall contacts, a loaded wall (Force_Displacement.dat).
const std::string kSpec = R"({
  "name": "bonded block under a loaded plate",
  "materials": [{"name": "rock", "density": 2500, "youngsModulus": 1e7, "poissonRatio": 0.25},
                {"name": "steel", "rigid": true, "density": 7800}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5, "friction": 0.5},
                   {"a": "rock", "b": "steel", "restitution": 0.5, "friction": 0.5}],
  "contact": {"normal": "HERTZ"},
  "lattices": [{"kind": "CUBIC", "min": {"x": 0, "y": 0, "z": 0.01}, "max": {"x": 0.06, "y": 0.06, "z": 0.07},
                "radius": 0.01, "spacing": 1.0, "material": "rock"}],
  "bonds": {"youngsModulus": 1e7, "tensileStrength": 2e3, "shearStrength": 2e3, "gapTolerance": 0.01},
  "walls": [{"name": "floor", "material": "steel", "plane": {"point": {"z": 0}, "normal": {"z": 1}}},
            {"name": "press", "material": "steel", "plate": {"c1": {"x": -0.1, "y": -0.1, "z": 0.08},
             "c2": {"x": 0.1, "y": -0.1, "z": 0.08}, "c3": {"x": 0.1, "y": 0.1, "z": 0.08}, "c4": {"x": -0.1, "y": 0.1, "z": 0.08}},
             "load": {"direction": {"z": -1}, "mass": 0.5, "cyclic": {"fMin": 2, "fMax": 30, "frequency": 20, "cycles": 2}}}],
  "gravity": {"z": -9.81},
  "time": {"steps": 6000},
  "outputs": {"everySteps": 1000, "lengthUnit": "mm", "numberFormat": "FULL"}
})";

std::vector<std::string> lines_of(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<double> numbers_of(const std::string& line, char separator) {
  std::vector<double> v;
  std::stringstream s(line);
  for (std::string item; std::getline(s, item, separator);)
    if (!item.empty()) v.push_back(std::stod(item));
  return v;
}

class CsvOutput : public DemCommandTest {
 protected:
  fs::path run(const std::string& spec, const std::string& name, const std::string& extra = "") {
    const fs::path out = dir_ / name;
    const CommandResult r = run_dem("run " + shell_quoted(write_spec(name + ".json", spec)) + " --out " +
                                    shell_quoted(out) + " --quiet" + extra);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return out;
  }
};

TEST_F(CsvOutput, EachTimeSeriesHasATwinWithNamedColumnsAndTheSameNumbers) {
  const fs::path out = run(kSpec, "block");
  const std::map<std::string, std::string> first_columns = {
      {"Energy", "time (s),kinetic translation (J),kinetic rotation (J)"},
      {"Masscenter", "time (s),x (mm),y (mm),z (mm)"},
      {"Disp_Max", "time (s),largest displacement (mm)"},
      {"Coord_OL", "time (s),coordination number (-)"},
      {"Fragments", "time (s),fragments,particles in the largest,intact bonds"},
      {"Fragment_Sizes", "time (s),fragment size (particles)"},
      {"Bond_Breaks", "time of the break (s),particle i,particle j"},
      {"Wall_Mean_Force_CN", "time (s),mean wall contact force (N)"},
      {"Wall_PDF_CoordN", "time (s),coordination number"},
      {"Wall_PDF_ForceChain", "time (s),force bin centre (N)"},
      {"Force_Displacement", "time (s),displacement (mm),force (N)"}};
  for (const auto& [name, header] : first_columns) {
    const std::vector<std::string> csv = lines_of(out / (name + ".csv"));
    const std::vector<std::string> dat = lines_of(out / (name + ".dat"));
    ASSERT_FALSE(csv.empty()) << name;
    EXPECT_EQ(csv[0].rfind(header, 0), 0u) << name << ": " << csv[0];
    const auto columns = static_cast<std::size_t>(std::count(csv[0].begin(), csv[0].end(), ',') + 1);
    ASSERT_EQ(csv.size(), dat.size() + 1) << name << ": a row for each of the .dat's";
    for (std::size_t k = 0; k < dat.size(); ++k) {
      const std::vector<double> from_csv = numbers_of(csv[k + 1], ',');
      EXPECT_EQ(from_csv.size(), columns) << name << " row " << k;
      EXPECT_EQ(from_csv, numbers_of(dat[k], ' ')) << name << " row " << k;  // FULL: the same doubles
    }
  }
  EXPECT_GT(lines_of(out / "Bond_Breaks.csv").size(), 1u) << "the load breaks no bond: the test checks less";
  EXPECT_EQ(lines_of(out / "Force_Displacement.csv").size(), 8u);  // the header, steps 0, 1000, ..., 6000
}

TEST_F(CsvOutput, AContinuedRunAppendsWithoutASecondHeader) {
  const fs::path whole = run(kSpec, "whole");
  std::string half = kSpec;
  half.replace(half.find(R"("steps": 6000)"), 13, R"("steps": 3000)");
  const fs::path out = run(half, "continued");
  run(kSpec, "continued", " --restart " + shell_quoted(out / "restart.dat"));
  for (const char* name : {"Energy.csv", "Masscenter.csv", "Fragments.csv", "Wall_PDF_ForceChain.csv",
                           "Force_Displacement.csv", "Bond_Breaks.csv"})
    EXPECT_EQ(read(out / name), read(whole / name)) << name;
}

TEST_F(CsvOutput, NoneWhenTheSpecTurnsThemOffAndNoneOfAnEarlierRunStays) {
  std::string off = kSpec;
  off.replace(off.find(R"("outputs": {)"), 12, R"("outputs": {"csv": false, )");
  run(kSpec, "off");
  const fs::path out = run(off, "off");
  ASSERT_TRUE(fs::exists(out / "Energy.dat"));
  for (const fs::directory_entry& e : fs::directory_iterator(out))
    EXPECT_NE(e.path().extension(), ".csv") << e.path().filename();
}

}  // namespace
}  // namespace dem::test
