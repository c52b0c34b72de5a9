// The wall files of legacy-formats.md section 5: Wall_Animation_3D.dat, Wall_ForceChain_3D.dat and
// Force_Displacement.dat round-trip, read up to their last whole frame when cut, and name the
// line of a malformed one.
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <sstream>

#include "legacy/legacy_formats.hpp"

namespace dem::legacy {
namespace {

std::string written(const std::function<void(std::FILE*)>& write) {
  char* buffer = nullptr;
  std::size_t size = 0;
  std::FILE* out = open_memstream(&buffer, &size);
  write(out);
  std::fclose(out);
  std::string text(buffer, size);
  std::free(buffer);
  return text;
}

std::vector<WallFrame> wall_frames() {
  std::vector<WallFrame> frames(3);
  for (int f = 0; f < 3; ++f) {
    frames[f].step = 1000 * f;
    AnimationPlate plate;
    plate.id = 1;
    plate.corners = {Vec3(-350, -400, -150 + f), Vec3(350, -400, -150 + f), Vec3(350, 400, -150 + f),
                     Vec3(-350, 400, -150 + f)};
    frames[f].plates.push_back(plate);
    for (int t = 0; t < 2; ++t) {
      AnimationTriangle tri;
      tri.id = t + 1;
      tri.corners = {Vec3(0, 0, 0.5 * f), Vec3(1.25, 0, 0), Vec3(0, 1, 1e-3 * t)};
      frames[f].triangles.push_back(tri);
    }
  }
  return frames;
}

TEST(WallAnimationFile, RoundTrips) {
  const auto frames = wall_frames();
  const std::string text = written([&](std::FILE* out) {
    for (const auto& f : frames) write_wall_frame(out, f, NumberFormat::Scientific);
  });
  EXPECT_EQ(text.substr(0, 11), "3DW: 0 3\n1 ");
  std::istringstream in(text);
  const auto read = read_wall_frames(in);
  ASSERT_TRUE(read.problem.empty()) << read.problem;
  ASSERT_EQ(read.frames.size(), 3u);
  for (int f = 0; f < 3; ++f) {
    EXPECT_EQ(read.frames[f].step, frames[f].step);
    ASSERT_EQ(read.frames[f].plates.size(), 1u);
    ASSERT_EQ(read.frames[f].triangles.size(), 2u);
    EXPECT_TRUE(read.frames[f].plates[0].corners[2].isApprox(frames[f].plates[0].corners[2], 1e-6));
    EXPECT_TRUE(read.frames[f].triangles[1].corners[2].isApprox(frames[f].triangles[1].corners[2], 1e-6));
  }
}

TEST(WallAnimationFile, CutAtAnyByteReturnsTheCompleteFrames) {
  const auto frames = wall_frames();
  std::vector<std::size_t> ends;
  std::string text;
  for (const auto& f : frames) {
    text += written([&](std::FILE* out) { write_wall_frame(out, f, NumberFormat::Scientific); });
    ends.push_back(text.size());
  }
  for (std::size_t cut = 0; cut <= text.size(); ++cut) {
    std::istringstream in(text.substr(0, cut));
    const auto read = read_wall_frames(in);
    std::size_t whole = 0;
    while (whole < ends.size() && ends[whole] <= cut) ++whole;
    ASSERT_EQ(read.frames.size(), whole) << "cut at " << cut;
    const bool at_boundary = cut == 0 || (whole > 0 && ends[whole - 1] == cut);
    EXPECT_EQ(read.truncated, !at_boundary) << "cut at " << cut;
  }
}

TEST(WallAnimationFile, AWrongWordIsNamed) {
  std::istringstream in("3DW: 5 1\n1 plate 0 0 0 1 0 0 1 1 0 0 1 0\n");
  const auto read = read_wall_frames(in);
  EXPECT_TRUE(read.frames.empty());
  EXPECT_FALSE(read.truncated);
  EXPECT_EQ(read.problem.rfind("line 2: expected a wall line", 0), 0u) << read.problem;
}

TEST(WallForceChainFile, RoundTripsInBothFormats) {
  WallForceChainFrame frame;
  frame.step = 13500;
  frame.chains = {{2, 1, 45895.55, 22947.77}, {2, 6, 12.5, 0}, {7, 1, 0.25, 0.125}};
  for (NumberFormat format : {NumberFormat::Scientific, NumberFormat::LegacyFixed}) {
    const std::string text = written([&](std::FILE* out) { write_wall_force_chain_frame(out, frame, format); });
    if (format == NumberFormat::LegacyFixed) {
      EXPECT_EQ(text.substr(0, 35), "3DWF: 13500 3\n2 1 45895.55 22947.77");
    }
    std::istringstream in(text);
    const auto read = read_wall_force_chains(in);
    ASSERT_TRUE(read.problem.empty()) << read.problem;
    ASSERT_EQ(read.frames.size(), 1u);
    ASSERT_EQ(read.frames[0].chains.size(), 3u);
    EXPECT_EQ(read.frames[0].chains[1].wall, 6);
    EXPECT_NEAR(read.frames[0].chains[0].normal_force, 45895.55, 0.006);
  }
}

TEST(WallForceChainFile, ANonNumberIsNamed) {
  std::istringstream in("3DWF: 1 1\n2 1 abc 0\n");
  const auto read = read_wall_force_chains(in);
  EXPECT_EQ(read.problem, "line 2: column 3 ('abc') is not a number");
}

TEST(ForceDisplacementFile, RoundTripsAndStopsAtACutRow) {
  const std::string text = written([&](std::FILE* out) {
    write_force_displacement_row(out, {0.0, 0.0, 1500.0}, NumberFormat::Scientific);
    write_force_displacement_row(out, {0.1, 0.25, 51840.0}, NumberFormat::Scientific);
  });
  EXPECT_EQ(text.substr(0, 39), "0.000000e+00 0.000000e+00 1.500000e+03\n");
  std::istringstream in(text);
  const auto read = read_force_displacement(in);
  ASSERT_EQ(read.frames.size(), 2u);
  EXPECT_EQ(read.frames[1].force, 51840.0);
  EXPECT_EQ(read.frames[1].displacement, 0.25);
  std::istringstream cut(text.substr(0, text.size() - 5));
  const auto partial = read_force_displacement(cut);
  EXPECT_EQ(partial.frames.size(), 1u);
  EXPECT_TRUE(partial.truncated);
  std::istringstream bad("0 1\n");
  EXPECT_EQ(read_force_displacement(bad).problem, "line 1: expected 3 values (time displacement force), found 2");
}

TEST(StatisticsFiles, RowsRoundTripAndNameABadLine) {
  const std::string text = written([&](std::FILE* out) {
    write_row(out, {0.5, 1.25, -3e-7, 42}, NumberFormat::Scientific);
    write_row(out, {1.0, 2.5, 0, 43}, NumberFormat::Scientific);
  });
  std::istringstream in(text);
  const auto read = read_rows(in, 4);
  ASSERT_TRUE(read.problem.empty()) << read.problem;
  ASSERT_EQ(read.frames.size(), 2u);
  EXPECT_EQ(read.frames[0], (std::vector<double>{0.5, 1.25, -3e-7, 42}));
  std::istringstream bad("0 1 2\n");
  EXPECT_EQ(read_rows(bad, 4).problem, "line 1: expected 4 values, found 3");
  std::istringstream cut(text.substr(0, text.size() - 3));
  const auto partial = read_rows(cut, 4);
  EXPECT_EQ(partial.frames.size(), 1u);
  EXPECT_TRUE(partial.truncated);
}

}  // namespace
}  // namespace dem::legacy
