// A job's own log, DATA/jobs/ID/job.log (GET /api/v1/jobs/{id}/log): what happened to the job and
// what its run printed, a line each after the time (ISO 8601 UTC): submitted, started or resumed,
// progress, stages, checkpoints, the results' notes, how the run ended and why; cancel, resume,
// interruption and shutdown. It is only ever appended to, by one write() a line (O_APPEND), so the
// queue's threads and the job's own can write to it at once and a reader sees whole lines.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "sim/runner.hpp"

namespace dem::server {

// Appends "TIME  text" (each line of a text of several lines so). Never throws and never fails the
// job: a log that cannot be written (a full disk, a job folder deleted meanwhile, a link planted in
// place of the file) loses the line.
void append_job_log(const std::filesystem::path& log, std::string_view text) noexcept;

// The run's progress in the log: a line at most every 10 s and the last one (as `dem run` prints to
// a file), and a line when a staged run's stage changes.
class ProgressLog {
 public:
  explicit ProgressLog(std::filesystem::path log) : log_(std::move(log)) {}
  void report(const Progress& p);

 private:
  std::filesystem::path log_;
  std::chrono::steady_clock::time_point last_{};
  std::int64_t last_step_ = 0;
  bool reported_ = false;
  std::string stage_;
};

// The last `count` lines of the file, read from its end (a line still being written left out).
// Throws std::runtime_error when the file cannot be read.
std::string last_lines(const std::filesystem::path& path, std::size_t count);

}  // namespace dem::server
