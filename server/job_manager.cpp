#include "server/job_manager.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>

#include <spdlog/spdlog.h>

#include "server/durable_file.hpp"
#include "server/job_execution.hpp"
#include "server/job_log.hpp"
#include "server/tar_archive.hpp"
#include "spec/referenced_files.hpp"
#include "spec/spec_loader.hpp"

namespace dem::server {
namespace fs = std::filesystem;
namespace {

constexpr const char* kCancelled = "cancelled on request";
// Room for hundreds of the table's row updates (a few 4 KB pages each, with the WAL).
constexpr std::uint64_t kReservedBytes = 1u << 20;

// What a submission leaves when the server dies inside the transaction that inserts its row: the
// spec (or part of it, or its temporary) and an empty outputs folder, nothing else.
bool uncommitted_submission(const fs::path& folder) {
  for (const fs::directory_entry& e : fs::directory_iterator(folder)) {
    const std::string name = e.path().filename().string();
    if (e.is_directory() && name == "outputs" && fs::is_empty(e.path())) continue;
    if (e.is_regular_file() && name.rfind("spec.pb", 0) == 0) continue;
    return false;
  }
  return true;
}

// DATA/unaccounted/NAME, or NAME.2, NAME.3, ... when taken.
fs::path unaccounted_place(const fs::path& data, const std::string& name) {
  fs::path place = data / "unaccounted" / name;
  for (int k = 2; fs::exists(place); ++k) place = data / "unaccounted" / (name + "." + std::to_string(k));
  return place;
}

}  // namespace

// The frames' particles alone, at 100 bytes a sphere in the animation (a line is 100 to 300 bytes by
// the number format) and 169 in ParaView's .vtu: a spec that would pass the limit with that is
// refused before it runs.
void JobManager::refuse_outputs_past_limit(const Simulation& sim) const {
  const Scene& scene = sim.scene();
  const double per_sphere = (scene.outputs.animation ? 100.0 : 0.0) + (scene.outputs.vtk ? 169.0 : 0.0);
  if (per_sphere == 0 || scene.outputs.every_steps <= 0) return;
  // and a staged run's frame at the end of each stage
  const double frames =
      std::floor(static_cast<double>(sim.total_steps()) / static_cast<double>(scene.outputs.every_steps)) + 1 +
      static_cast<double>(scene.stages.size());
  const double bytes = frames * static_cast<double>(sim.particles().size()) * per_sphere;
  if (bytes <= options_.max_output_bytes) return;
  const char* files = !scene.outputs.vtk        ? "ANIMATION_3D.dat"
                      : scene.outputs.animation ? "ANIMATION_3D.dat and ParaView's .vtu files"
                                                : "ParaView's .vtu files";
  char buf[500];
  std::snprintf(buf, sizeof buf,
                "outputs: %.0f frames of %zu particles would write at least %.1f MB of %s, past the server's limit "
                "of %.1f MB for a job's files (--max-output-mb); write frames less often (outputs.interval or "
                "outputs.everySteps)%s",
                frames, sim.particles().size(), bytes / 1048576, files, options_.max_output_bytes / 1048576,
                scene.outputs.vtk ? " or leave ParaView's files out (outputs.vtk: false)" : "");
  throw spec::SpecError({buf});
}

JobManager::JobManager(ManagerOptions options, FrameHub& frames) : options_(std::move(options)), frames_(frames) {
  fs::create_directories(options_.data / "jobs");
  reserve_ = std::make_unique<SpaceReserve>(options_.data / "space.reserve", kReservedBytes);
  store_ = std::make_unique<JobStore>((options_.data / "jobs.db").string());
  recover();
}

JobManager::~JobManager() { shutdown(); }

void JobManager::recover() {
  for (JobRecord& job : store_->load_all()) {
    if (job.checkpoint_step >= 0 && !fs::exists(folder(job.id).checkpoint())) job.checkpoint_step = -1;
    if (job.state == JobState::Running) {
      job.state = JobState::Interrupted;
      // the table holds the step it last saved (at a checkpoint), not the one the job had reached: a
      // job killed at 84% read "at step 0" (an independent tester)
      job.error = "the server stopped while the job ran" +
                  (job.step > 0 ? " (past step " + std::to_string(job.step) + ", the last it saved)" : std::string()) +
                  "; " +
                  (job.checkpoint_step >= 0
                       ? "resume it to continue from its checkpoint at step " + std::to_string(job.checkpoint_step)
                       : std::string("it had no checkpoint yet: resuming starts it again"));
      save(job);  // on a full disk the table catches up later; the server starts all the same
      append_job_log(folder(job.id).log(), "interrupted: " + job.error);
    }
    if (!job.idempotency_key.empty()) by_key_[job.idempotency_key] = job.id;
    // half-written files of a crash (checkpoint.dat.tmp, outputs.tar.tmp): their whole versions
    // were never renamed over the real ones
    std::error_code ignored;
    for (const std::string& temporary :
         {folder(job.id).checkpoint().string() + ".tmp", folder(job.id).archive().string() + ".tmp"})
      fs::remove(temporary, ignored);
    jobs_[job.id] = std::move(job);
  }
  // A folder without a row: a submission that crashed before its row was committed holds its spec
  // and an empty outputs folder, and goes. Anything else (outputs, a checkpoint, an archive: a job
  // table lost or replaced) is never deleted: it is moved aside, out of the way of new jobs' ids.
  for (const fs::directory_entry& e : fs::directory_iterator(options_.data / "jobs")) {
    const std::string name = e.path().filename().string();
    const bool numeric = !name.empty() && name.size() < 19 &&
                         std::all_of(name.begin(), name.end(), [](char c) { return c >= '0' && c <= '9'; });
    if (!e.is_directory() || !numeric || jobs_.count(std::stoll(name))) continue;
    if (uncommitted_submission(e.path())) {
      fs::remove_all(e.path());
      continue;
    }
    const fs::path aside = unaccounted_place(options_.data, name);
    fs::create_directories(aside.parent_path());
    fs::rename(e.path(), aside);
    spdlog::warn("{} holds a job's files but the job table ({}) has no row for it: moved to {}, nothing deleted",
                 e.path().string(), (options_.data / "jobs.db").string(), aside.string());
  }
}

void JobManager::start() {
  std::lock_guard lock(mutex_);
  stopping_ = false;
  for (int k = 0; k < std::max(1, options_.concurrency); ++k) workers_.emplace_back([this] { work(); });
  if (options_.retention.active()) sweeper_ = std::thread([this] { sweep(); });
}

void JobManager::shutdown() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    for (auto& [id, running] : running_) {
      running->checkpoint_on_stop = true;
      running->stop = true;
    }
  }
  changed_.notify_all();
  sweeper_wake_.notify_all();
  for (std::thread& t : workers_)
    if (t.joinable()) t.join();
  workers_.clear();
  if (sweeper_.joinable()) sweeper_.join();
  std::lock_guard lock(mutex_);
  save_unsaved();
}

