// A full disk under --data: health says so, the operator can still delete jobs (which frees the
// space), the server starts again on a full disk, and a job that fails on it is failed in the job
// table once there is room, not left `running`. The data folder is a small tmpfs of its own (the
// test needs root to mount it, as the test command runs; it is skipped otherwise).
#include <sys/mount.h>

#include <cerrno>
#include <cstring>

#include "support/server_test.hpp"

namespace dem::test {
namespace {

class ServerFullDisk : public ServerTest {
 protected:
  void SetUp() override {
    ServerTest::SetUp();
    data_ = dir_ / "data";
    fs::create_directories(data_);
    if (::mount("tmpfs", data_.c_str(), "tmpfs", 0, "size=6m") != 0)
      GTEST_SKIP() << "cannot mount a small tmpfs for the data folder (" << std::strerror(errno) << "): needs root";
    mounted_ = true;
  }
  void TearDown() override {
    server_.reset();
    if (mounted_) ::umount2(data_.c_str(), MNT_DETACH);
    ServerTest::TearDown();
  }

  // Fills the file system with one file until a write fails (ENOSPC).
  void fill_disk() {
    std::FILE* f = std::fopen((data_ / "filler").c_str(), "ab");
    ASSERT_NE(f, nullptr);
    std::setvbuf(f, nullptr, _IONBF, 0);
    const std::string block(4096, 'x');
    while (std::fwrite(block.data(), 1, block.size(), f) == block.size()) {
    }
    std::fclose(f);
  }

  nlohmann::json health() { return nlohmann::json::parse(client_->get("/api/health").body); }

  fs::path data_;
  bool mounted_ = false;
};

TEST_F(ServerFullDisk, HealthReportsTheStoreAndDeletingStillWorksAndFreesTheSpace) {
  start_server();
  const long id = submit_json(pouring_spec(0.015, 100, 50))["id"];
  wait_for(id, "succeeded");
  nlohmann::json h = health();
  EXPECT_EQ(h.value("status", ""), "ok") << h.dump();
  ASSERT_TRUE(h.contains("store")) << h.dump();
  EXPECT_GT(h["store"].value("freeBytes", 0.0), 1e6) << h.dump();

  fill_disk();
  h = health();
  EXPECT_EQ(h.value("status", ""), "degraded") << h.dump();
  EXPECT_LT(h["store"].value("freeBytes", 1e9), 65536) << h.dump();
  EXPECT_NE(h["store"].value("problem", ""), "") << h.dump();

  const client::Response r = client_->request("DELETE", "/api/jobs/" + std::to_string(id), "", "", {});
  EXPECT_EQ(r.status, 204) << r.body;
  EXPECT_FALSE(fs::exists(data_ / "jobs" / std::to_string(id)));
  EXPECT_EQ(client_->get("/api/jobs/" + std::to_string(id)).status, 404);
  // and it stays deleted across a restart (the row went, not only the folder)
  EXPECT_EQ(server_->stop(SIGTERM), 0);
  start_server();
  EXPECT_EQ(client_->get("/api/jobs/" + std::to_string(id)).status, 404);
}

TEST_F(ServerFullDisk, TheServerStartsOnAFullDiskAndSaysSo) {
  start_server();
  const long id = submit_json(pouring_spec(0.015, 100, 50))["id"];
  wait_for(id, "succeeded");
  EXPECT_EQ(server_->stop(SIGTERM), 0);
  fill_disk();
  start_server();  // throws when the server does not start
  const nlohmann::json h = health();
  EXPECT_EQ(h.value("status", ""), "degraded") << h.dump();
  EXPECT_EQ(job(id).value("state", ""), "succeeded");
  const client::Response r = client_->request("DELETE", "/api/jobs/" + std::to_string(id), "", "", {});
  EXPECT_EQ(r.status, 204) << r.body;
  // a submission on a full disk is refused as such (507), not as a server error
  fs::remove(data_ / "filler");
  fill_disk();
  const client::Response refused =
      client_->request("POST", "/api/jobs", pouring_spec(0.015, 100, 50), "application/json", {});
  EXPECT_EQ(refused.status, 507) << refused.body;
}

TEST_F(ServerFullDisk, AJobThatFailsOnAFullDiskIsFailedInTheTableOnceThereIsRoom) {
  start_server();
  const long keep = submit_json(pouring_spec(0.015, 100, 50))["id"];
  wait_for(keep, "succeeded");
  fill_disk();
  fs::resize_file(data_ / "filler", fs::file_size(data_ / "filler") - 256 * 1024);  // room for the spec, not the run
  const long id = submit_json(pouring_spec(0.012, 20000, 10, true))["id"];
  const nlohmann::json failed = wait_for(id, "failed");
  EXPECT_NE(failed.value("error", "").find("No space left"), std::string::npos) << failed.dump();
  // the operator frees space by deleting a job; the failed job's row catches up
  EXPECT_EQ(client_->request("DELETE", "/api/jobs/" + std::to_string(keep), "", "", {}).status, 204);
  EXPECT_EQ(server_->stop(SIGTERM), 0);
  fs::remove(data_ / "filler");
  start_server();
  EXPECT_EQ(job(id).value("state", ""), "failed") << job(id).dump();
}

// The disk stays full through a restart: the job table must still hold how the job ended (it came
// back "interrupted", the reason lost: an independent tester's finding). A little space is held in
// reserve for the table (DATA/space.reserve) and given up when the disk fills.
TEST_F(ServerFullDisk, AJobThatFailsOnAFullDiskKeepsItsReasonThroughARestartOnTheFullDisk) {
  start_server();
  EXPECT_TRUE(fs::exists(data_ / "space.reserve"));
  fill_disk();
  fs::resize_file(data_ / "filler", fs::file_size(data_ / "filler") - 256 * 1024);  // room for the spec, not the run
  const long id = submit_json(pouring_spec(0.012, 20000, 10, true))["id"];
  const nlohmann::json failed = wait_for(id, "failed");
  EXPECT_NE(failed.value("error", "").find("No space left"), std::string::npos) << failed.dump();
  EXPECT_EQ(server_->stop(SIGTERM), 0);
  fill_disk();  // whatever the reserve gave back is taken too
  start_server();
  const nlohmann::json after = job(id);
  EXPECT_EQ(after.value("state", ""), "failed") << after.dump();
  EXPECT_NE(after.value("error", "").find("No space left"), std::string::npos) << after.dump();
  // with room again, the reserve is taken back
  fs::remove(data_ / "filler");
  EXPECT_EQ(client_->request("DELETE", "/api/jobs/" + std::to_string(id), "", "", {}).status, 204);
  const long next = submit_json(pouring_spec(0.015, 100, 50))["id"];
  wait_for(next, "succeeded");
  EXPECT_TRUE(fs::exists(data_ / "space.reserve"));
}

}  // namespace
}  // namespace dem::test
