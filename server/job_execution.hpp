// Runs one job of the server: its spec from its folder, the legacy files into its outputs, live
// frames to its viewers, a checkpoint now and then; resumed from the checkpoint when there is one.
// What the run does (start, progress, checkpoints, notes, how it ended) goes to the job's log.
#pragma once

#include <cstdint>

#include <atomic>
#include <functional>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "server/frame_hub.hpp"
#include "server/job_folder.hpp"
#include "sim/runner.hpp"

namespace dem::server {

struct ExecutionHooks {
  std::int64_t job = 0;
  int threads = 0;                                        // OpenMP threads for the job (0: all cores)
  double checkpoint_seconds = 10;                         // a checkpoint every this many seconds (checked each 0.5 s)
  const std::atomic<bool>* stop = nullptr;                // cancel or shut down: stop between steps
  const std::atomic<bool>* checkpoint_on_stop = nullptr;  // shut down: save the state where it stopped
  std::shared_ptr<FrameChannel> frames;                   // may be null
  double max_frame_rate = 30;                             // live frames a second at most; 0: every output frame
  double max_output_bytes = 0;                            // the job's files may hold at most this (0: no limit)
  std::function<void(const Simulation&)> on_start;
  std::function<void(const Progress&)> on_progress;
  std::function<void(std::int64_t step)> on_checkpoint;
};

struct ExecutionResult {
  enum class Kind { Succeeded, Failed, Stopped };
  Kind kind = Kind::Succeeded;
  std::string error;
  double run_seconds = 0;     // the stepping loop's wall time, observers included
  double stream_seconds = 0;  // of which making and handing out live frames
  std::int64_t step = -1;     // the step the run reached (where it failed or stopped); -1: never began
  nlohmann::json results;     // the run's results (results.json) when it ran to its end or failed; else null
};

ExecutionResult execute_job(const JobFolder& folder, const ExecutionHooks& hooks);

}  // namespace dem::server
