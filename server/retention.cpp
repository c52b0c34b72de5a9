#include "server/retention.hpp"

#include <algorithm>
#include <cstdio>
#include <ctime>

namespace dem::server {

std::chrono::milliseconds RetentionPolicy::sweep_interval() const {
  double seconds = 60;
  if (max_age_seconds > 0) seconds = std::clamp(max_age_seconds / 10, 0.5, 60.0);
  if (max_finished > 0) seconds = std::min(seconds, 1.0);  // a count is cheap to keep
  return std::chrono::milliseconds(static_cast<long long>(seconds * 1000));
}

std::optional<std::chrono::system_clock::time_point> parse_utc(const std::string& text) {
  std::tm t{};
  int millis = 0, used = 0;
  if (std::sscanf(text.c_str(), "%4d-%2d-%2dT%2d:%2d:%2d.%3dZ%n", &t.tm_year, &t.tm_mon, &t.tm_mday, &t.tm_hour,
                  &t.tm_min, &t.tm_sec, &millis, &used) != 7 ||
      used != static_cast<int>(text.size()))
    return std::nullopt;
  t.tm_year -= 1900;
  t.tm_mon -= 1;
  const std::time_t seconds = timegm(&t);
  if (seconds == static_cast<std::time_t>(-1)) return std::nullopt;
  return std::chrono::system_clock::from_time_t(seconds) + std::chrono::milliseconds(millis);
}

std::vector<std::int64_t> jobs_past_retention(const std::vector<JobRecord>& jobs, const RetentionPolicy& policy,
                                              std::chrono::system_clock::time_point now) {
  struct Finished {
    std::chrono::system_clock::time_point at;
    std::int64_t id;
  };
  std::vector<Finished> finished;
  for (const JobRecord& j : jobs)
    if (is_final(j.state))
      finished.push_back({parse_utc(j.finished_at).value_or(std::chrono::system_clock::time_point{}), j.id});
  // oldest first; the same end time (to the millisecond): the older id first
  std::sort(finished.begin(), finished.end(),
            [](const Finished& a, const Finished& b) { return a.at != b.at ? a.at < b.at : a.id < b.id; });
  std::vector<std::int64_t> out;
  const std::size_t over =
      policy.max_finished > 0 && finished.size() > policy.max_finished ? finished.size() - policy.max_finished : 0;
  for (std::size_t k = 0; k < finished.size(); ++k) {
    const double age = std::chrono::duration<double>(now - finished[k].at).count();
    if (k < over || (policy.max_age_seconds > 0 && age > policy.max_age_seconds)) out.push_back(finished[k].id);
  }
  return out;
}

}  // namespace dem::server
