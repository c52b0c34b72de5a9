// The BallastDEM manual's wall statistics (Wall_Mean_Force_CN.dat, Wall_PDF_CoordN.dat,
// Wall_PDF_ForceChain.dat; columns defined in docs/formats.md section 5): written by the run's
// writers and read back with read_rows, their numbers checked against the contacts the engine
// reports in the same state.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <cmath>
#include <map>

#include "legacy/legacy_formats.hpp"
#include "output/run_writers.hpp"
#include "output/wall_statistics_output.hpp"
#include "spec/spec_loader.hpp"
#include "support/command.hpp"
#include "support/scenes.hpp"

namespace dem::test {
namespace {

namespace fs = std::filesystem;

// A private folder per test (DemCommandTest's), removed afterwards.
class WallStatistics : public DemCommandTest {
 protected:
  // Every writer of a run, one frame now (as a run's first frame), closed; returns the rows of `name`.
  std::vector<std::vector<double>> written(const Simulation& sim, const char* name, std::size_t columns) {
    {
      auto writers = make_run_writers(sim, dir_.string(), false);
      for (auto& w : writers) w->frame(sim);
    }
    std::ifstream in(dir_ / name);
    EXPECT_TRUE(in.good()) << name << " was not written";
    const auto read = legacy::read_rows(in, columns);
    EXPECT_TRUE(read.problem.empty()) << name << ": " << read.problem;
    return read.frames;
  }
};

// Three spheres in a row on a floor, the middle one pressed into both neighbours and all three
// into the floor; a second, far wall touches nothing.
Simulation three_on_a_floor() {
  Scene s = base_scene(LinearNormal::kName, 2500, 0, 0, 0.5, 0.3, 1e5);
  const double r = 0.01;
  s.particles.push_back(sphere({0, 0, r * 0.99}, r));
  s.particles.push_back(sphere({2 * r * 0.98, 0, r * 0.98}, r));
  s.particles.push_back(sphere({4 * r * 0.98, 0, r * 0.995}, r));
  s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}, "floor"));
  s.walls.push_back(plane({0, 0, 1}, {0, 0, -1}, "roof"));
  return Simulation(s);
}

TEST_F(WallStatistics, MeanWallForceAndContactsAreThoseOfTheWallContacts) {
  const Simulation sim = three_on_a_floor();
  const std::vector<WallContact> walls = sim.wall_contacts();
  ASSERT_EQ(walls.size(), 3u);
  double sum = 0;
  for (const WallContact& c : walls) sum += c.fn;
  const auto rows = written(sim, "Wall_Mean_Force_CN.dat", 4);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0][0], 0.0);
  EXPECT_NEAR(rows[0][1], sum / 3, 1e-7 * sum);  // 8 digits in the file
  EXPECT_EQ(rows[0][2], 1.5);                    // 3 contacts over 2 walls
  EXPECT_EQ(rows[0][3], 3.0);
}

TEST_F(WallStatistics, CoordinationSharesCountEveryGrainOnce) {
  const Simulation sim = three_on_a_floor();
  const auto rows = written(sim, "Wall_PDF_CoordN.dat", 3);
  // the end spheres: the floor and the middle one (2); the middle one: the floor and both (3)
  ASSERT_EQ(rows.size(), 4u);
  const double want[] = {0, 0, 2.0 / 3, 1.0 / 3};
  for (std::size_t z = 0; z < 4; ++z) {
    EXPECT_EQ(rows[z][1], static_cast<double>(z));
    EXPECT_NEAR(rows[z][2], want[z], 1e-7) << "Z = " << z;
  }
}

TEST_F(WallStatistics, ForceDensityIntegratesToOneInBinsAboutATenthOfTheMean) {
  const Simulation sim = three_on_a_floor();
  std::vector<double> forces;
  for (const PairContact& c : sim.pair_contacts()) forces.push_back(c.fn);
  for (const WallContact& c : sim.wall_contacts()) forces.push_back(c.fn);
  ASSERT_EQ(forces.size(), 5u);
  double mean = 0, largest = 0;
  for (double f : forces) {
    mean += f / 5;
    largest = std::max(largest, f);
  }
  const auto rows = written(sim, "Wall_PDF_ForceChain.dat", 3);
  const auto bins = static_cast<std::size_t>(std::ceil(10 * largest / mean));
  ASSERT_EQ(rows.size(), bins);
  const double width = largest / static_cast<double>(bins);
  EXPECT_LE(width, mean / 10 * 1.1);
  double integral = 0, first_moment = 0;
  for (std::size_t b = 0; b < rows.size(); ++b) {
    EXPECT_NEAR(rows[b][1], (static_cast<double>(b) + 0.5) * width, 1e-6 * rows[b][1]);  // 7 digits in the file
    integral += rows[b][2] * width;
    first_moment += rows[b][1] * rows[b][2] * width;
  }
  EXPECT_NEAR(integral, 1.0, 1e-5);
  EXPECT_NEAR(first_moment, mean, width / 2);  // each force at its bin's centre
  EXPECT_GT(rows.back()[2], 0.0);              // the largest force is in the last bin
}

// Forces 1, 1, 2 N: mean 4/3, 2 N is 15 tenths of it: 15 bins 2/15 wide; 1 N falls in bin 7, 2 N
// closes bin 14.
TEST(WallStatisticsDensity, ClosedForm) {
  const auto rows = WallStatisticsWriter::force_density({1, 1, 2});
  const double width = 2.0 / 15;
  ASSERT_EQ(rows.size(), 15u);
  for (std::size_t b = 0; b < rows.size(); ++b) {
    const double want = b == 7 ? 2 / (3 * width) : b == 14 ? 1 / (3 * width) : 0.0;
    EXPECT_NEAR(rows[b].second, want, 1e-12 * want + 1e-300) << "bin " << b;
  }
}

