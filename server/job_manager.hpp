// The job queue: takes submissions, keeps the job table (job_store.hpp) and runs a set number of
// jobs at once on worker threads, oldest first. After a crash, jobs that were running are marked
// interrupted and can be resumed from their checkpoints.
#pragma once

#include <atomic>
#include <condition_variable>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "dem.pb.h"
#include "server/frame_hub.hpp"
#include "server/job.hpp"
#include "server/job_folder.hpp"
#include "server/job_store.hpp"
#include "server/retention.hpp"
#include "server/space_reserve.hpp"

namespace dem {
class Simulation;
}

namespace dem::server {

struct ManagerOptions {
  std::filesystem::path data;  // the data folder: jobs.db and jobs/
  int concurrency = 1;         // jobs running at once
  int threads_per_job = 0;     // 0: the cores divided among the running jobs
  double checkpoint_seconds = 10;
  double max_frame_rate = 30;                       // live frames a second per job; 0: every output frame
  double max_output_bytes = 10000.0 * 1024 * 1024;  // what one job's files may hold (--max-output-mb)
  double max_job_memory_bytes = 0;  // a spec needing more (estimated before it is built) is refused; 0: none
  RetentionPolicy retention;        // finished jobs deleted by age or count; none by default
};

// What a request on a job came to.
enum class Outcome { Done, NotFound, Conflict };

struct ActionResult {
  Outcome outcome = Outcome::Done;
  std::string message;  // why not, for NotFound and Conflict
  JobRecord job;
};

class JobManager {
 public:
  JobManager(ManagerOptions options, FrameHub& frames);  // opens the table, recovers; throws StoreError
  ~JobManager();
  void start();     // the worker threads (and the retention sweeper, with a policy)
  void shutdown();  // stops taking jobs; running ones are checkpointed and queued again

  // Checks the spec as `dem validate` does (throws spec::SpecError or SceneError) and queues it.
  // With an idempotency key already seen, returns that job instead (created = false), or, when
  // that job's spec was another, says so (conflict = true) and queues nothing.
  struct Submitted {
    JobRecord job;
    bool created = true;
    bool conflict = false;
  };
  Submitted submit(const api::JobSpec& spec, const std::string& idempotency_key);
  // The checks of submit, queueing nothing: no file named (the server reads no files of the
  // client's), dem validate's checks, this server's limits. Throws as submit does; returns the
  // record the job would have.
  JobRecord check(const api::JobSpec& spec) const;

  // The idempotency keys of the jobs kept that begin with `prefix` (a study's run keys).
  std::vector<std::string> keys_beginning(const std::string& prefix) const;

  std::optional<JobRecord> get(std::int64_t id) const;
  std::vector<JobRecord> list() const;
  ActionResult cancel(std::int64_t id);
  ActionResult resume(std::int64_t id);
  ActionResult remove(std::int64_t id);

  // The frames of a queued or running job; null (and `why`) for a job that will send none.
  std::shared_ptr<FrameChannel> frames_of(std::int64_t id, std::string& why);

  JobFolder folder(std::int64_t id) const { return JobFolder(options_.data, id); }
  std::map<std::string, int> counts() const;  // jobs per state

  // The data folder's file system and the table's state: `problem` is empty when all is well, else
  // why not (the last failed write of the table, or too little space left).
  struct StoreHealth {
    double free_bytes = 0, total_bytes = 0;
    std::size_t unsaved_jobs = 0;  // jobs whose latest state the table does not hold yet
    bool low_on_space = false;     // less than min(64 MiB, 2% of the file system) free
    std::string problem;
  };
  StoreHealth store_health() const;

 private:
  struct Running {
    std::atomic<bool> stop{false};
    std::atomic<bool> cancelled{false};  // by a request: wins over a shutdown
    std::atomic<bool> checkpoint_on_stop{false};
  };

  void recover();
  void work();
  void run_one(const JobRecord& job);
  // Into the table; the caller holds mutex_. Never throws: a row that cannot be written (a full
  // disk) is kept in memory, listed in unsaved_, and written with the next write that succeeds.
  void save(const JobRecord& job);
  void update_row(const JobRecord& job);        // throws when the table cannot be written even from the reserve
  void save_unsaved();                          // the caller holds mutex_
  ActionResult remove_locked(std::int64_t id);  // the caller holds mutex_
  void sweep();                                 // applies the retention policy, until shutdown
  void refuse_outputs_past_limit(const Simulation& sim) const;  // throws spec::SpecError
  int threads_per_job() const;

  ManagerOptions options_;
  FrameHub& frames_;
  std::unique_ptr<JobStore> store_;
  std::unique_ptr<SpaceReserve> reserve_;  // given up for the table when the disk fills
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::map<std::int64_t, JobRecord> jobs_;
  std::map<std::string, std::int64_t> by_key_;
  std::map<std::int64_t, std::shared_ptr<Running>> running_;
  std::vector<std::thread> workers_;
  std::thread sweeper_;
  std::condition_variable sweeper_wake_;  // at shutdown
  bool stopping_ = false;
  std::set<std::int64_t> unsaved_;  // jobs whose last save failed
  std::string store_problem_;       // why, while any is unsaved
};

}  // namespace dem::server
