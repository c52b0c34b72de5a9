// ANIMATION_2D.dat (docs/formats.md section 3a): written and read back in each number format, cut at any byte,
// malformed lines named; and the traces of plates and triangles on the plane y = 0 that its frames draw.
#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "legacy/legacy_formats.hpp"
#include "output/animation_2d_output.hpp"

namespace dem {
namespace {

using legacy::Animation2DFrame;
using legacy::Vec2;

std::string text_of(const std::vector<Animation2DFrame>& frames, legacy::NumberFormat format) {
  std::FILE* file = std::tmpfile();
  for (const Animation2DFrame& f : frames) legacy::write_animation_2d_frame(file, f, format);
  std::fflush(file);
  std::rewind(file);
  std::string text;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, file)) > 0;) text.append(buffer, n);
  std::fclose(file);
  return text;
}

legacy::ReadResult<Animation2DFrame> read_text(const std::string& text) {
  std::istringstream in(text);
  return legacy::read_animation_2d(in);
}

Animation2DFrame sample_frame(std::int64_t step) {
  Animation2DFrame f;
  f.domain = {-0.5, 1.25, 0, 2.0 / 3.0};
  f.scalars = {0.125 * static_cast<double>(step), 0.001, 1500.5, 3.25e-4};
  f.step = step;
  f.plates.push_back({1, {Vec2(-0.5, 0), Vec2(1.25, 0.1)}});
  f.triangles.push_back({7, {Vec2(0.1, 0.2), Vec2(0.3, 1.0 / 3.0)}});
  f.discs.push_back({1, Vec2(0.1, 0.05), 0.01, Vec2(-0.25, 1e-7), 3, -12.5, 0});
  f.discs.push_back({2, Vec2(0.2, 1.0 / 7.0), 0.02, Vec2(0, -2), 0, 0.75, 4});
  return f;
}

void expect_same(const Animation2DFrame& a, const Animation2DFrame& b, double tolerance) {
  EXPECT_EQ(a.step, b.step);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(a.domain[k], b.domain[k], tolerance * std::abs(b.domain[k]));
    EXPECT_NEAR(a.scalars[k], b.scalars[k], tolerance * std::abs(b.scalars[k]));
  }
  ASSERT_EQ(a.plates.size(), b.plates.size());
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  ASSERT_EQ(a.discs.size(), b.discs.size());
  EXPECT_EQ(a.triangles[0].id, b.triangles[0].id);
  EXPECT_TRUE(a.triangles[0].ends[1].isApprox(b.triangles[0].ends[1], tolerance));
  for (std::size_t k = 0; k < a.discs.size(); ++k) {
    EXPECT_EQ(a.discs[k].id, b.discs[k].id);
    EXPECT_TRUE(a.discs[k].position.isApprox(b.discs[k].position, tolerance));
    EXPECT_NEAR(a.discs[k].diameter, b.discs[k].diameter, tolerance * b.discs[k].diameter);
    EXPECT_NEAR(a.discs[k].spin, b.discs[k].spin, tolerance * std::abs(b.discs[k].spin));
    EXPECT_EQ(a.discs[k].contacts, b.discs[k].contacts);
    EXPECT_EQ(a.discs[k].part, b.discs[k].part);
  }
}

TEST(Animation2DFile, WritesTheLayoutOfTheDocs) {
  const std::string text = text_of({sample_frame(40)}, legacy::NumberFormat::LegacyFixed);
  EXPECT_EQ(text,
            "2DA:\n"
            "-0.500 1.250 0.000 0.667\n"
            "5.0000 0.0010 1500.5000 0.0003\n"
            "1\n"
            "40 2 1\n"
            "1 rplate -0.500 0.000 1.250 0.100\n"
            "7 tri 0.100 0.200 0.300 0.333\n"
            "1 0.10 0.05 0.0100 -0.25 0.00 3 -12.50 0\n"
            "2 0.20 0.14 0.0200 0.00 -2.00 0 0.75 4\n");
}

