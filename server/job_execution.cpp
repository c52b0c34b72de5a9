#include "server/job_execution.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "output/run_results.hpp"
#include "output/run_writers.hpp"
#include "results/results_json.hpp"
#include "server/checkpoint.hpp"
#include "server/job_log.hpp"
#include "server/own_files.hpp"
#include "spec/spec_loader.hpp"

namespace dem::server {
namespace {

// Saves a checkpoint when the last one is `seconds` old. Any step will do: the output files change
// only at frames, so their lengths at any step match the state.
class Checkpointer {
 public:
  Checkpointer(const JobFolder& folder, double seconds, std::function<void(std::int64_t)> saved)
      : folder_(folder), seconds_(seconds), saved_(std::move(saved)), last_(std::chrono::steady_clock::now()) {}
  void maybe_save(const Simulation& sim) {
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_).count() >= seconds_) save(sim);
  }
  void save(const Simulation& sim) {
    // at step 0 a resumed run would write its first frame again: it starts over instead
    if (sim.step_count() == 0) return;
    write_checkpoint(sim, folder_.outputs().string(), folder_.checkpoint().string());
    last_ = std::chrono::steady_clock::now();
    if (saved_) saved_(sim.step_count());
  }

 private:
  const JobFolder& folder_;
  double seconds_;
  std::function<void(std::int64_t)> saved_;
  std::chrono::steady_clock::time_point last_;
};

// Encodes and publishes a frame only while somebody watches (an unwatched job pays nothing). With a
// rate, a frame goes out whenever 1/rate seconds have passed, at any step, so a run whose files
// have a frame a minute still moves on screen (force chains come with the files' frames only);
// with rate 0, at every frame of the files. The last step always goes out.
class FramePublisher {
 public:
  FramePublisher(std::int64_t job, std::shared_ptr<FrameChannel> channel, double max_rate)
      : encoder_(job), channel_(std::move(channel)), min_interval_(max_rate > 0 ? 1.0 / max_rate : 0.0) {}
  void after_step(const Simulation& sim, bool file_frame) {
    if (!channel_ || !channel_->has_viewers()) return;
    const bool last = sim.step_count() == sim.total_steps();
    if (!last) {
      if (min_interval_ == 0 && !file_frame) return;
      if (min_interval_ > 0) {
        const auto now = std::chrono::steady_clock::now();
        if (published_ && std::chrono::duration<double>(now - last_).count() < min_interval_) return;
      }
    }
    const auto start = std::chrono::steady_clock::now();
    channel_->publish(std::make_shared<const EncodedFrame>(encoder_.encode(sim, channel_->wants_force_chains())));
    last_ = start;
    published_ = true;
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  double seconds() const { return seconds_; }  // the engine's time spent on live frames

 private:
  FrameEncoder encoder_;
  std::shared_ptr<FrameChannel> channel_;
  double min_interval_;
  std::chrono::steady_clock::time_point last_;
  bool published_ = false;
  double seconds_ = 0;
};

// The job's files, at a frame: past the server's limit the job stops here, failed (the files
// written so far stay as they are).
void check_output_size(const JobFolder& folder, double limit) {
  std::uintmax_t total = 0;
  std::error_code error;
  for (const auto& f : std::filesystem::directory_iterator(folder.outputs(), error))
    if (f.is_regular_file(error)) total += f.file_size(error);
  if (static_cast<double>(total) <= limit) return;
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "the job's files hold %.1f MB, past the server's limit of %.1f MB (--max-output-mb): write frames less "
                "often (outputs.interval or outputs.everySteps) or fewer files (outputs.vtk: false leaves ParaView's "
                "out)",
                static_cast<double>(total) / 1048576, limit / 1048576);
  throw std::runtime_error(buf);
}