int JobManager::threads_per_job() const {
  if (options_.threads_per_job > 0) return options_.threads_per_job;
  return std::max(1, omp_get_num_procs() / std::max(1, options_.concurrency));
}

// One row's update of the job table; on a full disk the reserve is given up and the update tried
// once more (the table must learn how a job ended, whatever else the disk holds).
void JobManager::update_row(const JobRecord& job) {
  try {
    store_->update(job);
  } catch (const std::exception& e) {
    if (!reserve_->release()) throw;
    spdlog::warn("{}: the job table could not be written ({}): the space held in reserve is freed for it",
                 options_.data.string(), e.what());
    store_->update(job);
  }
  reserve_->restore();  // once there is room again
}

void JobManager::save(const JobRecord& job) {
  try {
    update_row(job);
  } catch (const std::exception& e) {
    if (unsaved_.insert(job.id).second)
      spdlog::error("job {}: its state is kept in memory until the table can be written: {}", job.id, e.what());
    store_problem_ = e.what();
    return;
  }
  unsaved_.erase(job.id);
  save_unsaved();
}

void JobManager::save_unsaved() {
  for (auto it = unsaved_.begin(); it != unsaved_.end();) {
    const auto job = jobs_.find(*it);
    if (job == jobs_.end()) {  // deleted meanwhile
      it = unsaved_.erase(it);
      continue;
    }
    try {
      update_row(job->second);
    } catch (const std::exception& e) {
      store_problem_ = e.what();
      return;
    }
    it = unsaved_.erase(it);
  }
  store_problem_.clear();
}

