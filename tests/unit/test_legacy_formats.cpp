// Tests of the legacy text formats: Fortran numbers, ANIMATION_3D.dat and ForceChain_3D.dat
// (docs/formats.md sections 3 and 4).
#include <gtest/gtest.h>

#include <clocale>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "legacy/legacy_formats.hpp"

namespace dem::legacy {
namespace {

// ---------------------------------------------------------------------------------------------
// Helpers

// What a writer puts into a FILE*, as a string.
std::string written_text(const std::function<void(std::FILE*)>& write) {
  std::FILE* file = std::tmpfile();
  if (file == nullptr) {
    ADD_FAILURE() << "tmpfile() failed";
    return {};
  }
  write(file);
  std::fflush(file);
  std::rewind(file);
  std::string text;
  char buffer[4096];
  std::size_t count = 0;
  while ((count = std::fread(buffer, 1, sizeof buffer, file)) > 0) text.append(buffer, count);
  std::fclose(file);
  return text;
}

std::string animation_text(const std::vector<AnimationFrame>& frames, NumberFormat format) {
  return written_text([&](std::FILE* file) {
    for (const AnimationFrame& frame : frames) write_animation_frame(file, frame, format);
  });
}

std::string force_chain_text(const std::vector<ForceChainFrame>& frames, NumberFormat format) {
  return written_text([&](std::FILE* file) {
    for (const ForceChainFrame& frame : frames) write_force_chain_frame(file, frame, format);
  });
}

ReadResult<AnimationFrame> read_animation_text(const std::string& text) {
  std::istringstream in(text);
  return read_animation(in);
}

ReadResult<ForceChainFrame> read_force_chain_text(const std::string& text) {
  std::istringstream in(text);
  return read_force_chains(in);
}

// A frame shaped like BallastDEM's sample (manual figure 3.5): its domain, a plate and a particle.
AnimationFrame manual_sample_frame() {
  AnimationFrame frame;
  frame.domain = {-540, 540, -540, 540, -540, 540};
  frame.scalars = {0.3, 0, 0.5, 0.009};
  frame.step = 0;
  AnimationPlate plate;
  plate.id = 1;
  plate.corners = {Vec3(-350, -400, -150), Vec3(350, -400, -150), Vec3(350, 400, -150), Vec3(-350, 400, -150)};
  frame.plates.push_back(plate);
  AnimationParticle particle;
  particle.id = 1;
  particle.position = Vec3(-40.34, -34.86, -136.05);
  particle.diameter = 10.1036;
  particle.part = 3;
  frame.particles.push_back(particle);
  return frame;
}

// Frames with plates, triangles (none in the second frame) and particles. With scale > 0 every real
// lies in [-scale, scale] (the fixed format prints them to a few decimals); with scale == 0 the reals
// spread over eleven decades and both signs (the scientific format keeps seven digits of each).
std::vector<AnimationFrame> varied_animation_frames(int frame_count, double scale, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> decade(-6, 5);
  auto value = [&] { return scale > 0 ? unit(random) * scale : unit(random) * std::pow(10.0, decade(random)); };
  auto vec3 = [&] { return Vec3(value(), value(), value()); };

  std::vector<AnimationFrame> frames;
  for (int f = 0; f < frame_count; ++f) {
    AnimationFrame frame;
    for (double& d : frame.domain) d = value();
    for (double& s : frame.scalars) s = value();
    frame.step = 1000LL * f + 7;
    for (int k = 0; k < 2; ++k) {
      AnimationPlate plate;
      plate.id = k + 1;
      for (Vec3& corner : plate.corners) corner = vec3();
      frame.plates.push_back(plate);
    }
    for (int k = 0; k < (f == 1 ? 0 : 3); ++k) {
      AnimationTriangle triangle;
      triangle.id = k + 1;
      for (Vec3& corner : triangle.corners) corner = vec3();
      frame.triangles.push_back(triangle);
    }
    for (int k = 0; k < 4 + f; ++k) {
      AnimationParticle particle;
      particle.id = k + 1;
      particle.position = vec3();
      particle.diameter = std::abs(value());
      particle.velocity = vec3();
      particle.contacts = k % 5;
      particle.angular_velocity = vec3();
      particle.part = k / 2;
      frame.particles.push_back(particle);
    }
    frames.push_back(frame);
  }
  return frames;
}

std::vector<ForceChainFrame> varied_force_chain_frames(int frame_count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> force(0.0, 6e5);
  std::vector<ForceChainFrame> frames;
  for (int f = 0; f < frame_count; ++f) {
    ForceChainFrame frame;
    frame.step = 13500LL + 500 * f;
    for (int k = 0; k < 3 + f; ++k) {
      const double normal = force(random);
      frame.chains.push_back({k + 1, k + 10 + f, normal, 0.5 * normal * (k % 3) / 2.0});
    }
    frames.push_back(frame);
  }
  return frames;
}

// Tolerance of a value printed with 7 significant digits (%.6e).
double scientific_tolerance(double value) { return 5.0000001e-7 * std::abs(value) + 1e-300; }

// Tolerance of a value printed with `decimals` decimals (%.<decimals>f).
double fixed_tolerance(int decimals) { return 0.5000001 * std::pow(10.0, -decimals) + 1e-9; }

struct AnimationTolerances {
  std::function<double(double)> domain, scalar, corner, position, diameter, velocity;
};

AnimationTolerances tolerances(NumberFormat format) {
  if (format == NumberFormat::Scientific) {
    auto t = [](double v) { return scientific_tolerance(v); };
    return {t, t, t, t, t, t};
  }
  auto decimals = [](int d) { return [d](double) { return fixed_tolerance(d); }; };
  return {decimals(3), decimals(4), decimals(3), decimals(2), decimals(4), decimals(2)};
}

void expect_near_vec3(const Vec3& expected, const Vec3& actual, const std::function<double(double)>& tolerance) {
  for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(expected[axis], actual[axis], tolerance(expected[axis]));
}

void expect_animation_frames_match(const std::vector<AnimationFrame>& expected,
                                   const std::vector<AnimationFrame>& actual, NumberFormat format) {
  const AnimationTolerances tol = tolerances(format);
  ASSERT_EQ(expected.size(), actual.size());
  for (std::size_t f = 0; f < expected.size(); ++f) {
    const AnimationFrame& e = expected[f];
    const AnimationFrame& a = actual[f];
    for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(e.domain[k], a.domain[k], tol.domain(e.domain[k]));
    for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(e.scalars[k], a.scalars[k], tol.scalar(e.scalars[k]));
    EXPECT_EQ(e.step, a.step);
    ASSERT_EQ(e.plates.size(), a.plates.size());
    for (std::size_t k = 0; k < e.plates.size(); ++k) {
      EXPECT_EQ(e.plates[k].id, a.plates[k].id);
      for (int c = 0; c < 4; ++c) expect_near_vec3(e.plates[k].corners[c], a.plates[k].corners[c], tol.corner);
    }
    ASSERT_EQ(e.triangles.size(), a.triangles.size());
    for (std::size_t k = 0; k < e.triangles.size(); ++k) {
      EXPECT_EQ(e.triangles[k].id, a.triangles[k].id);
      for (int c = 0; c < 3; ++c) expect_near_vec3(e.triangles[k].corners[c], a.triangles[k].corners[c], tol.corner);
    }
    ASSERT_EQ(e.particles.size(), a.particles.size());
    for (std::size_t k = 0; k < e.particles.size(); ++k) {
      const AnimationParticle& ep = e.particles[k];
      const AnimationParticle& ap = a.particles[k];
      EXPECT_EQ(ep.id, ap.id);
      expect_near_vec3(ep.position, ap.position, tol.position);
      EXPECT_NEAR(ep.diameter, ap.diameter, tol.diameter(ep.diameter));
      expect_near_vec3(ep.velocity, ap.velocity, tol.velocity);
      EXPECT_EQ(ep.contacts, ap.contacts);
      expect_near_vec3(ep.angular_velocity, ap.angular_velocity, tol.velocity);
      EXPECT_EQ(ep.part, ap.part);
    }
  }
}

void expect_force_chain_frames_match(const std::vector<ForceChainFrame>& expected,
                                     const std::vector<ForceChainFrame>& actual, NumberFormat format) {
  auto tolerance = [&](double v) {
    return format == NumberFormat::Scientific ? scientific_tolerance(v) : fixed_tolerance(2);
  };
  ASSERT_EQ(expected.size(), actual.size());
  for (std::size_t f = 0; f < expected.size(); ++f) {
    EXPECT_EQ(expected[f].step, actual[f].step);
    ASSERT_EQ(expected[f].chains.size(), actual[f].chains.size());
    for (std::size_t k = 0; k < expected[f].chains.size(); ++k) {
      const ForceChain& e = expected[f].chains[k];
      const ForceChain& a = actual[f].chains[k];
      EXPECT_EQ(e.i, a.i);
      EXPECT_EQ(e.j, a.j);
      EXPECT_NEAR(e.normal_force, a.normal_force, tolerance(e.normal_force));
      EXPECT_NEAR(e.tangential_force, a.tangential_force, tolerance(e.tangential_force));
    }
  }
}

bool starts_with(const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; }

// ---------------------------------------------------------------------------------------------
// Fortran numbers

TEST(FortranReal, AcceptsFortranAndCForms) {
  const std::vector<std::pair<std::string, double>> cases = {{"7.547503e+002", 754.7503},
                                                             {"1.405110e+003", 1405.110},
                                                             {"1.0E9", 1.0e9},
                                                             {"1.0D9", 1.0e9},
                                                             {"1.0d-3", 1.0e-3},
                                                             {".5", 0.5},
                                                             {"5.", 5.0},
                                                             {"+3", 3.0},
                                                             {"-3.25", -3.25},
                                                             {"-.5", -0.5},
                                                             {"1.e5", 1.0e5},
                                                             {"0", 0.0},
                                                             {"45895.55", 45895.55},
                                                             {"1e-5", 1e-5},
                                                             {"2.5D+02", 250.0},
                                                             {"1.0-100", 1.0e-100},
                                                             {"1.0+100", 1.0e100},
                                                             {"-0.00", 0.0}};
  for (const auto& [token, expected] : cases) {
    const std::optional<double> value = parse_fortran_real(token);
    ASSERT_TRUE(value.has_value()) << token;
    EXPECT_DOUBLE_EQ(expected, *value) << token;
  }
}

TEST(FortranReal, RejectsWhatIsNotARealNumber) {
  const std::vector<std::string> cases = {"",     "1.0e",  "abc",   "1.2.3",  "1.0x", "e5",  ".",      "+",
                                          "-",    "1.0e+", "+-1",   "--1",    "nan",  "inf", "1,5",    " 1.0",
                                          "1.0 ", "0x1p3", "1e400", "1e-400", "1.0d", "1..", "rplate", "3DA:"};
  for (const std::string& token : cases) EXPECT_FALSE(parse_fortran_real(token).has_value()) << "'" << token << "'";
}

// ---------------------------------------------------------------------------------------------
// The manuals' sample rows

TEST(AnimationFile, ReadsTheBallastManualSampleRows) {
  // Tab-separated and with trailing tabs, as in the manual's Notepad screenshot (figure 3.5).
  const std::string text =
      "3DA:\t\n"
      "-540.000\t540.000\t-540.000\t540.000\t-540.000\t540.000\n"
      "0.3000\t0.0000\t0.5000\t0.0090\n"
      "\t0\n"
      "\t0\t1\t1\t\n"
      "1\trplate\t-350.000\t-400.000\t-150.000\t350.000\t-400.000\t-150.000\t350.000\t400.000\t-150.000\t-350.000\t400."
      "000\t-150.000\t\n"
      "1 -40.34 -34.86 -136.05 10.1036 0.00 0.00 0.00 0 0.00 0.00 0.00 3\n";
  const ReadResult<AnimationFrame> result = read_animation_text(text);
  ASSERT_EQ("", result.problem);
  EXPECT_FALSE(result.truncated);
  ASSERT_EQ(1u, result.frames.size());
  expect_animation_frames_match({manual_sample_frame()}, result.frames, NumberFormat::LegacyFixed);
  const AnimationParticle& particle = result.frames[0].particles[0];
  EXPECT_DOUBLE_EQ(-136.05, particle.position.z());
  EXPECT_DOUBLE_EQ(10.1036, particle.diameter);
  EXPECT_EQ(0, particle.contacts);
  EXPECT_EQ(3, particle.part);
  EXPECT_DOUBLE_EQ(-350.0, result.frames[0].plates[0].corners[3].x());
  EXPECT_DOUBLE_EQ(400.0, result.frames[0].plates[0].corners[3].y());
}

TEST(ForceChainFile, ReadsTheLandslideManualSample) {
  // PDEM-EGD section 3.2 item 6: the first 26 rows as printed (the header there counts all 420).
  const std::string rows =
      "2\t1\t485\t45895.55\t22947.77\t\n2\t1\t519\t31932.12\t15966.06\t\n4\t3\t90\t91886.00\t45943.21\t\n"
      "4\t3\t348\t176688.00\t88344.06\t\n5\t4\t241\t554963.00\t228636.62\t\n6\t5\t577\t181699.00\t90849.92\t\n"
      "9\t8\t260\t30410.00\t15205.11\t\n9\t8\t308\t66100.00\t33050.08\t\n10\t9\t225\t261552.00\t128274.37\t\n"
      "11\t10\t55\t293665.00\t146832.97\t\n13\t12\t333\t317549.00\t158774.70\t\n13\t12\t269\t59778.00\t294608.86\t\n"
      "13\t12\t319\t533674.18\t260141.34\t\n15\t14\t198\t119872.15\t15058.90\t\n16\t15\t280\t65882.32\t32691.16\t\n"
      "16\t15\t160\t21444.14\t10722.07\t\n17\t16\t737\t58079.63\t29039.81\t\n18\t17\t296\t65892.19\t30625.63\t\n"
      "18\t17\t410\t159316.00\t79658.00\t\n18\t17\t243\t437612.47\t195211.15\t\n19\t18\t650\t349476.03\t174738.02\t\n"
      "20\t19\t171\t88860.64\t44430.32\t\n21\t20\t386\t544760.08\t260333.95\t\n23\t22\t660\t62083.11\t31041.56\t\n"
      "23\t22\t517\t114308.17\t56801.73\t\n24\t23\t50\t166181.67\t83090.84\t\n";

  const ReadResult<ForceChainFrame> complete = read_force_chain_text("3DF:\t13500\t26\t\n" + rows);
  ASSERT_EQ("", complete.problem);
  ASSERT_EQ(1u, complete.frames.size());
  const ForceChainFrame& frame = complete.frames[0];
  EXPECT_EQ(13500, frame.step);
  ASSERT_EQ(26u, frame.chains.size());
  EXPECT_EQ(2, frame.chains[0].i);
  EXPECT_EQ(485, frame.chains[0].j);
  EXPECT_DOUBLE_EQ(45895.55, frame.chains[0].normal_force);
  EXPECT_DOUBLE_EQ(22947.77, frame.chains[0].tangential_force);
  EXPECT_EQ(24, frame.chains[25].i);
  EXPECT_EQ(50, frame.chains[25].j);
  for (const ForceChain& chain : frame.chains) EXPECT_LT(chain.i, chain.j);

  // With the manual's own header the excerpt is a frame cut short: no frame, truncation reported.
  const ReadResult<ForceChainFrame> excerpt = read_force_chain_text("3DF:\t13500\t420\t\n" + rows);
  EXPECT_TRUE(excerpt.frames.empty());
  EXPECT_TRUE(excerpt.truncated);
  EXPECT_NE(std::string::npos, excerpt.problem.find("line 1")) << excerpt.problem;
  EXPECT_NE(std::string::npos, excerpt.problem.find("chain line 27 of 420")) << excerpt.problem;
}

// ---------------------------------------------------------------------------------------------
// Exact written text

TEST(AnimationFile, WritesTheManualLayoutInLegacyFixed) {
  AnimationFrame frame = manual_sample_frame();
  AnimationTriangle triangle;
  triangle.id = 1;
  triangle.corners = {Vec3(0, 0, 0), Vec3(1.5, 0, 0), Vec3(0, -2.25, 0.0005)};
  frame.triangles.push_back(triangle);
  frame.particles[0].velocity = Vec3(0.126, -0.004, 1);
  frame.particles[0].contacts = 4;
  frame.particles[0].angular_velocity = Vec3(-2.5, 0, 0.333);
  frame.step = 13500;

  const std::string expected =
      "3DA:\n"
      "-540.000 540.000 -540.000 540.000 -540.000 540.000\n"
      "0.3000 0.0000 0.5000 0.0090\n"
      "1\n"
      "13500 1 1\n"
      "1 rplate -350.000 -400.000 -150.000 350.000 -400.000 -150.000 350.000 400.000 -150.000 -350.000 400.000 "
      "-150.000\n"
      "1 tri 0.000 0.000 0.000 1.500 0.000 0.000 0.000 -2.250 0.001\n"
      "1 -40.34 -34.86 -136.05 10.1036 0.13 -0.00 1.00 4 -2.50 0.00 0.33 3\n";
  EXPECT_EQ(expected, animation_text({frame}, NumberFormat::LegacyFixed));
}

TEST(AnimationFile, WritesEveryRealAsScientific) {
  AnimationFrame frame;
  frame.domain = {-1.5, 1.5, -2, 2, 0, 3};
  frame.scalars = {0.3, 0.001, 12.5, 0.25};
  frame.step = 42;
  AnimationTriangle triangle;
  triangle.id = 7;
  triangle.corners = {Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1)};
  frame.triangles.push_back(triangle);
  AnimationParticle particle;
  particle.id = 1;
  particle.position = Vec3(-40.34, 1e-9, 754.7503);
  particle.diameter = 0.0101036;
  particle.velocity = Vec3(1, -2, 0);
  particle.contacts = 2;
  particle.angular_velocity = Vec3(0, 0, 123456789);
  particle.part = 3;
  frame.particles.push_back(particle);