api::JobSpec read_spec(const JobFolder& folder) {
  std::ifstream in(folder.spec(), std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  if (!in) throw std::runtime_error("cannot read the job's spec " + folder.spec().string());
  return spec::parse_binary(bytes.str());
}

// What `dem run` prints first: the scene's size and its time step; and the threads it runs on.
std::string scene_line(const Simulation& sim) {
  char line[200];
  std::snprintf(line, sizeof line, "%zu particles, %zu walls, %lld steps; ", sim.particles().size(),
                sim.scene().walls.size(), static_cast<long long>(sim.total_steps()));
  const int threads = sim.scene().numerics.threads;
  return line + sim.time_step().describe() +
         (threads > 0 ? "; " + std::to_string(threads) + (threads == 1 ? " thread" : " threads") : "; all cores");
}

// How the run ended, for the job's log.
std::string outcome_line(const ExecutionResult& result) {
  char line[200];
  switch (result.kind) {
    case ExecutionResult::Kind::Succeeded:
      std::snprintf(line, sizeof line, "run completed at step %lld (%.1f s of stepping, %.1f s of it on live frames)",
                    static_cast<long long>(result.step), result.run_seconds, result.stream_seconds);
      return line;
    case ExecutionResult::Kind::Failed:
      if (result.step < 0) return "run failed before its first step: " + result.error;
      return "run failed at step " + std::to_string(result.step) + ": " + result.error;
    case ExecutionResult::Kind::Stopped:  // the queue says why (a cancel, the server's shutdown)
      return "run stopped at step " + std::to_string(result.step);
  }
  return "";
}

ExecutionResult run_job(const JobFolder& folder, const ExecutionHooks& hooks) {
  ExecutionResult result;
  // where a run that throws (a file that cannot be written, the output limit) stopped, and after how
  // long: the job's record shows them as for any other failure
  std::optional<std::chrono::steady_clock::time_point> loop_start;
  auto note_where_it_stopped = [&](std::int64_t step) {
    if (step >= 0) result.step = step;
    if (loop_start)
      result.run_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - *loop_start).count();
  };
  std::int64_t last_step = -1;
  try {
    Scene scene = spec::to_scene(read_spec(folder));
    if (hooks.threads > 0 && (scene.numerics.threads == 0 || scene.numerics.threads > hooks.threads))
      scene.numerics.threads = hooks.threads;
    Simulation sim(std::move(scene));
    std::filesystem::create_directories(folder.outputs());
    if (!is_own_folder(folder.root) || !is_own_folder(folder.outputs()))
      throw std::runtime_error(folder.outputs().string() +
                               " is not a folder of the job's own (a link?): the job's files are not written there");
    const bool resume = std::filesystem::exists(folder.checkpoint());
    if (resume) resume_from_checkpoint(sim, folder.outputs().string(), folder.checkpoint().string());
    append_job_log(folder.log(), (resume ? "run resumed from the checkpoint at step " +
                                               std::to_string(sim.step_count()) + " (its files cut back to it): "
                                         : std::string("run started: ")) +
                                     scene_line(sim));
    if (hooks.on_start) hooks.on_start(sim);

    std::vector<std::unique_ptr<Observer>> writers = make_run_writers(sim, folder.outputs().string(), resume);
    FramePublisher publisher(hooks.job, hooks.frames, hooks.max_frame_rate);
    Checkpointer checkpointer(folder, hooks.checkpoint_seconds, [&](std::int64_t step) {
      append_job_log(folder.log(), "checkpoint at step " + std::to_string(step));
      if (hooks.on_checkpoint) hooks.on_checkpoint(step);
    });
    ProgressLog progress_log(folder.log());
    ResultsRecorder recorder(sim, (folder.outputs() / ResultsRecorder::kTrackName).string(), resume);
    std::vector<Observer*> observers;
    observers.reserve(writers.size() + 1);
    for (auto& w : writers) observers.push_back(w.get());
    observers.push_back(&recorder);

    RunOptions options;
    options.cancel = hooks.stop;
    options.on_progress = [&](const Progress& p) {
      progress_log.report(p);
      if (hooks.on_progress) hooks.on_progress(p);
    };
    options.progress_seconds = 0.5;
    options.periodically = [&](const Simulation& s) { checkpointer.maybe_save(s); };
    options.after_step = [&](const Simulation& s, bool frame) {
      last_step = s.step_count();
      publisher.after_step(s, frame);
      if (frame && hooks.max_output_bytes > 0) check_output_size(folder, hooks.max_output_bytes);
    };
    last_step = sim.step_count();
    loop_start = std::chrono::steady_clock::now();
    const RunOutcome outcome = run(sim, observers, options);
    result.step = sim.step_count();
    writers.clear();  // closes the files
    result.run_seconds = outcome.loop_seconds;
    result.stream_seconds = publisher.seconds();
    if (outcome.cancelled) {
      result.kind = ExecutionResult::Kind::Stopped;
      if (hooks.checkpoint_on_stop && hooks.checkpoint_on_stop->load()) checkpointer.save(sim);
    } else if (!outcome.ok) {
      result.kind = ExecutionResult::Kind::Failed;
      result.error = outcome.error;
    }
    if (result.kind != ExecutionResult::Kind::Stopped) {  // a stopped job goes on, or was cancelled
      results::write_results_file(recorder.results(), folder.outputs().string());
      result.results = results::to_json(recorder.results());
      for (const std::string& note : recorder.results().notes) append_job_log(folder.log(), "note: " + note);
    }
  } catch (const spec::SpecError& e) {
    result.kind = ExecutionResult::Kind::Failed;
    for (const std::string& p : e.problems()) result.error += (result.error.empty() ? "" : "; ") + p;
  } catch (const std::exception& e) {
    result.kind = ExecutionResult::Kind::Failed;
    result.error = e.what();
    note_where_it_stopped(last_step);
  }
  return result;
}

}  // namespace

ExecutionResult execute_job(const JobFolder& folder, const ExecutionHooks& hooks) {
  ExecutionResult result = run_job(folder, hooks);
  append_job_log(folder.log(), outcome_line(result));
  return result;
}

}  // namespace dem::server