// Equal forces (the tester's 1, 3 and 7 equal contacts): ten bins of [0, F], all of the density in
// the last, whatever the round-off of the mean.
TEST(WallStatisticsDensity, EqualForcesFillTheLastOfTenBins) {
  for (int n : {1, 3, 7})
    for (double f : {1.0, 1.4, 0.1, 3e-7}) {
      const auto rows = WallStatisticsWriter::force_density(std::vector<double>(static_cast<std::size_t>(n), f));
      ASSERT_EQ(rows.size(), 10u) << n << " x " << f;
      EXPECT_NEAR(rows.back().first, 0.95 * f, 1e-12 * f);
      EXPECT_NEAR(rows.back().second * f / 10, 1.0, 1e-12);
    }
}

// No pressed contact: no rows. One force of 1e15 N among a thousand of 1 N would ask for 1e13 bins
// about a tenth of the mean wide: at most 1,000, wider, and still a density.
TEST(WallStatisticsDensity, EmptyAndExtremeForces) {
  EXPECT_TRUE(WallStatisticsWriter::force_density({}).empty());
  EXPECT_TRUE(WallStatisticsWriter::force_density({0, 0, -3}).empty());
  std::vector<double> forces(1000, 1.0);
  forces.push_back(1e15);
  const auto rows = WallStatisticsWriter::force_density(forces);
  ASSERT_EQ(rows.size(), 1000u);
  const double width = rows[1].first - rows[0].first;
  double integral = 0;
  for (const auto& [centre, density] : rows) integral += density * width;
  EXPECT_NEAR(integral, 1.0, 1e-9);
  EXPECT_NEAR(rows[0].second * width, 1000.0 / 1001, 1e-12);
  EXPECT_NEAR(rows.back().second * width, 1.0 / 1001, 1e-12);
}

// With the legacy fixed widths (four decimals) a density in 1/N of forces of kilonewtons printed as
// 0.0000 or 0.0001 and integrated to 0.8 (an independent tester's finding): these files, which the
// manuals never print, keep seven digits.
TEST_F(WallStatistics, TheForceDensityKeepsItsDigitsWithTheLegacyNumberFormat) {
  Scene s = base_scene(LinearNormal::kName, 2500, 0, 0, 0.5, 0.3, 1e9);
  s.outputs.number_format = FileNumberFormat::LegacyFixed;
  for (int k = 0; k < 5; ++k) s.particles.push_back(sphere({0.1 * k, 0, 0.01 * (1 - 1e-3 * (k + 1))}, 0.01));
  s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}, "floor"));
  const Simulation sim(s);
  const auto rows = written(sim, "Wall_PDF_ForceChain.dat", 3);
  ASSERT_GE(rows.size(), 2u);
  const double width = rows[1][1] - rows[0][1];
  double integral = 0;
  for (const auto& row : rows) integral += row[2] * width;
  EXPECT_GT(rows.back()[1], 1e3);  // kilonewtons
  EXPECT_NEAR(integral, 1.0, 1e-5);
}

// A clump is one grain: a two-sphere stone lying on the floor on both members has 2 contacts.
TEST_F(WallStatistics, AClumpIsOneGrainWithItsMembersContacts) {
  const Scene scene = spec::to_scene(spec::parse_json(R"({"name": "stone",
  "materials": [{"name": "rock", "density": 2650, "normalStiffness": 2e5}, {"name": "steel", "rigid": true}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5, "friction": 0.5},
                   {"a": "rock", "b": "steel", "restitution": 0.5, "friction": 0.5}],
  "contact": {"normal": "LINEAR"},
  "clumpShapes": [{"name": "pair", "spheres": [{"center": {"x": -0.006}, "radius": 0.01},
                                               {"center": {"x": 0.006}, "radius": 0.01}]}],
  "clumps": [{"shape": "pair", "material": "rock", "position": {"z": 0.0099}}],
  "particles": [{"position": {"x": 0.5, "z": 0.5}, "radius": 0.01, "material": "rock"}],
  "walls": [{"material": "steel", "plane": {"point": {}, "normal": {"z": 1}}}],
  "time": {"steps": 1}})"));
  const Simulation sim(scene);
  ASSERT_EQ(sim.wall_contacts().size(), 2u);
  const auto rows = written(sim, "Wall_PDF_CoordN.dat", 3);
  ASSERT_EQ(rows.size(), 3u);  // Z = 0 (the free sphere), 1 (none), 2 (the stone)
  EXPECT_NEAR(rows[0][2], 0.5, 1e-12);
  EXPECT_NEAR(rows[1][2], 0.0, 1e-12);
  EXPECT_NEAR(rows[2][2], 0.5, 1e-12);
}

// A scene without walls writes none of the three.
TEST_F(WallStatistics, NotWrittenWithoutWalls) {
  Scene s = base_scene(LinearNormal::kName, 2500, 0, 0, 0.5, 0.3, 1e5);
  s.particles.push_back(sphere({0, 0, 0}, 0.01));
  const Simulation sim(s);
  {
    auto writers = make_run_writers(sim, dir_.string(), false);
    for (auto& w : writers) w->frame(sim);
  }
  EXPECT_TRUE(fs::exists(dir_ / "Coord_OL.dat"));
  for (const char* name : {"Wall_Mean_Force_CN.dat", "Wall_PDF_CoordN.dat", "Wall_PDF_ForceChain.dat"})
    EXPECT_FALSE(fs::exists(dir_ / name)) << name;
}

}  // namespace
}  // namespace dem::test