JobManager::StoreHealth JobManager::store_health() const {
  StoreHealth h;
  std::error_code error;
  const fs::space_info space = fs::space(options_.data, error);
  {
    std::lock_guard lock(mutex_);
    h.unsaved_jobs = unsaved_.size();
    h.problem = store_problem_;
  }
  if (error) {
    if (h.problem.empty()) h.problem = "cannot read the space of " + options_.data.string() + ": " + error.message();
    return h;
  }
  h.free_bytes = static_cast<double>(space.available);
  h.total_bytes = static_cast<double>(space.capacity);
  h.low_on_space = h.free_bytes < std::min(64.0 * 1024 * 1024, 0.02 * h.total_bytes);
  if (h.low_on_space && h.problem.empty()) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "%.0f bytes free of %.0f: jobs may fail to write their files; delete jobs to free space",
                  h.free_bytes, h.total_bytes);
    h.problem = options_.data.string() + ": " + buf;
  }
  return h;
}

JobRecord JobManager::check(const api::JobSpec& spec) const {
  std::vector<std::string> files = spec::file_references(spec);
  if (!files.empty()) {
    for (std::string& f : files)
      f += ": the server reads no files of the client's; give its content inline (`dem submit` inlines the files a "
           "spec names)";
    throw spec::SpecError(files);
  }
  JobRecord job;
  spec::SpecLimits limits;
  limits.max_memory_bytes = options_.max_job_memory_bytes;
  limits.memory_limit_name = "this server's limit for one job (--max-job-memory-mb)";
  // the checks of `dem validate`, the time step's included
  const Simulation sim(spec::to_scene(spec, "", limits));
  job.name = spec.name();
  job.tags.assign(spec.tags().begin(), spec.tags().end());
  job.length_unit = spec.outputs().length_unit().empty() ? "m" : spec.outputs().length_unit();
  job.particles = static_cast<std::int64_t>(sim.particles().size());
  job.total_steps = sim.total_steps();
  job.time_step = sim.dt();
  refuse_outputs_past_limit(sim);
  return job;
}

std::vector<std::string> JobManager::keys_beginning(const std::string& prefix) const {
  std::lock_guard lock(mutex_);
  std::vector<std::string> keys;
  for (auto it = by_key_.lower_bound(prefix); it != by_key_.end() && it->first.starts_with(prefix); ++it)
    keys.push_back(it->first);
  return keys;
}

JobManager::Submitted JobManager::submit(const api::JobSpec& spec, const std::string& idempotency_key) {
  const std::string bytes = spec.SerializeAsString();
  auto replay = [&]() -> std::optional<Submitted> {
    if (idempotency_key.empty()) return std::nullopt;
    const auto it = by_key_.find(idempotency_key);
    if (it == by_key_.end()) return std::nullopt;
    std::ifstream in(folder(it->second).spec(), std::ios::binary);
    const std::string earlier((std::istreambuf_iterator<char>(in)), {});
    return Submitted{jobs_.at(it->second), false, earlier != bytes};
  };
  {
    std::lock_guard lock(mutex_);
    if (auto earlier = replay()) return *earlier;
  }
  JobRecord job = check(spec);
  job.created_at = utc_now();
  job.idempotency_key = idempotency_key;

  std::lock_guard lock(mutex_);
  if (auto earlier = replay()) return *earlier;  // the same key submitted meanwhile
  store_->insert(job, [&](std::int64_t id) {
    const JobFolder f = folder(id);
    fs::remove_all(f.root);
    fs::create_directories(f.outputs());
    write_file_durably(f.spec(), bytes);
  });
  if (!idempotency_key.empty()) by_key_[idempotency_key] = job.id;
  jobs_[job.id] = job;
  changed_.notify_all();
  // after the row is committed: a folder without a row must still look like a submission cut short
  char line[200];
  std::snprintf(line, sizeof line, "queued: %lld particles, %lld steps of %.6g s",
                static_cast<long long>(job.particles), static_cast<long long>(job.total_steps), job.time_step);
  append_job_log(folder(job.id).log(), "submitted as \"" + job.name + "\"; " + line +
                                           (idempotency_key.empty() ? "" : "; Idempotency-Key " + idempotency_key));
  return {job, true};
}

