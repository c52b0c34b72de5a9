// The server's parameter studies (/api/studies): a study (study/study_plan.hpp) becomes one job per
// run in the job queue; its record (DATA/studies/ID.json, written once, durably) keeps the study as
// posted and its jobs' ids. Its table and figure are made from the jobs' records when asked for.
#pragma once

#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
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
  nlohmann::json study;  // as posted (its base inline)
  std::vector<std::int64_t> jobs;
};

class StudyManager {
 public:
  // Reads the studies of the data folder; throws std::runtime_error naming a record it cannot read.
  StudyManager(const std::filesystem::path& data, JobManager& jobs);

  // Plans the study, checks every run's spec as a submission is checked, then queues them all (or,
  // when one cannot be queued, none: those queued already are cancelled). Throws study::StudyError
  // listing every problem, each naming the run and its values.
  StudyRecord create(const nlohmann::json& study);
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
  std::filesystem::path folder_;  // DATA/studies
  JobManager& jobs_;
  mutable std::mutex mutex_;
  std::vector<StudyRecord> studies_;
  std::int64_t next_id_ = 1;
};

}  // namespace dem::server