  const std::string expected =
      "3DA:\n"
      "-1.500000e+00 1.500000e+00 -2.000000e+00 2.000000e+00 0.000000e+00 3.000000e+00\n"
      "3.000000e-01 1.000000e-03 1.250000e+01 2.500000e-01\n"
      "1\n"
      "42 1 0\n"
      "7 tri 0.000000e+00 0.000000e+00 1.000000e+00 1.000000e+00 0.000000e+00 1.000000e+00 0.000000e+00 "
      "1.000000e+00 1.000000e+00\n"
      "1 -4.034000e+01 1.000000e-09 7.547503e+02 1.010360e-02 1.000000e+00 -2.000000e+00 0.000000e+00 2 "
      "0.000000e+00 0.000000e+00 1.234568e+08 3\n";
  EXPECT_EQ(expected, animation_text({frame}, NumberFormat::Scientific));
}

TEST(ForceChainFile, WritesTheManualLayout) {
  ForceChainFrame frame;
  frame.step = 13500;
  frame.chains = {{2, 485, 45895.55, 22947.77}, {2, 519, 31932.12, 15966.06}};

  EXPECT_EQ("3DF: 13500 2\n2 1 485 45895.55 22947.77\n2 1 519 31932.12 15966.06\n",
            force_chain_text({frame}, NumberFormat::LegacyFixed));
  EXPECT_EQ("3DF: 13500 2\n2 1 485 4.589555e+04 2.294777e+04\n2 1 519 3.193212e+04 1.596606e+04\n",
            force_chain_text({frame}, NumberFormat::Scientific));
}

TEST(ForceChainFile, WritesAnEmptyFrame) {
  ForceChainFrame frame;
  frame.step = 5;
  EXPECT_EQ("3DF: 5 0\n", force_chain_text({frame}, NumberFormat::Scientific));
  const ReadResult<ForceChainFrame> result = read_force_chain_text("3DF: 5 0\n3DF: 6 0\n");
  ASSERT_EQ(2u, result.frames.size());
  EXPECT_TRUE(result.frames[1].chains.empty());
}

TEST(LegacyWriters, IgnoreADecimalCommaLocale) {
  const char* const candidates[] = {"de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8", "fr_FR.utf8"};
  const std::string previous = std::setlocale(LC_NUMERIC, nullptr);
  bool switched = false;
  for (const char* name : candidates) switched = switched || std::setlocale(LC_NUMERIC, name) != nullptr;
  if (!switched) GTEST_SKIP() << "no decimal-comma locale installed";
  ForceChainFrame frame;
  frame.chains = {{1, 2, 1.5, 0.25}};
  const std::string text = force_chain_text({frame}, NumberFormat::LegacyFixed);
  std::setlocale(LC_NUMERIC, previous.c_str());
  EXPECT_EQ("3DF: 0 1\n1 0 2 1.50 0.25\n", text);
}

// ---------------------------------------------------------------------------------------------
// Round trips

TEST(AnimationFile, RoundTripsScientificToSevenDigits) {
  const std::vector<AnimationFrame> frames = varied_animation_frames(3, 0, 11);  // many magnitudes
  const ReadResult<AnimationFrame> result = read_animation_text(animation_text(frames, NumberFormat::Scientific));
  EXPECT_EQ("", result.problem);
  EXPECT_FALSE(result.truncated);
  expect_animation_frames_match(frames, result.frames, NumberFormat::Scientific);
}

TEST(AnimationFile, RoundTripsLegacyFixedToThePrintedDecimals) {
  const std::vector<AnimationFrame> frames = varied_animation_frames(3, 500, 12);  // a ballast box in mm
  const ReadResult<AnimationFrame> result = read_animation_text(animation_text(frames, NumberFormat::LegacyFixed));
  EXPECT_EQ("", result.problem);
  EXPECT_FALSE(result.truncated);
  expect_animation_frames_match(frames, result.frames, NumberFormat::LegacyFixed);
}

TEST(ForceChainFile, RoundTripsInBothNumberFormats) {
  const std::vector<ForceChainFrame> frames = varied_force_chain_frames(4, 13);
  for (NumberFormat format : {NumberFormat::Scientific, NumberFormat::LegacyFixed}) {
    const ReadResult<ForceChainFrame> result = read_force_chain_text(force_chain_text(frames, format));
    EXPECT_EQ("", result.problem);
    EXPECT_FALSE(result.truncated);
    expect_force_chain_frames_match(frames, result.frames, format);
  }
}

TEST(AnimationFile, RewritingWhatWasReadGivesTheSameText) {
  for (NumberFormat format : {NumberFormat::Scientific, NumberFormat::LegacyFixed}) {
    const std::string text = animation_text(varied_animation_frames(3, 0, 14), format);
    EXPECT_EQ(text, animation_text(read_animation_text(text).frames, format));
  }
}

// ---------------------------------------------------------------------------------------------
// Reader tolerance of the legacy programs' habits

TEST(AnimationFile, AcceptsBlankLinesTabsCrLfAndIntegersWrittenAsReals) {
  const std::string text =
      "\n3DA:\r\n"
      "  -540.0   540.0 -5.4D2 5.4D2 -540. 540.\r\n"
      "\r\n"
      "0.3\t0\t.5\t9.0E-3\r\n"
      "0.0\r\n"
      "0.0 1.0 1.0E0\r\n"
      "1.0 rplate -350 -400 -150 350 -400 -150 350 400 -150 -350 400 -150\r\n"
      "\t\r\n"
      "1.0\t-40.34\t-34.86\t-136.05\t10.1036\t0\t0\t0\t0.0\t0\t0\t0\t3.0\r\n";
  const ReadResult<AnimationFrame> result = read_animation_text(text);
  ASSERT_EQ("", result.problem);
  expect_animation_frames_match({manual_sample_frame()}, result.frames, NumberFormat::Scientific);
}

TEST(LegacyReaders, EmptyInputHasNoFramesAndNoProblem) {
  const ReadResult<AnimationFrame> animation = read_animation_text("");
  EXPECT_TRUE(animation.frames.empty());
  EXPECT_FALSE(animation.truncated);
  EXPECT_EQ("", animation.problem);
  const ReadResult<ForceChainFrame> chains = read_force_chain_text("\n \t\n");
  EXPECT_TRUE(chains.frames.empty());
  EXPECT_FALSE(chains.truncated);
  EXPECT_EQ("", chains.problem);
}

// ---------------------------------------------------------------------------------------------
// Truncated files

// End offsets of each frame in a file written frame by frame.
std::vector<std::size_t> frame_ends(const std::vector<std::string>& frame_texts) {
  std::vector<std::size_t> ends;
  std::size_t end = 0;
  for (const std::string& text : frame_texts) ends.push_back(end += text.size());
  return ends;
}

std::size_t complete_frames_before(const std::vector<std::size_t>& ends, std::size_t cut) {
  std::size_t count = 0;
  while (count < ends.size() && ends[count] <= cut) ++count;
  return count;
}

bool is_frame_boundary(const std::vector<std::size_t>& ends, std::size_t cut) {
  if (cut == 0) return true;
  for (std::size_t end : ends) {
    if (end == cut) return true;
  }
  return false;
}

TEST(AnimationFile, CutAtAnyByteReturnsTheCompleteFrames) {
  for (NumberFormat format : {NumberFormat::Scientific, NumberFormat::LegacyFixed}) {
    const std::vector<AnimationFrame> frames =
        varied_animation_frames(3, format == NumberFormat::Scientific ? 0 : 500, 15);
    std::vector<std::string> frame_texts;
    for (const AnimationFrame& frame : frames) frame_texts.push_back(animation_text({frame}, format));
    const std::vector<std::size_t> ends = frame_ends(frame_texts);
    const std::string text = frame_texts[0] + frame_texts[1] + frame_texts[2];

    for (std::size_t cut = 0; cut <= text.size(); ++cut) {
      const ReadResult<AnimationFrame> result = read_animation_text(text.substr(0, cut));
      const std::size_t expected_frames = complete_frames_before(ends, cut);
      ASSERT_EQ(expected_frames, result.frames.size()) << "cut at byte " << cut;
      const bool mid_frame = !is_frame_boundary(ends, cut);
      ASSERT_EQ(mid_frame, result.truncated) << "cut at byte " << cut << ": " << result.problem;
      ASSERT_EQ(mid_frame, !result.problem.empty()) << "cut at byte " << cut;
      if (mid_frame) {
        ASSERT_NE(std::string::npos, result.problem.find("line ")) << result.problem;
      }
      // The frames returned are exactly the ones written: rewriting them gives the same text.
      for (std::size_t f = 0; f < result.frames.size(); ++f) {
        ASSERT_EQ(frame_texts[f], animation_text({result.frames[f]}, format)) << "cut at byte " << cut;
      }
    }
  }
}

TEST(ForceChainFile, CutAtAnyByteReturnsTheCompleteFrames) {
  for (NumberFormat format : {NumberFormat::Scientific, NumberFormat::LegacyFixed}) {
    const std::vector<ForceChainFrame> frames = varied_force_chain_frames(3, 16);
    std::vector<std::string> frame_texts;
    for (const ForceChainFrame& frame : frames) frame_texts.push_back(force_chain_text({frame}, format));
    const std::vector<std::size_t> ends = frame_ends(frame_texts);
    const std::string text = frame_texts[0] + frame_texts[1] + frame_texts[2];

    for (std::size_t cut = 0; cut <= text.size(); ++cut) {
      const ReadResult<ForceChainFrame> result = read_force_chain_text(text.substr(0, cut));
      ASSERT_EQ(complete_frames_before(ends, cut), result.frames.size()) << "cut at byte " << cut;
      const bool mid_frame = !is_frame_boundary(ends, cut);
      ASSERT_EQ(mid_frame, result.truncated) << "cut at byte " << cut << ": " << result.problem;
      ASSERT_EQ(mid_frame, !result.problem.empty()) << "cut at byte " << cut;
      for (std::size_t f = 0; f < result.frames.size(); ++f) {
        ASSERT_EQ(frame_texts[f], force_chain_text({result.frames[f]}, format)) << "cut at byte " << cut;
      }
    }
  }
}

TEST(ForceChainFile, UnfinishedLastLineIsNotUsedEvenIfItLooksComplete) {
  // "22947.77" cut to "22947.7" would read as a valid but wrong number.
  const ReadResult<ForceChainFrame> result = read_force_chain_text("3DF: 13500 1\n2 1 485 45895.55 22947.7");
  EXPECT_TRUE(result.frames.empty());
  EXPECT_TRUE(result.truncated);
  EXPECT_NE(std::string::npos, result.problem.find("line 2")) << result.problem;
}

TEST(ForceChainFile, HugeCountInATruncatedFileDoesNotAllocateIt) {
  const ReadResult<ForceChainFrame> result = read_force_chain_text("3DF: 1 2000000000\n1 0 2 1.0 0.5\n");
  EXPECT_TRUE(result.frames.empty());
  EXPECT_TRUE(result.truncated);
}

// ---------------------------------------------------------------------------------------------
// Malformed lines

// The text of three small LegacyFixed animation frames, one line each in a vector.
std::vector<std::string> animation_lines() {
  std::istringstream text(animation_text(varied_animation_frames(3, 500, 17), NumberFormat::LegacyFixed));
  std::vector<std::string> lines;
  for (std::string line; std::getline(text, line);) lines.push_back(line);
  return lines;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

// Frame 1 of varied_animation_frames: 5 header lines, 2 plates, 3 triangles, 4 particles = 14 lines.
constexpr std::size_t first_frame_lines = 14;

TEST(AnimationFile, WrongColumnCountReportsTheLine) {
  std::vector<std::string> lines = animation_lines();
  const std::size_t bad = first_frame_lines + 8;  // a particle line of the second frame
  lines[bad] = "1 2 3";
  const ReadResult<AnimationFrame> result = read_animation_text(joined(lines));
  EXPECT_EQ(1u, result.frames.size());
  EXPECT_FALSE(result.truncated);
  EXPECT_TRUE(starts_with(result.problem, "line " + std::to_string(bad + 1) + ": expected 13 values"))
      << result.problem;
}

TEST(AnimationFile, NotANumberReportsLineAndColumn) {
  std::vector<std::string> lines = animation_lines();
  lines.insert(lines.begin() + 3, "");                // a blank line still counts in line numbers
  const std::size_t bad = first_frame_lines + 1 + 9;  // a particle line of the second frame
  lines[bad] = "3 1.2.3 0 0 10.0 0 0 0 0 0 0 0 1";
  const ReadResult<AnimationFrame> result = read_animation_text(joined(lines));
  EXPECT_EQ(1u, result.frames.size());
  EXPECT_FALSE(result.truncated);
  EXPECT_EQ("line " + std::to_string(bad + 1) + ": column 2 ('1.2.3') is not a number", result.problem);
}

TEST(AnimationFile, NonIntegralIdReportsTheLine) {
  std::vector<std::string> lines = animation_lines();
  lines[10] = "1.5 0 0 0 10.0 0 0 0 0 0 0 0 1";
  const ReadResult<AnimationFrame> result = read_animation_text(joined(lines));
  EXPECT_TRUE(result.frames.empty());
  EXPECT_EQ("line 11: column 1 ('1.5') is not an integer", result.problem);
}

TEST(AnimationFile, WrongPlateWordReportsTheLine) {
  std::vector<std::string> lines = animation_lines();
  lines[5].replace(lines[5].find("rplate"), 6, "rpiace");
  const ReadResult<AnimationFrame> result = read_animation_text(joined(lines));
  EXPECT_TRUE(result.frames.empty());
  EXPECT_EQ("line 6: column 2 is 'rpiace', expected 'rplate'", result.problem);
}

TEST(AnimationFile, NegativeCountReportsTheLine) {
  std::vector<std::string> lines = animation_lines();
  lines[3] = "-1";
  const ReadResult<AnimationFrame> result = read_animation_text(joined(lines));
  EXPECT_TRUE(result.frames.empty());
  EXPECT_FALSE(result.truncated);
  EXPECT_EQ("line 4: column 1 ('-1') is a negative count", result.problem);
}

TEST(AnimationFile, JunkBeforeTheFirstFrameReportsLineOne) {
  const ReadResult<AnimationFrame> result = read_animation_text("hello world\n3DA:\n");
  EXPECT_TRUE(result.frames.empty());
  EXPECT_FALSE(result.truncated);
  EXPECT_TRUE(starts_with(result.problem, "line 1: expected the frame header '3DA:'")) << result.problem;
}

TEST(AnimationFile, NewFrameInsideAnIncompleteFrameReportsBoth) {
  std::vector<std::string> lines = animation_lines();
  lines.erase(lines.begin() + 12, lines.begin() + first_frame_lines);  // drop the last 2 particles of frame 1
  const ReadResult<AnimationFrame> result = read_animation_text(joined(lines));
  EXPECT_TRUE(result.frames.empty());
  EXPECT_FALSE(result.truncated);
  EXPECT_EQ(
      "line 13: a new frame starts here, but the frame that starts at line 1 is incomplete: its particle line 3 of 4 "
      "is "
      "missing",
      result.problem);
}

TEST(ForceChainFile, MalformedLinesReportTheLine) {
  EXPECT_EQ("line 3: expected 5 values on the chain line 2 of 2 (i i-1 j Fn Ft), found 4",
            read_force_chain_text("3DF: 1 2\n1 0 2 1.0 0.5\n1 0 3 1.0\n").problem);
  EXPECT_EQ("line 2: column 4 ('abc') is not a number", read_force_chain_text("3DF: 1 1\n1 0 2 abc 0.5\n").problem);
  EXPECT_EQ("line 1: expected the frame header '3DF: step NC', found '3DF:' and more",
            read_force_chain_text("3DF: 1\n").problem);
  const ReadResult<ForceChainFrame> second_bad =
      read_force_chain_text("3DF: 1 1\n1 0 2 1 0.5\n3DF: x 1\n1 0 2 1 0.5\n");
  EXPECT_EQ(1u, second_bad.frames.size());
  EXPECT_FALSE(second_bad.truncated);
  EXPECT_EQ("line 3: column 2 ('x') is not an integer", second_bad.problem);
}

TEST(LegacyReaders, NeverCrashOnCorruptedFiles) {
  std::mt19937 random(18);
  const std::string animation = animation_text(varied_animation_frames(3, 500, 19), NumberFormat::LegacyFixed);
  const std::string chains = force_chain_text(varied_force_chain_frames(3, 20), NumberFormat::Scientific);
  const std::string alphabet = std::string("0123456789.-+eEdD \t\r\n\0\xff", 23) + "3DA:F";
  std::uniform_int_distribution<std::size_t> pick(0, alphabet.size() - 1);

  for (int attempt = 0; attempt < 3000; ++attempt) {
    std::string corrupted_animation = animation;
    std::string corrupted_chains = chains;
    for (int change = 0; change < 1 + attempt % 5; ++change) {
      corrupted_animation[random() % corrupted_animation.size()] = alphabet[pick(random)];
      corrupted_chains[random() % corrupted_chains.size()] = alphabet[pick(random)];
    }
    const ReadResult<AnimationFrame> a = read_animation_text(corrupted_animation);
    const ReadResult<ForceChainFrame> c = read_force_chain_text(corrupted_chains);
    ASSERT_LE(a.frames.size(), 3u);
    ASSERT_LE(c.frames.size(), 4u);  // a corrupted count can split a frame in two
    ASSERT_TRUE(a.problem.empty() || a.problem.find("line ") != std::string::npos) << a.problem;
    ASSERT_TRUE(!a.truncated || !a.problem.empty());
    ASSERT_TRUE(!c.truncated || !c.problem.empty());
  }
}

}  // namespace
}  // namespace dem::legacy
