// The bundled cases' trends, on the cases' own specs (cases/NAME/spec.json) as their studies vary
// them: what each case's README shows in its figure must hold beyond the scatter between seeds.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "output/run_results.hpp"
#include "sim/runner.hpp"
#include "spec/spec_loader.hpp"

namespace dem::test::test_case_trends {
namespace {

namespace fs = std::filesystem;

fs::path case_dir(const std::string& name) { return fs::path(DEM_SOURCE_DIR) / "cases" / name; }

// Runs `spec` (read from the case's folder, its files relative to it) with a results recorder.
RunResults run_case(const std::string& name, const api::JobSpec& spec, const std::string& label) {
  const Scene scene = spec::to_scene(spec, case_dir(name).string());
  Simulation sim(scene);
  const fs::path dir = fs::temp_directory_path() / ("dem_trend_" + label + "_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  ResultsRecorder recorder(sim, (dir / ResultsRecorder::kTrackName).string(), false);
  run(sim, {&recorder});
  fs::remove_all(dir);
  return recorder.results();
}

// cases/rockfall: the more the ground resists rolling, the shorter the rocks run. Rolling friction
// 0.2 and 0.4 on the ground, two seeds of the rocks' shapes and places each (the study's 0.2 and
// 0.4 rows): every rock stays on the terrain, and the median and 90th-percentile travel at 0.4 are
// below the least of them at 0.2 (the README's study: 10.9-11.4 m against 8.8-8.9 m).
TEST(CaseTrends, RockfallRunsShorterOnAGroundThatResistsRolling) {
  const api::JobSpec base = spec::read_json_file((case_dir("rockfall") / "spec.json").string());
  std::vector<MotionResults> low, high;
  for (double mu_r : {0.2, 0.4})
    for (unsigned seed : {1u, 2u}) {
      api::JobSpec spec = base;
      spec.mutable_interactions(1)->set_rolling_friction(mu_r);
      spec.mutable_ballast_stones(0)->set_seed(seed);
      const RunResults r = run_case("rockfall", spec, "rockfall" + std::to_string(seed));
      ASSERT_TRUE(r.ok) << r.error;
      ASSERT_TRUE(r.motion.has_value());
      const MotionResults& m = *r.motion;
      ASSERT_EQ(m.piece_travel.size(), static_cast<std::size_t>(MotionResults::kPieceQuantiles));
      EXPECT_GT(m.pieces, 30) << "each rock and boulder is its own piece";
      EXPECT_LT(m.piece_travel.back(), 30.0) << "mu_r " << mu_r << ", seed " << seed << ": a rock left the terrain";
      (mu_r < 0.3 ? low : high).push_back(m);
    }
  for (const MotionResults& h : high)
    for (const MotionResults& l : low) {
      EXPECT_LT(h.piece_travel[10], l.piece_travel[10]) << "the median travel";
      EXPECT_LT(h.piece_travel[18], l.piece_travel[18]) << "the 90th percentile";
    }
}

}  // namespace
}  // namespace dem::test::test_case_trends