std::optional<JobRecord> JobManager::get(std::int64_t id) const {
  std::lock_guard lock(mutex_);
  const auto it = jobs_.find(id);
  if (it == jobs_.end()) return std::nullopt;
  return it->second;
}

std::vector<JobRecord> JobManager::list() const {
  std::lock_guard lock(mutex_);
  std::vector<JobRecord> out;
  for (const auto& [id, job] : jobs_) out.push_back(job);
  return out;
}

std::map<std::string, int> JobManager::counts() const {
  std::lock_guard lock(mutex_);
  std::map<std::string, int> out;
  for (const auto& [id, job] : jobs_) ++out[to_string(job.state)];
  return out;
}

ActionResult JobManager::cancel(std::int64_t id) {
  std::unique_lock lock(mutex_);
  const auto it = jobs_.find(id);
  if (it == jobs_.end()) return {Outcome::NotFound, "no job " + std::to_string(id), {}};
  JobRecord& job = it->second;
  if (is_final(job.state))
    return {Outcome::Conflict, "job " + std::to_string(id) + " has already ended (" + to_string(job.state) + ")", job};
  if (job.state == JobState::Running) {
    append_job_log(folder(id).log(), "cancel requested: the run stops within a step");
    running_.at(id)->cancelled = true;
    running_.at(id)->stop = true;
    // the engine stops within a step; wait for it so that the answer shows the final state
    changed_.wait_for(lock, std::chrono::seconds(2), [&] { return jobs_.at(id).state != JobState::Running; });
    return {Outcome::Done, "", jobs_.at(id)};
  }
  append_job_log(folder(id).log(), std::string("cancelled on request (it was ") + to_string(job.state) + ")");
  JobRecord cancelled = job;  // the table first (on a full disk it catches up later: save)
  cancelled.state = JobState::Cancelled;
  cancelled.error = kCancelled;
  cancelled.finished_at = utc_now();
  cancelled.checkpoint_step = -1;
  save(cancelled);
  job = cancelled;
  std::error_code ignored;
  fs::remove(folder(id).checkpoint(), ignored);  // an interrupted job's, no longer needed
  changed_.notify_all();
  frames_.close(id, "job cancelled");
  return {Outcome::Done, "", job};
}

std::shared_ptr<FrameChannel> JobManager::frames_of(std::int64_t id, std::string& why) {
  std::lock_guard lock(mutex_);  // held while the channel is made: a job ending now closes it after
  const auto it = jobs_.find(id);
  if (it == jobs_.end()) {
    why = "no job " + std::to_string(id);
    return nullptr;
  }
  const JobState state = it->second.state;
  if (state != JobState::Queued && state != JobState::Running) {
    why = "job " + std::to_string(id) + " is " + to_string(state) +
          ": its frames are in its ANIMATION_3D.dat (a 2D run's: ANIMATION_2D.dat)";
    return nullptr;
  }
  return frames_.open(id);
}

ActionResult JobManager::resume(std::int64_t id) {
  std::lock_guard lock(mutex_);
  const auto it = jobs_.find(id);
  if (it == jobs_.end()) return {Outcome::NotFound, "no job " + std::to_string(id), {}};
  JobRecord& job = it->second;
  if (job.state != JobState::Interrupted)
    return {Outcome::Conflict,
            "job " + std::to_string(id) + " is " + to_string(job.state) + ": only an interrupted job can be resumed",
            job};
  JobRecord queued = job;
  queued.state = JobState::Queued;
  queued.error.clear();
  save(queued);
  const std::string from = job.checkpoint_step >= 0
                               ? "continue from the checkpoint at step " + std::to_string(job.checkpoint_step)
                               : std::string("start over (no checkpoint)");
  append_job_log(folder(id).log(), "resumed on request: queued again, to " + from);
  job = queued;
  changed_.notify_all();
  return {Outcome::Done, "", job};
}

