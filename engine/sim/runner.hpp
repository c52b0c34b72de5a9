// Runs a simulation to its end, calling observers between steps (never inside the force loop).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "sim/simulation.hpp"

namespace dem {

struct RunOutcome {
  bool ok = true;
  bool cancelled = false;
  std::string error;  // set when !ok
  std::int64_t steps = 0;
  double loop_seconds = 0;  // wall time of the stepping loop, observers included
};

// Observers see the simulation at frame times: the first step, every outputs.every_steps, the last.
class Observer {
 public:
  virtual ~Observer() = default;
  virtual void frame(const Simulation& sim) = 0;
  virtual void finish(const Simulation&, const RunOutcome&) {}
  // An observer that needs every step (a few numbers per step, as the results' load cycles) says so:
  // step() is then called after each step, frames included.
  virtual bool wants_steps() const { return false; }
  virtual void step(const Simulation&) {}
};

struct Progress {
  std::int64_t step;
  std::int64_t total;  // a stage that ends early shortens it
  double steps_per_second;
  double seconds_left;
  std::string stage;  // a staged run's stage, "" without stages
};

struct RunOptions {
  std::function<void(const Progress&)> on_progress;  // called about every progress_seconds
  // Also about every progress_seconds, between steps (the server's checkpoints: the state may be
  // saved at any step, since the files change only at frames).
  std::function<void(const Simulation&)> periodically;
  // After every step, told whether it was a frame (the server's live frames, which may come more
  // often than the files' frames).
  std::function<void(const Simulation&, bool frame)> after_step;
  double progress_seconds = 0.5;
  const std::atomic<bool>* cancel = nullptr;
};

RunOutcome run(Simulation& sim, const std::vector<Observer*>& observers, const RunOptions& options = {});

}  // namespace dem
