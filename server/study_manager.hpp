// The server's parameter studies (/api/studies): a study (study/study_plan.hpp) becomes one job per
// run in the job queue; its record (DATA/studies/ID.json, written once, durably) keeps the study as
// posted and its jobs' ids. Its table and figure are made from the jobs' records when asked for.
#pragma once

#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "server/job_manager.hpp"
#include "study/study_table.hpp"

namespace dem::server {

struct StudyRecord {
  std::int64_t id = 0;
  std::string name;
  std::string created_at;
  nlohmann::json study;            // as posted (its base inline)
  std::vector<std::int64_t> jobs;  // per run; -1: a run that could not be queued when a crash was mended
  std::string idempotency_key;
  // false from the record's first write until every run is queued: a server that died in between
  // queues the rest when it starts again (each run's job has the key "study ID run K")
  bool complete = false;
};

class StudyManager {
 public:
  // The idempotency keys of a study's runs ("study ID run K") begin so; clients may not use them.
  static constexpr const char* kRunKeyPrefix = "study ";

  // Reads the studies of the data folder; throws std::runtime_error naming a record it cannot read.
  StudyManager(const std::filesystem::path& data, JobManager& jobs);

  // Plans the study, checks every run's spec as a submission is checked, then queues them all.
  // Throws study::StudyError listing every problem, each naming the run and its values; nothing is
  // queued then. With an idempotency key already used, returns that study (created = false), or,
  // when it was another study, says so (conflict = true).
  struct Created {
    StudyRecord study;
    bool created = true;
    bool conflict = false;
    bool being_made = false;  // another request with its key is still checking and queueing its runs
  };
  Created create(const nlohmann::json& study, const std::string& idempotency_key = "");
  std::vector<StudyRecord> list() const;
  std::optional<StudyRecord> get(std::int64_t id) const;

  // The study with each job's state and progress, counts per state, and whether all have ended.
  nlohmann::json describe(const StudyRecord& study) const;
  // Cancels every job that has not ended / resumes every interrupted one.
  void cancel(const StudyRecord& study);
  void resume(const StudyRecord& study);

  // The plan (from the stored study) and a row per run from its job's record.
  study::StudyPlan plan(const StudyRecord& study) const;
  std::vector<study::StudyRow> rows(const StudyRecord& study, const study::StudyPlan& plan) const;

 private:
  // rows(), also keeping each row's job record as read for it (nullopt where there is none).
  std::vector<study::StudyRow> rows(const StudyRecord& study, const study::StudyPlan& plan,
                                    std::vector<std::optional<JobRecord>>* snapshots) const;
  std::filesystem::path folder_;  // DATA/studies
  JobManager& jobs_;
  mutable std::mutex mutex_;
  void save(const StudyRecord& study) const;  // written whole, durably
  void queue_runs(StudyRecord& study) const;  // queues each run not queued yet (idempotent per run)

  std::vector<StudyRecord> studies_;
  std::set<std::string> keys_being_made_;  // of requests still checking and queueing their runs
  std::int64_t next_id_ = 1;
};

}  // namespace dem::server
