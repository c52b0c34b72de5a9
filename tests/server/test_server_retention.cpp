// The retention policy for finished jobs: with --keep-finished-days, a job that succeeded, failed or
// was cancelled longer ago than that is deleted with its files; with --keep-finished-jobs, only the
// newest that many finished jobs are kept. Queued, running and interrupted jobs are never touched.
// Without either option nothing is deleted (the default).
#include <thread>

#include "support/server_test.hpp"

namespace dem::test {
namespace {

class ServerRetention : public ServerTest {
 protected:
  fs::path folder_of(long id) { return dir_ / "data" / "jobs" / std::to_string(id); }

  // Polls until GET /api/jobs/{id} answers 404, at most `seconds`.
  bool gone_within(long id, double seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      if (client_->get("/api/jobs/" + std::to_string(id)).status == 404) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return false;
  }

  std::string refusal_of(const std::vector<std::string>& args) {
    std::string command = std::string(DEM_BINARY_DIR) + "/dem-server --data '" + (dir_ / "d").string() + "'";
    for (const std::string& a : args) command += " " + a;
    std::FILE* p = popen((command + " 2>&1").c_str(), "r");
    char buf[2048] = {};
    const std::size_t got = std::fread(buf, 1, sizeof buf - 1, p);
    EXPECT_NE(pclose(p), 0) << command;
    return std::string(buf, got);
  }
};

TEST_F(ServerRetention, AFinishedJobPastTheAgeIsDeletedWithItsFilesAndARunningOneIsKept) {
  start_server({"--keep-finished-days", "0.00004"});  // 3.5 s
  const long done = submit_json(pouring_spec(0.02, 20, 10))["id"];
  wait_for(done, "succeeded");
  ASSERT_TRUE(fs::exists(folder_of(done)));
  const long running = submit_json(pouring_spec(0.02, 5000000, 100000))["id"];
  wait_for(running, "running");
  EXPECT_EQ(client_->get("/api/jobs/" + std::to_string(done)).status, 200);  // not yet old enough
  EXPECT_TRUE(gone_within(done, 20)) << "a job finished 3.5 s ago was kept";
  EXPECT_FALSE(fs::exists(folder_of(done)));
  EXPECT_EQ(job(running).value("state", ""), "running");
  EXPECT_TRUE(fs::exists(folder_of(running)));
  EXPECT_EQ(client_->request("POST", "/api/jobs/" + std::to_string(running) + "/cancel", "", "", {}).status, 200);
  wait_for(running, "cancelled");
  EXPECT_TRUE(gone_within(running, 20)) << "a cancelled job was kept past the age";
}

TEST_F(ServerRetention, OnlyTheNewestFinishedJobsAreKeptPastTheCount) {
  start_server({"--keep-finished-jobs", "2"});
  std::vector<long> ids;
  for (int k = 0; k < 3; ++k) {
    ids.push_back(submit_json(pouring_spec(0.02, 20, 10))["id"]);
    wait_for(ids.back(), "succeeded");
  }
  EXPECT_TRUE(gone_within(ids[0], 20)) << "the oldest of three finished jobs was kept";
  EXPECT_FALSE(fs::exists(folder_of(ids[0])));
  for (int k = 1; k < 3; ++k) {
    EXPECT_EQ(job(ids[k]).value("state", ""), "succeeded");
    EXPECT_TRUE(fs::exists(folder_of(ids[k])));
  }
}

TEST_F(ServerRetention, WithoutAPolicyNothingIsDeleted) {
  start_server();
  const long id = submit_json(pouring_spec(0.02, 20, 10))["id"];
  wait_for(id, "succeeded");
  std::this_thread::sleep_for(std::chrono::seconds(2));
  EXPECT_EQ(job(id).value("state", ""), "succeeded");
  EXPECT_TRUE(fs::exists(folder_of(id)));
}

TEST_F(ServerRetention, APolicyMustBeAPositiveAgeOrAWholeCount) {
  EXPECT_NE(refusal_of({"--keep-finished-days", "-1"}).find("--keep-finished-days: must be"), std::string::npos);
  EXPECT_NE(refusal_of({"--keep-finished-days", "0"}).find("--keep-finished-days: must be"), std::string::npos);
  EXPECT_NE(refusal_of({"--keep-finished-jobs", "1.5"}).find("--keep-finished-jobs: must be"), std::string::npos);
  EXPECT_NE(refusal_of({"--keep-finished-jobs", "0"}).find("--keep-finished-jobs: must be"), std::string::npos);
  // decimal only: std::stod alone took 0x10 as 16 (an independent tester's finding)
  EXPECT_NE(refusal_of({"--keep-finished-jobs", "0x10"}).find("--keep-finished-jobs: must be"), std::string::npos);
  EXPECT_NE(refusal_of({"--keep-finished-days", "1e9"}).find("at most 1e6"), std::string::npos);
}

}  // namespace
}  // namespace dem::test
