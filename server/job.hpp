// A job of the server: its record in the job table and how it is shown over REST.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace dem::server {

// interrupted: it was running when the server died; it can be resumed from its last checkpoint.
// Where the API's links point: its versioned path (/api/ is an alias of it).
inline constexpr const char* kApiBase = "/api/v1";

enum class JobState { Queued, Running, Succeeded, Failed, Cancelled, Interrupted };

const char* to_string(JobState state);
std::optional<JobState> job_state_from(const std::string& text);
bool is_final(JobState state);  // succeeded, failed or cancelled: nothing more will happen to it

struct JobRecord {
  std::int64_t id = 0;
  std::string name;
  std::vector<std::string> tags;  // the spec's, to find it by (GET /api/v1/jobs?tag=)
  JobState state = JobState::Queued;
  std::string created_at, started_at, finished_at;  // ISO 8601 UTC; empty until it happens
  std::string error;                                // why it failed or was interrupted
  std::string idempotency_key;
  std::string length_unit = "m";  // of the legacy files: "m", "cm" or "mm" (outputs.lengthUnit)
  std::int64_t particles = 0;
  std::int64_t step = 0;
  std::int64_t total_steps = 0;
  double time_step = 0;               // s
  double steps_per_second = 0;        // while running
  double seconds_left = 0;            // while running
  std::string stage;                  // while running: a staged run's stage (not kept in the job table)
  std::int64_t checkpoint_step = -1;  // step of the last checkpoint; -1: none
  double run_seconds = 0;             // wall time of its stepping (summed over resumed runs)
  double stream_seconds = 0;          // of which the engine spent making live frames
  nlohmann::json results;             // what the run found (results.json), once it ended; null before

  double progress() const;
};

nlohmann::json to_json(const JobRecord& job);

// Now, as ISO 8601 UTC with milliseconds ("2026-11-22T07:40:01.250Z").
std::string utc_now();

}  // namespace dem::server
