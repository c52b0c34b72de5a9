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

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  return text.replace(text.find(from), from.size(), to);
}

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

// An independent tester's findings: twins of series another run wrote stayed in a reused folder
// (with outputs.csv false, or of a scene without bonds or walls); a continued run with another
// length unit wrote metres under a header in mm; one begun without twins gave them only the rows
// from the restart on, and one continued without them left a twin of part of the rows.
TEST_F(CsvOutput, AReusedFolderKeepsNoTwinOfAnotherRunAndAContinuedRunKeepsItsUnits) {
  const std::string plain = R"({"name": "one sphere falling", "materials": [{"name": "rock", "density": 2500,
    "youngsModulus": 1e7, "poissonRatio": 0.25}], "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5,
    "friction": 0.5}], "contact": {"normal": "HERTZ"}, "particles": [{"position": {"z": 1}, "radius": 0.01,
    "material": "rock"}], "gravity": {"z": -9.81}, "time": {"steps": 100}, "outputs": {"everySteps": 50}})";
  for (const std::string& second :
       {plain, replaced(plain, R"("everySteps": 50)", R"("everySteps": 50, "csv": false)")}) {
    const fs::path out = run(kSpec, "reused");  // every series, with bonds and walls
    ASSERT_TRUE(fs::exists(out / "Wall_PDF_ForceChain.csv"));
    run(second, "reused");
    for (const fs::directory_entry& e : fs::directory_iterator(out)) {
      if (e.path().extension() != ".csv") continue;
      EXPECT_TRUE(second.find("\"csv\": false") == std::string::npos) << e.path().filename() << " stayed";
      EXPECT_TRUE(fs::exists(fs::path(e.path()).replace_extension(".dat"))) << e.path().filename();
      for (const char* other : {"Fragments.csv", "Bond_Breaks.csv", "Wall_Mean_Force_CN.csv", "Force_Displacement.csv"})
        EXPECT_NE(e.path().filename(), other) << "another run's twin stayed";
    }
  }

  std::string half = kSpec;
  half.replace(half.find(R"("steps": 6000)"), 13, R"("steps": 3000)");
  // another length unit: refused, naming the columns
  const fs::path units = run(half, "units");
  std::string in_metres = kSpec;
  in_metres.replace(in_metres.find(R"("lengthUnit": "mm")"), 18, R"("lengthUnit": "m")");
  const CommandResult refused =
      run_dem("run " + shell_quoted(write_spec("m.json", in_metres)) + " --out " + shell_quoted(units) +
              " --quiet --restart " + shell_quoted(units / "restart.dat"));
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_NE(refused.output.find("its columns are \"time (s),displacement (mm),force (N)\", this run's"),
            std::string::npos)
      << refused.output;

  // begun without twins, continued with them: a twin of every row; the other way: no twin
  const fs::path whole = run(kSpec, "whole");
  std::string half_off = half;
  half_off.replace(half_off.find(R"("outputs": {)"), 12, R"("outputs": {"csv": false, )");
  const fs::path late = run(half_off, "late");
  run(kSpec, "late", " --restart " + shell_quoted(late / "restart.dat"));
  for (const char* name : {"Energy", "Masscenter", "Fragments"}) {
    const std::vector<std::string> csv = lines_of(late / (std::string(name) + ".csv"));
    const std::vector<std::string> full = lines_of(whole / (std::string(name) + ".csv"));
    ASSERT_EQ(csv.size(), full.size()) << name;
    EXPECT_EQ(csv.front(), full.front()) << name;
    for (std::size_t k = 1; k < csv.size(); ++k) EXPECT_EQ(numbers_of(csv[k], ','), numbers_of(full[k], ',')) << name;
  }
  const fs::path dropped = run(half, "dropped");
  std::string full_off = kSpec;
  full_off.replace(full_off.find(R"("outputs": {)"), 12, R"("outputs": {"csv": false, )");
  run(full_off, "dropped", " --restart " + shell_quoted(dropped / "restart.dat"));
  EXPECT_FALSE(fs::exists(dropped / "Energy.csv")) << "a twin of part of the rows";
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
