#include "server/job.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>

namespace dem::server {

const char* to_string(JobState state) {
  switch (state) {
    case JobState::Queued:
      return "queued";
    case JobState::Running:
      return "running";
    case JobState::Succeeded:
      return "succeeded";
    case JobState::Failed:
      return "failed";
    case JobState::Cancelled:
      return "cancelled";
    case JobState::Interrupted:
      return "interrupted";
  }
  return "unknown";
}

std::optional<JobState> job_state_from(const std::string& text) {
  for (JobState s : {JobState::Queued, JobState::Running, JobState::Succeeded, JobState::Failed, JobState::Cancelled,
                     JobState::Interrupted})
    if (text == to_string(s)) return s;
  return std::nullopt;
}

bool is_final(JobState state) {
  return state == JobState::Succeeded || state == JobState::Failed || state == JobState::Cancelled;
}

double JobRecord::progress() const {
  if (state == JobState::Succeeded) return 1.0;
  if (total_steps <= 0) return 0.0;
  return std::min(1.0, static_cast<double>(step) / static_cast<double>(total_steps));
}

nlohmann::json to_json(const JobRecord& job) {  // dumped with invalid UTF-8 replaced (http_util.cpp)
  nlohmann::json j = {
      {"id", job.id},
      {"name", job.name},
      {"tags", job.tags},
      {"state", to_string(job.state)},
      {"progress", job.progress()},
      {"step", job.step},
      {"totalSteps", job.total_steps},
      {"timeStep", job.time_step},
      {"particles", job.particles},
      {"lengthUnit", job.length_unit},
      {"createdAt", job.created_at},
  };
  if (!job.started_at.empty()) j["startedAt"] = job.started_at;
  if (!job.finished_at.empty()) j["finishedAt"] = job.finished_at;
  if (job.state == JobState::Running) {
    j["stepsPerSecond"] = job.steps_per_second;
    j["secondsLeft"] = job.seconds_left;
    if (!job.stage.empty()) j["stage"] = job.stage;
  }
  if (!job.error.empty()) j["error"] = job.error;
  if (!job.idempotency_key.empty()) j["idempotencyKey"] = job.idempotency_key;
  j["resumable"] = job.state == JobState::Interrupted;
  if (job.checkpoint_step >= 0) j["checkpointStep"] = job.checkpoint_step;
  if (job.run_seconds > 0) {
    j["runSeconds"] = job.run_seconds;
    j["streamSeconds"] = job.stream_seconds;
  }
  if (!job.results.is_null()) j["results"] = job.results;
  const std::string self = std::string(kApiBase) + "/jobs/" + std::to_string(job.id);
  j["links"] = {{"self", self},
                {"results", self + "/results"},
                {"artifacts", self + "/artifacts"},
                {"frames", self + "/frames"},
                {"log", self + "/log"}};
  return j;
}

std::string utc_now() {
  using namespace std::chrono;
  const auto now = system_clock::now();
  const std::time_t t = system_clock::to_time_t(now);
  const long ms = static_cast<long>(duration_cast<milliseconds>(now.time_since_epoch()).count() % 1000);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[64];
  std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d.%03ldZ", tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday,
                tm.tm_hour, tm.tm_min, tm.tm_sec, ms);
  return text;
}

}  // namespace dem::server