ActionResult JobManager::remove(std::int64_t id) {
  std::lock_guard lock(mutex_);
  return remove_locked(id);
}

void JobManager::sweep() {
  std::unique_lock lock(mutex_);
  while (!stopping_) {
    std::vector<JobRecord> all;
    all.reserve(jobs_.size());
    for (const auto& [id, job] : jobs_) all.push_back(job);
    for (const std::int64_t id : jobs_past_retention(all, options_.retention, std::chrono::system_clock::now())) {
      const ActionResult r = remove_locked(id);
      if (r.outcome == Outcome::Done)
        spdlog::info("retention: deleted job {} ({}, finished {})", id, to_string(r.job.state), r.job.finished_at);
    }
    sweeper_wake_.wait_for(lock, options_.retention.sweep_interval(), [this] { return stopping_; });
  }
}

ActionResult JobManager::remove_locked(std::int64_t id) {
  const auto it = jobs_.find(id);
  if (it == jobs_.end()) return {Outcome::NotFound, "no job " + std::to_string(id), {}};
  if (it->second.state == JobState::Running)
    return {Outcome::Conflict, "job " + std::to_string(id) + " is running: cancel it first", it->second};
  JobRecord job = it->second;
  std::error_code ignored;
  try {
    store_->remove(id);  // first the row: a crash now leaves a folder that recovery moves aside
  } catch (const StoreError&) {
    // A full disk: the table's log cannot grow by the page the deletion needs. The job's files,
    // which the operator asked to go, go first and free the space; then the row (a crash between
    // leaves a row without files, which says so: better than a disk nobody can free through the API).
    fs::remove_all(folder(id).root, ignored);
    store_->remove(id);
  }
  fs::remove_all(folder(id).root, ignored);
  if (!job.idempotency_key.empty()) by_key_.erase(job.idempotency_key);
  jobs_.erase(it);
  frames_.close(id, "job deleted");
  save_unsaved();  // the space freed may let the table catch up
  return {Outcome::Done, "", job};
}

void JobManager::work() {
  for (;;) {
    JobRecord job;
    try {
      {
        std::unique_lock lock(mutex_);
        auto next = [&]() -> JobRecord* {
          for (auto& [id, j] : jobs_)
            if (j.state == JobState::Queued) return &j;
          return nullptr;
        };
        changed_.wait(lock, [&] { return stopping_ || next() != nullptr; });
        if (stopping_) return;
        JobRecord& chosen = *next();
        JobRecord running = chosen;
        running.state = JobState::Running;
        if (running.started_at.empty()) running.started_at = utc_now();
        save(running);
        chosen = running;
        running_[chosen.id] = std::make_shared<Running>();
        job = chosen;
      }
      run_one(job);
    } catch (const std::exception& e) {
      // the job table could not be written (disk full, the file gone): the worker goes on; the
      // job is failed in memory, and the table shows it as it last could
      spdlog::error("job {}: {}", job.id, e.what());
      if (job.id == 0) {  // not even picked: wait a moment rather than spin on the same failure
        std::this_thread::sleep_for(std::chrono::seconds(1));
        continue;
      }
      {
        std::lock_guard lock(mutex_);
        running_.erase(job.id);
        JobRecord& j = jobs_.at(job.id);
        j.state = JobState::Failed;
        j.error = e.what();
      }
      append_job_log(folder(job.id).log(), std::string("failed: ") + e.what());
      changed_.notify_all();
      frames_.close(job.id, "job failed");
    }
  }
}

