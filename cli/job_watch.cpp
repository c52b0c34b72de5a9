#include "cli/job_watch.hpp"

#include "cli/terminal_text.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <thread>

#include "cli/progress_bar.hpp"

namespace dem::cli {
namespace {

Progress progress_of(const nlohmann::json& job) {
  return Progress{job.value("step", std::int64_t{0}), job.value("totalSteps", std::int64_t{0}),
                  job.value("stepsPerSecond", 0.0), job.value("secondsLeft", 0.0), job.value("stage", std::string())};
}

bool has_ended(const std::string& state) { return state != "queued" && state != "running"; }

}  // namespace

const nlohmann::json& checked_job(const nlohmann::json& job) {
  if (!job.is_object() || !job.contains("id") || !job["id"].is_number_integer() || !job.contains("state") ||
      !job["state"].is_string())
    throw std::runtime_error("the server's answer is not of dem-server's form (not a job with an id and a state)");
  return job;
}

std::string job_summary(const nlohmann::json& job) {
  const std::string state = job.value("state", "unknown");
  const std::string name = job.value("name", "");
  const Progress p = progress_of(job);
  const auto step = static_cast<long long>(p.step), total = static_cast<long long>(p.total);
  const long long particles = job.value("particles", 0LL);
  std::string text = "job " + std::to_string(job.value("id", 0LL));
  if (!name.empty()) text += " \"" + name + "\"";
  text += ": " + state;
  char buf[256];
  if (state == "running") {
    std::snprintf(buf, sizeof buf, " %.1f%% (step %lld/%lld, %.0f steps/s, %s left)", 100 * job.value("progress", 0.0),
                  step, total, p.steps_per_second, clock_text(p.seconds_left).c_str());
    text += buf;
  } else if (state == "queued") {
    std::snprintf(buf, sizeof buf, " (%lld particles, %lld steps)", particles, total);
    text += buf;
  } else if (state == "succeeded") {
    std::snprintf(buf, sizeof buf, " (%lld steps, %lld particles)", total, particles);
    text += buf;
    if (job.contains("finishedAt")) text += ", finished " + job.value("finishedAt", "");
  } else {
    std::snprintf(buf, sizeof buf, " at step %lld/%lld", step, total);
    text += buf;
    const std::string error = job.value("error", "");
    if (!error.empty() && error != state) text += ": " + error;
    if (job.value("resumable", false))
      text += " (dem resume " + std::to_string(job.value("id", 0LL)) + " continues it)";
  }
  return printable(text);  // the name and the error are the server's (and the submitter's) text
}

int watch_job(const ServerApi& api, std::int64_t id, const std::string& verb, WatchOutput output) {
  const bool quiet = output == WatchOutput::quiet;
  const bool terminal = isatty(STDERR_FILENO) == 1;
  std::function<void(const Progress&)> show;
  if (!quiet) show = make_progress_printer(terminal);
  const std::string target = job_target(id);
  std::string last_state;
  std::int64_t shown = -1;  // the last step given to the printer
  double rate = 0;
  nlohmann::json job;
  for (;;) {
    job = checked_job(api.call("GET", target));
    const std::string state = job.value("state", "");
    if (has_ended(state)) break;
    if (show && state == "queued" && last_state != "queued")
      std::fprintf(stderr, "job %lld: queued\n", static_cast<long long>(id));
    if (show && state == "running") {
      const Progress p = progress_of(job);
      show(p);
      shown = p.step;
      rate = p.steps_per_second;
    }
    last_state = state;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  const Progress last = progress_of(job);
  if (show && shown >= 0 && shown < last.total) {
    // the printer closes its line (and logs its last line) only at the last step
    if (job.value("state", "") == "succeeded")
      show(Progress{last.total, last.total, rate, 0, last.stage});
    else if (terminal)
      std::fputc('\n', stderr);
  }
  if (output == WatchOutput::json) print_json_line(job);
  if (job.value("state", "") == "succeeded") {
    if (output == WatchOutput::lines) std::printf("%s\n", job_summary(job).c_str());
    return 0;
  }
  std::fprintf(stderr, "dem %s: %s\n", verb.c_str(), job_summary(job).c_str());
  return 1;
}

}  // namespace dem::cli
