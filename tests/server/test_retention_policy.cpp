// The retention policy's choice of jobs (server/retention.hpp), without a server.
#include <gtest/gtest.h>

#include "server/retention.hpp"

namespace dem::server {
namespace {

JobRecord finished(std::int64_t id, JobState state, const std::string& at) {
  JobRecord j;
  j.id = id;
  j.state = state;
  j.finished_at = at;
  return j;
}

const auto kNow = *parse_utc("2026-12-03T12:00:00.000Z");

TEST(RetentionPolicy, ReadsTheServersOwnTimes) {
  const auto t = parse_utc("2026-11-22T07:40:01.250Z");
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(std::chrono::duration_cast<std::chrono::milliseconds>(t->time_since_epoch()).count() % 1000, 250);
  EXPECT_FALSE(parse_utc("").has_value());
  EXPECT_FALSE(parse_utc("2026-11-22 07:40:01").has_value());
  EXPECT_FALSE(parse_utc("2026-11-22T07:40:01.250Zjunk").has_value());
}

TEST(RetentionPolicy, DeletesFinishedJobsPastTheAgeAndNothingElse) {
  RetentionPolicy p;
  p.max_age_seconds = 3600;
  const std::vector<JobRecord> jobs = {
      finished(1, JobState::Succeeded, "2026-12-03T10:00:00.000Z"),    // 2 h ago
      finished(2, JobState::Failed, "2026-12-03T10:59:59.000Z"),       // 1 h 1 s ago
      finished(3, JobState::Cancelled, "2026-12-03T11:30:00.000Z"),    // 30 min ago
      finished(4, JobState::Interrupted, "2026-12-01T00:00:00.000Z"),  // not final: kept
      finished(5, JobState::Queued, ""),
      finished(6, JobState::Running, "")};
  EXPECT_EQ(jobs_past_retention(jobs, p, kNow), (std::vector<std::int64_t>{1, 2}));
}

TEST(RetentionPolicy, KeepsTheNewestFinishedJobsByTheirEndNotTheirId) {
  RetentionPolicy p;
  p.max_finished = 2;
  const std::vector<JobRecord> jobs = {
      finished(1, JobState::Succeeded, "2026-12-03T11:00:00.000Z"),  // resumed and finished last
      finished(2, JobState::Succeeded, "2026-12-03T09:00:00.000Z"),
      finished(3, JobState::Failed, "2026-12-03T10:00:00.000Z"), finished(4, JobState::Running, "")};
  EXPECT_EQ(jobs_past_retention(jobs, p, kNow), (std::vector<std::int64_t>{2}));
  p.max_finished = 3;
  EXPECT_TRUE(jobs_past_retention(jobs, p, kNow).empty());
}

TEST(RetentionPolicy, AnUnreadableEndCountsAsTheOldest) {
  RetentionPolicy p;
  p.max_finished = 1;
  const std::vector<JobRecord> jobs = {finished(1, JobState::Succeeded, "2026-12-03T11:00:00.000Z"),
                                       finished(2, JobState::Succeeded, "garbled")};
  EXPECT_EQ(jobs_past_retention(jobs, p, kNow), (std::vector<std::int64_t>{2}));
}

TEST(RetentionPolicy, NoPolicyDeletesNothing) {
  const std::vector<JobRecord> jobs = {finished(1, JobState::Succeeded, "2000-01-01T00:00:00.000Z")};
  EXPECT_FALSE(RetentionPolicy{}.active());
  EXPECT_TRUE(jobs_past_retention(jobs, RetentionPolicy{}, kNow).empty());
}

}  // namespace
}  // namespace dem::server
