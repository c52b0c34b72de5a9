// The retention policy for finished jobs (--keep-finished-days, --keep-finished-jobs): which jobs
// that succeeded, failed or were cancelled are old enough, or beyond the newest N, to be deleted
// with their files. Queued, running and interrupted jobs are never chosen. No policy: none.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "server/job.hpp"

namespace dem::server {

struct RetentionPolicy {
  double max_age_seconds = 0;    // 0: no age limit
  std::size_t max_finished = 0;  // 0: no count limit
  bool active() const { return max_age_seconds > 0 || max_finished > 0; }
  // How often the server applies it: often enough that a job outlives its age by a tenth at most.
  std::chrono::milliseconds sweep_interval() const;
};

// The finished jobs the policy deletes at `now`, oldest first. A finished job whose end time cannot
// be read counts as the oldest (its row was written by this server, so that should not happen).
std::vector<std::int64_t> jobs_past_retention(const std::vector<JobRecord>& jobs, const RetentionPolicy& policy,
                                              std::chrono::system_clock::time_point now);

// "2026-11-22T07:40:01.250Z" (utc_now's form) as a time point; nothing for any other text.
std::optional<std::chrono::system_clock::time_point> parse_utc(const std::string& text);

}  // namespace dem::server
