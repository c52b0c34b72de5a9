// What one job may write: a spec whose frames alone would pass the server's output limit
// (--max-output-mb) is refused when submitted, naming the limit; a job whose files grow past it
// anyway (other files, longer lines than the estimate) is stopped and failed, naming it, with what
// it wrote kept. A 1 KB spec with a frame every step once wrote 1.1 GB in 5 s.
#include "support/server_test.hpp"

namespace dem::test {
namespace {

class ServerLimits : public ServerTest {};

TEST_F(ServerLimits, ASpecWhoseFramesPassTheOutputLimitIsRefused) {
  start_server({"--max-output-mb", "1"});
  // 486 spheres, a frame every step for 20,000 steps: 20,001 frames, about 1 GB of ANIMATION_3D.dat
  const client::Response r = client_->request("POST", "/api/jobs", pouring_spec(0.012, 20000, 1), "application/json", {});
  EXPECT_EQ(r.status, 400) << r.body;
  EXPECT_NE(r.body.find("--max-output-mb"), std::string::npos) << r.body;
  EXPECT_NE(r.body.find("outputs"), std::string::npos) << r.body;
}

TEST_F(ServerLimits, AJobWhoseFilesGrowPastTheLimitIsStoppedAndFailed) {
  start_server({"--max-output-mb", "2"});
  // 35 frames of 447 spheres: an estimate of 1.6 MB at 100 bytes a sphere, 2.3 MB of animation
  // written at about 150, and the force chains besides
  const long id = submit_json(pouring_spec(0.012, 3400, 100, true))["id"];
  const nlohmann::json j = wait_for(id, "failed,succeeded");
  EXPECT_EQ(j.value("state", ""), "failed") << j.dump();
  EXPECT_NE(j.value("error", "").find("--max-output-mb"), std::string::npos) << j.dump();
  std::uintmax_t total = 0;
  for (const auto& f : fs::directory_iterator(dir_ / "data" / "jobs" / std::to_string(id) / "outputs")) total += f.file_size();
  EXPECT_GT(total, 2u << 20);
  EXPECT_LT(total, 3u << 20);  // stopped at the frame that passed it
  EXPECT_FALSE(read_bytes(dir_ / "data" / "jobs" / std::to_string(id) / "outputs" / "ANIMATION_3D.dat").empty());
}

TEST_F(ServerLimits, TheLimitMustBeAPositiveSize) {
  const std::string command = std::string(DEM_BINARY_DIR) + "/dem-server --data '" + (dir_ / "d").string() +
                              "' --max-output-mb 0 2>&1";
  std::FILE* p = popen(command.c_str(), "r");
  char buf[512] = {};
  const std::size_t got = std::fread(buf, 1, sizeof buf - 1, p);
  const int status = pclose(p);
  EXPECT_NE(status, 0);
  EXPECT_NE(std::string(buf, got).find("--max-output-mb must be"), std::string::npos) << std::string(buf, got);
}

}  // namespace
}  // namespace dem::test
