// outputs.lastFrames (the PDEM-EGD manual's NLast): the particle files keep the run's last N frames;
// the time series keep every frame.
#include <gtest/gtest.h>

#include <fstream>

#include "legacy/legacy_formats.hpp"
#include "output/run_writers.hpp"
#include "sim/runner.hpp"
#include "support/command.hpp"
#include "support/scenes.hpp"

namespace dem::test {
namespace {

class LastFrames : public DemCommandTest {
 protected:
  // A sphere falling onto a floor for 100 steps, a frame every 10: 11 frames.
  std::vector<std::int64_t> animation_steps(std::int64_t last_frames, std::size_t* energy_rows) {
    Scene s = base_scene(LinearNormal::kName, 2500, 0, 0, 0.5, 0.3, 1e5);
    s.particles.push_back(sphere({0, 0, 0.02}, 0.01));
    s.walls.push_back(plane({0, 0, 0}, {0, 0, 1}, "floor"));
    s.gravity = {0, 0, -9.81};
    s.time.steps = 100;
    s.time.dt = 1e-5;
    s.outputs.animation = true;
    s.outputs.force_chains = true;
    s.outputs.every_steps = 10;
    s.outputs.last_frames = last_frames;
    Simulation sim(s);
    {
      auto writers = make_run_writers(sim, dir_.string(), false);
      std::vector<Observer*> observers;
      for (auto& w : writers) observers.push_back(w.get());
      EXPECT_TRUE(run(sim, observers).ok);
    }
    std::ifstream in(dir_ / "ANIMATION_3D.dat");
    const auto frames = legacy::read_animation(in);
    EXPECT_TRUE(frames.problem.empty()) << frames.problem;
    std::vector<std::int64_t> steps;
    for (const auto& f : frames.frames) steps.push_back(f.step);
    std::ifstream energy(dir_ / "Energy.dat");
    *energy_rows = legacy::read_rows(energy, 16).frames.size();
    std::ifstream chains(dir_ / "ForceChain_3D.dat");
    EXPECT_EQ(legacy::read_force_chains(chains).frames.size(), steps.size());
    return steps;
  }
};

TEST_F(LastFrames, TheParticleFilesKeepTheLastFramesAndTheTimeSeriesEveryFrame) {
  std::size_t rows = 0;
  EXPECT_EQ(animation_steps(3, &rows), (std::vector<std::int64_t>{80, 90, 100}));
  EXPECT_EQ(rows, 11u);
  EXPECT_EQ(animation_steps(0, &rows).size(), 11u);
  EXPECT_EQ(animation_steps(50, &rows).size(), 11u);  // more than the run has: all of them
  EXPECT_EQ(animation_steps(1, &rows), (std::vector<std::int64_t>{100}));
}

}  // namespace
}  // namespace dem::test
