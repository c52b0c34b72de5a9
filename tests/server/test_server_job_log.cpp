// A job's own log (GET /api/v1/jobs/{id}/log): what happened to the job and what its run printed,
// as text with the time on each line; it grows while the job runs, says why a job failed, outlives
// a crash and a restart of the server, and its last lines come with ?tail=N.
#include <signal.h>

#include <regex>

#include "support/server_test.hpp"

namespace dem::test {
namespace {

class ServerJobLog : public ServerTest {
 protected:
  std::string log_path(long id) { return "/api/v1/jobs/" + std::to_string(id) + "/log"; }
  std::string log_of(long id, const std::string& query = "") {
    const client::Response r = client_->get(log_path(id) + query);
    EXPECT_EQ(r.status, 200) << r.body;
    EXPECT_EQ(r.header("content-type"), "text/plain; charset=utf-8");
    return r.body;
  }
  // Polls until the job's log holds `text` `times` times, at most a minute; the log then.
  std::string wait_for_log(long id, const std::string& text, std::size_t times = 1) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    std::string log;
    while (std::chrono::steady_clock::now() < end) {
      log = log_of(id);
      std::size_t seen = 0;
      for (std::size_t at = log.find(text); at != std::string::npos; at = log.find(text, at + 1)) ++seen;
      if (seen >= times) return log;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ADD_FAILURE() << "the log of job " << id << " has no " << times << " \"" << text << "\" after a minute:\n" << log;
    return log;
  }
  static std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }
  static bool has(const std::string& log, const std::string& text) { return log.find(text) != std::string::npos; }
};

// A job that runs for minutes unless stopped.
const std::string kEndlessSpec = pouring_spec(0.02, 5000000, 100000);

TEST_F(ServerJobLog, TheLogGrowsWhileTheJobRunsAndSaysHowItEnded) {
  start_server();
  const long id = submit_json(kEndlessSpec)["id"];
  EXPECT_EQ(job(id)["links"]["log"], log_path(id));
  wait_for(id, "running");
  const std::string running = wait_for_log(id, "progress: step ");
  EXPECT_TRUE(has(running, "submitted as \"pouring test\"; queued: ")) << running;
  EXPECT_TRUE(has(running, "run started: ")) << running;
  EXPECT_TRUE(has(running, " particles, 5 walls, 5000000 steps; dt = ")) << running;  // as dem run prints it
  const std::regex timed(R"(^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z  \S.*$)");
  for (const std::string& line : lines_of(running)) EXPECT_TRUE(std::regex_match(line, timed)) << line;

  ASSERT_EQ(client_->request("POST", "/api/v1/jobs/" + std::to_string(id) + "/cancel").status, 200);
  wait_for(id, "cancelled");
  const std::string ended = wait_for_log(id, "cancelled: cancelled on request");
  EXPECT_EQ(ended.rfind(running, 0), 0u) << "the log is only appended to:\n" << running << "\n---\n" << ended;
  EXPECT_TRUE(has(ended, "cancel requested")) << ended;
  EXPECT_TRUE(has(ended, "run stopped at step ")) << ended;
  // HEAD: the same headers, no body
  const client::Response head = client_->request("HEAD", log_path(id));
  EXPECT_EQ(head.status, 200);
  EXPECT_EQ(head.header("content-length"), std::to_string(ended.size()));
}

TEST_F(ServerJobLog, AFailedJobsLogSaysWhyAndASucceededOnesSaysItCompleted) {
  start_server({"--max-output-mb", "2"});
  // too many files for the limit (test_server_limits.cpp): stopped at a frame, failed
  std::string spec = pouring_spec(0.012, 3400, 100, true);
  spec.replace(spec.find(R"("forceChains": true)"), 19, R"("forceChains": true, "vtk": false)");
  const long failed = submit_json(spec)["id"];
  const long succeeded = submit_json(pouring_spec(0.02, 200, 100))["id"];
  ASSERT_EQ(wait_for(failed, "failed,succeeded")["state"], "failed");
  ASSERT_EQ(wait_for(succeeded, "failed,succeeded")["state"], "succeeded");
  const std::string why = log_of(failed);
  EXPECT_TRUE(has(why, "run failed at step ")) << why;
  EXPECT_TRUE(has(why, "--max-output-mb")) << why;
  EXPECT_TRUE(has(lines_of(why).back(), "failed: the job's files hold ")) << why;
  const std::string done = log_of(succeeded);
  EXPECT_TRUE(has(done, "run completed at step 200")) << done;
  EXPECT_TRUE(has(done, "progress: step 200/200 (100.0%)")) << done;  // the last progress line, always
  EXPECT_TRUE(has(done, "outputs archived in outputs.tar")) << done;
  EXPECT_TRUE(has(lines_of(done).back(), "  succeeded")) << done;
  // the log is the job's, beside its outputs: not an artifact, not in the archive
  const std::string artifacts = client_->get("/api/v1/jobs/" + std::to_string(succeeded) + "/artifacts").body;
  EXPECT_FALSE(has(artifacts, "job.log")) << artifacts;
}

TEST_F(ServerJobLog, TheLogOutlivesACrashAndARestartAndTellsThem) {
  start_server({"--checkpoint-seconds", "0"});
  const long id = submit_json(kEndlessSpec)["id"];
  wait_for_log(id, "checkpoint at step ");
  EXPECT_EQ(server_->stop(SIGKILL), 128 + SIGKILL);

  start_server({"--checkpoint-seconds", "0"});
  ASSERT_EQ(job(id)["state"], "interrupted");
  const std::string interrupted = log_of(id);
  EXPECT_TRUE(has(lines_of(interrupted).back(), "interrupted: the server stopped while the job ran")) << interrupted;
  ASSERT_EQ(client_->request("POST", "/api/v1/jobs/" + std::to_string(id) + "/resume").status, 200);
  std::string resumed = wait_for_log(id, "run resumed from the checkpoint at step ");
  EXPECT_TRUE(has(resumed, "resumed on request: queued again, to continue from the checkpoint at step ")) << resumed;
  EXPECT_EQ(resumed.rfind(interrupted, 0), 0u);

  // a clean stop (SIGTERM) checkpoints the job and queues it again; it goes on after the restart
  EXPECT_EQ(server_->stop(SIGTERM), 0);
  start_server({"--checkpoint-seconds", "0"});
  const std::string restarted = wait_for_log(id, "run resumed from the checkpoint at step ", 2);
  const std::size_t shutdown = restarted.find("queued again: the server is shutting down");
  ASSERT_NE(shutdown, std::string::npos) << restarted;
  EXPECT_NE(restarted.find("run resumed from the checkpoint at step ", shutdown), std::string::npos) << restarted;
  client_->request("POST", "/api/v1/jobs/" + std::to_string(id) + "/cancel");
  wait_for(id, "cancelled");
}

TEST_F(ServerJobLog, TailGivesTheLastLinesAndBadQueriesAndUnknownJobsAreRefused) {
  start_server();
  const long id = submit_json(pouring_spec(0.02, 200, 100))["id"];
  wait_for(id, "succeeded");
  const std::string whole = log_of(id);
  const std::vector<std::string> lines = lines_of(whole);
  ASSERT_GE(lines.size(), 5u) << whole;
  EXPECT_EQ(log_of(id, "?tail=1"), lines.back() + "\n");
  EXPECT_EQ(log_of(id, "?tail=2"), lines[lines.size() - 2] + "\n" + lines.back() + "\n");
  EXPECT_EQ(log_of(id, "?tail=10000"), whole);  // more than it has: all of it
  for (const auto& [query, says] : std::vector<std::pair<std::string, std::string>>{
           {"?tail=0", "tail=0: the number of lines must be a whole number from 1 to 10000"},
           {"?tail=-1", "tail=-1"},
           {"?tail=ten", "tail=ten"},
           {"?tail=10001", "tail=10001"},
           {"?tail=1&tail=2", "tail= is given more than once"},
           {"?lines=3", "\"lines\" is not a parameter of a job's log (tail)"}}) {
    const client::Response r = client_->get(log_path(id) + query);
    EXPECT_EQ(r.status, 400) << query;
    EXPECT_EQ(r.header("content-type"), "application/problem+json") << query;
    EXPECT_TRUE(has(nlohmann::json::parse(r.body).value("detail", ""), says)) << query << ": " << r.body;
  }
  const client::Response unknown = client_->get("/api/v1/jobs/999/log");
  EXPECT_EQ(unknown.status, 404);
  EXPECT_EQ(unknown.header("content-type"), "application/problem+json");
  EXPECT_EQ(client_->get("/api/v1/jobs/x/log").status, 404);
  EXPECT_EQ(client_->request("POST", log_path(id)).status, 405);
  EXPECT_EQ(client_->get("/api/jobs/" + std::to_string(id) + "/log").body, whole);  // the alias
  // a range of it, as of any file the server sends
  const client::Response part = client_->request("GET", log_path(id), "", "", {{"Range", "bytes=0-9"}});
  EXPECT_EQ(part.status, 206);
  EXPECT_EQ(part.body, whole.substr(0, 10));
}

}  // namespace
}  // namespace dem::test