void JobManager::run_one(const JobRecord& job) {
  const std::int64_t id = job.id;
  std::shared_ptr<Running> control;
  {
    std::lock_guard lock(mutex_);
    control = running_.at(id);
  }
  auto update = [&](auto&& change) {
    std::lock_guard lock(mutex_);
    change(jobs_.at(id));
  };
  auto last_saved = std::chrono::steady_clock::now();

  ExecutionHooks hooks;
  hooks.job = id;
  hooks.threads = threads_per_job();
  hooks.checkpoint_seconds = options_.checkpoint_seconds;
  hooks.max_frame_rate = options_.max_frame_rate;
  hooks.max_output_bytes = options_.max_output_bytes;
  hooks.stop = &control->stop;
  hooks.checkpoint_on_stop = &control->checkpoint_on_stop;
  hooks.frames = frames_.open(id);
  hooks.on_start = [&](const Simulation& sim) { update([&](JobRecord& j) { j.step = sim.step_count(); }); };
  hooks.on_progress = [&](const Progress& p) {
    update([&](JobRecord& j) {
      j.step = p.step;
      j.total_steps = p.total;  // a stage that ended early shortened the run
      j.stage = p.stage;
      j.steps_per_second = p.steps_per_second;
      j.seconds_left = p.seconds_left;
      const auto now = std::chrono::steady_clock::now();
      if (now - last_saved > std::chrono::seconds(5)) {  // the table needs the step only for the record
        save(j);
        last_saved = now;
      }
    });
  };
  hooks.on_checkpoint = [&](std::int64_t step) {
    update([&](JobRecord& j) {
      j.checkpoint_step = step;
      j.step = std::max(j.step, step);  // the table never shows a step before its checkpoint
      save(j);
    });
  };
  const ExecutionResult result = execute_job(folder(id), hooks);

  std::string archive_error;
  if (result.kind == ExecutionResult::Kind::Succeeded) {
    try {
      write_tar(folder(id).outputs().string(), folder(id).archive().string());
      append_job_log(folder(id).log(), std::string("outputs archived in ") + JobFolder::kArchiveName);
    } catch (const std::exception& e) {
      archive_error = std::string("the outputs could not be archived: ") + e.what();
    }
  }
  std::string frames_reason;
  {
    std::lock_guard lock(mutex_);
    JobRecord& j = jobs_.at(id);
    j.steps_per_second = 0;
    j.seconds_left = 0;
    j.run_seconds += result.run_seconds;
    j.stream_seconds += result.stream_seconds;
    if (!result.results.is_null()) {
      j.results = result.results;
      j.results["runSeconds"] = j.run_seconds;  // summed over the runs of a resumed job
    }
    switch (result.kind) {
      case ExecutionResult::Kind::Succeeded:
        j.state = archive_error.empty() ? JobState::Succeeded : JobState::Failed;
        j.error = archive_error;
        j.step = j.total_steps;
        break;
      case ExecutionResult::Kind::Failed:
        j.state = JobState::Failed;
        j.error = result.error;
        if (result.step >= 0) j.step = result.step;  // it may fail before its first progress report
        break;
      case ExecutionResult::Kind::Stopped:
        if (control->checkpoint_on_stop && !control->cancelled) {
          j.state = JobState::Queued;  // the server is shutting down: the job goes on after the restart
        } else {
          j.state = JobState::Cancelled;
          j.error = kCancelled;
        }
        break;
    }
    if (is_final(j.state)) {
      j.finished_at = utc_now();
      j.checkpoint_step = -1;
    }
    save(j);
    if (is_final(j.state)) {  // after the final state is saved: a crash between leaves a finished job
      std::error_code ignored;
      fs::remove(folder(id).checkpoint(), ignored);  // no longer needed; it can be as large as the scene
    }
    running_.erase(id);
    frames_reason = j.state == JobState::Queued ? "the server is shutting down; the job goes on after its restart"
                                                : std::string("job ") + to_string(j.state);
    std::string ended = to_string(j.state);  // "failed: why", "cancelled: cancelled on request", "succeeded"
    if (!j.error.empty()) ended += ": " + j.error;
    append_job_log(folder(id).log(), j.state == JobState::Queued ? "queued again: " + frames_reason : ended);
  }
  changed_.notify_all();
  frames_.close(id, frames_reason);
}

}  // namespace dem::server