TEST(Animation2DFile, RoundTripsInFullPrecisionAndToSevenDigitsInScientific) {
  const std::vector<Animation2DFrame> frames{sample_frame(0), sample_frame(100)};
  const auto full = read_text(text_of(frames, legacy::NumberFormat::Full));
  ASSERT_TRUE(full.problem.empty()) << full.problem;
  ASSERT_EQ(full.frames.size(), 2u);
  expect_same(full.frames[1], frames[1], 0);
  const auto scientific = read_text(text_of(frames, legacy::NumberFormat::Scientific));
  ASSERT_EQ(scientific.frames.size(), 2u);
  expect_same(scientific.frames[0], frames[0], 1e-6);
}

TEST(Animation2DFile, CutAtAnyByteKeepsTheCompleteFramesAndSaysItWasCut) {
  const std::string text = text_of({sample_frame(0), sample_frame(1)}, legacy::NumberFormat::Scientific);
  const std::size_t first_end = text.find("2DA:", 1);
  for (std::size_t cut = 1; cut < text.size(); ++cut) {
    const auto r = read_text(text.substr(0, cut));
    EXPECT_EQ(r.frames.size(), cut >= first_end ? 1u : 0u) << "cut at " << cut;
    if (cut != first_end) {
      EXPECT_TRUE(r.truncated) << "cut at " << cut << ": " << r.problem;
    }
  }
}

TEST(Animation2DFile, MalformedLinesAreNamed) {
  std::string text = text_of({sample_frame(3)}, legacy::NumberFormat::LegacyFixed);
  std::string wrong_columns = text;
  wrong_columns.replace(wrong_columns.find("1 0.10 0.05"), 11, "1 0.10 0.05 0.0");  // a 3D particle line
  auto r = read_text(wrong_columns);
  EXPECT_FALSE(r.truncated);
  EXPECT_EQ(r.problem, "line 8: expected 9 values on the disc line 1 of 2 (id x z D vx vz nc w part), found 10");
  std::string wrong_word = text;
  wrong_word.replace(wrong_word.find("tri"), 3, "seg");
  EXPECT_EQ(read_text(wrong_word).problem, "line 7: column 2 is 'seg', expected 'tri'");
  EXPECT_EQ(read_text("3DA:\n").problem, "line 1: expected the frame header '2DA:', found '3DA:'");
}

TEST(PlaneTrace, APlateAcrossThePlaneLeavesTheSegmentWhereItCrosses) {
  // a vertical plate from y = -1 to 1, leaning in x-z
  const std::array<Vec3, 4> plate{Vec3(0, -1, 0), Vec3(1, -1, 1), Vec3(1, 1, 1), Vec3(0, 1, 0)};
  const auto trace = trace_on_plane(plate.data(), 4);
  ASSERT_TRUE(trace);
  const Vec3 a = (*trace)[0], b = (*trace)[1];
  EXPECT_TRUE((a.isApprox(Vec3(0, 0, 0)) && b.isApprox(Vec3(1, 0, 1))) ||
              (b.isApprox(Vec3(0, 0, 0)) && a.isApprox(Vec3(1, 0, 1))));
  // a triangle with a corner in the plane and the opposite edge across it
  const std::array<Vec3, 3> triangle{Vec3(0, 0, 2), Vec3(1, -1, 0), Vec3(1, 1, 0)};
  const auto cut = trace_on_plane(triangle.data(), 3);
  ASSERT_TRUE(cut);
  EXPECT_NEAR(((*cut)[0] - (*cut)[1]).norm(), std::sqrt(5.0), 1e-12);
}

TEST(PlaneTrace, APolygonBesideThePlaneOrTouchingItAtACornerLeavesNone) {
  const std::array<Vec3, 3> beside{Vec3(0, 1, 0), Vec3(1, 2, 0), Vec3(0, 3, 1)};
  EXPECT_FALSE(trace_on_plane(beside.data(), 3));
  const std::array<Vec3, 3> corner{Vec3(0, 0, 0), Vec3(1, 2, 0), Vec3(0, 3, 1)};
  EXPECT_FALSE(trace_on_plane(corner.data(), 3));
}

}  // namespace
}  // namespace dem
