// What one job may write: a spec whose frames alone would pass the server's output limit
// (--max-output-mb) is refused when submitted, naming the limit; a job whose files grow past it
// anyway (other files, longer lines than the estimate) is stopped and failed, naming it, with what
// it wrote kept. A 1 KB spec with a frame every step once wrote 1.1 GB in 5 s.
#include <atomic>
#include <chrono>
#include <thread>

#include "support/command.hpp"
#include "support/raw_http.hpp"
#include "support/server_test.hpp"

namespace dem::test {
namespace {

class ServerLimits : public ServerTest {
 protected:
  // dem-server started with `options`, which it must refuse: what it said (exit status not 0).
  std::string refused_start(const std::string& options) {
    const CommandResult r = run_command("timeout 20 " + std::string(DEM_BINARY_DIR) + "/dem-server --data " +
                                        shell_quoted(dir_ / "d") + " " + options);
    EXPECT_NE(r.exit_code, 0) << options;
    return r.output;
  }
};

TEST_F(ServerLimits, ASpecWhoseFramesPassTheOutputLimitIsRefused) {
  start_server({"--max-output-mb", "1"});
  // 486 spheres, a frame every step for 20,000 steps: 20,001 frames, about 1 GB of ANIMATION_3D.dat
  const client::Response r =
      client_->request("POST", "/api/jobs", pouring_spec(0.012, 20000, 1), "application/json", {});
  EXPECT_EQ(r.status, 400) << r.body;
  EXPECT_NE(r.body.find("--max-output-mb"), std::string::npos) << r.body;
  EXPECT_NE(r.body.find("outputs"), std::string::npos) << r.body;
}

TEST_F(ServerLimits, AJobWhoseFilesGrowPastTheLimitIsStoppedAndFailed) {
  start_server({"--max-output-mb", "2"});
  // 35 frames of 447 spheres: an estimate of 1.6 MB at 100 bytes a sphere, 2.3 MB of animation
  // written at about 150, and the force chains besides
  std::string spec = pouring_spec(0.012, 3400, 100, true);  // without ParaView's files (the next test's)
  spec.replace(spec.find(R"("forceChains": true)"), 19, R"("forceChains": true, "vtk": false)");
  const long id = submit_json(spec)["id"];
  const nlohmann::json j = wait_for(id, "failed,succeeded");
  EXPECT_EQ(j.value("state", ""), "failed") << j.dump();
  EXPECT_NE(j.value("error", "").find("--max-output-mb"), std::string::npos) << j.dump();
  // where it stopped and how long it ran, as for any failure (it said step 0, progress 0, no time)
  EXPECT_GT(j.value("step", 0L), 1000) << j.dump();
  EXPECT_GT(j.value("progress", 0.0), 0.3) << j.dump();
  EXPECT_GT(j.value("runSeconds", 0.0), 0.0) << j.dump();
  std::uintmax_t total = 0;
  for (const auto& f : fs::directory_iterator(dir_ / "data" / "jobs" / std::to_string(id) / "outputs"))
    total += f.file_size();
  EXPECT_GT(total, 2u << 20);
  EXPECT_LT(total, 3u << 20);  // stopped at the frame that passed it
  EXPECT_FALSE(read_bytes(dir_ / "data" / "jobs" / std::to_string(id) / "outputs" / "ANIMATION_3D.dat").empty());
}

// ParaView's files, on by default, count: the spec whose animation alone would pass is refused, and
// the message says how to leave them out.
TEST_F(ServerLimits, ParaViewsFilesCountInTheEstimateAndTheMessageSaysHowToLeaveThemOut) {
  start_server({"--max-output-mb", "2"});
  const client::Response r =
      client_->request("POST", "/api/jobs", pouring_spec(0.012, 3400, 100, true), "application/json", {});
  EXPECT_EQ(r.status, 400) << r.body;
  EXPECT_NE(r.body.find("outputs.vtk: false"), std::string::npos) << r.body;
}

// A 45-million-sphere lattice took 2.9 GB of the server's memory while it was checked, then failed
// with a 500 (bad_alloc): what a job would need is estimated from its count and refused first.
TEST_F(ServerLimits, ASpecNeedingMoreMemoryThanTheLimitIsRefusedBeforeItIsBuilt) {
  start_server({"--max-job-memory-mb", "100"});
  nlohmann::json spec = nlohmann::json::parse(pouring_spec(0.012, 100, 0));
  // 2 m / 0.02 m = 100 sites a side: a million spheres, about 1 GB to run
  spec["lattices"].push_back({{"kind", "CUBIC"},
                              {"min", {{"x", 10}, {"y", 0}, {"z", 0}}},
                              {"max", {{"x", 12}, {"y", 2}, {"z", 2}}},
                              {"radius", 0.01},
                              {"material", "granite"}});
  const auto start = std::chrono::steady_clock::now();
  const client::Response r = client_->request("POST", "/api/jobs", spec.dump(), "application/json", {});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.status, 400) << r.body;
  EXPECT_NE(r.body.find("--max-job-memory-mb"), std::string::npos) << r.body;
  EXPECT_NE(r.body.find("lattices[1]: would make"), std::string::npos) << r.body;
  EXPECT_LT(seconds, 1.0) << "nothing was built";
}

TEST_F(ServerLimits, TheLimitMustBeAPositiveSize) {
  const std::string said = refused_start("--max-output-mb 0");
  EXPECT_NE(said.find("--max-output-mb: must be"), std::string::npos) << said;
}

}  // namespace
}  // namespace dem::test

namespace dem::test {
namespace {

// A client that sends half a request and stalls (slowloris) is answered 408 once the request
// timeout passes, and the connection closes; an idle kept-alive connection closes without a word.
// Slow clients were cut only after 60 s, and 20,000 of them used up the file descriptors.
TEST_F(ServerLimits, AStalledRequestIsAnswered408AfterTheRequestTimeout) {
  start_server({"--request-timeout", "1"});
  RawConnection half(server_->port());
  ASSERT_TRUE(half.connected());
  half.send("GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\n");  // no blank line: the header never ends
  const auto start = std::chrono::steady_clock::now();
  bool timed_out = false;
  const std::string answer = half.receive(10, &timed_out);
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_FALSE(timed_out) << "the connection was not closed";
  EXPECT_EQ(answer.rfind("HTTP/1.1 408", 0), 0u) << answer;
  EXPECT_GT(waited, 0.8);
  EXPECT_LT(waited, 5);
  RawConnection idle(server_->port());
  EXPECT_EQ(idle.receive(10, &timed_out), "");
  EXPECT_FALSE(timed_out) << "an idle connection was kept past the request timeout";
}

// Past --max-connections-per-client connections from one address, the next is answered 503 with
// Retry-After and closed; once one of them closes, a new one is served.
TEST_F(ServerLimits, ConnectionsPastTheLimitAreAnswered503WithRetryAfter) {
  start_server({"--max-connections-per-client", "3"});
  std::vector<std::unique_ptr<RawConnection>> held;
  for (int k = 0; k < 3; ++k) {
    held.push_back(std::make_unique<RawConnection>(server_->port()));
    ASSERT_TRUE(held.back()->connected());
  }
  // a served request on each: the server has accepted all three
  for (auto& c : held) {
    c->send("GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
    EXPECT_EQ(c->receive(10, nullptr, "\r\n\r\n").rfind("HTTP/1.1 200", 0), 0u);
  }
  RawConnection fourth(server_->port());
  fourth.send("GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
  const std::string refused = fourth.receive(10);
  EXPECT_EQ(refused.rfind("HTTP/1.1 503", 0), 0u) << refused;
  EXPECT_NE(refused.find("Retry-After: 1"), std::string::npos) << refused;
  EXPECT_NE(refused.find("--max-connections-per-client"), std::string::npos) << refused;
  held.pop_back();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the server sees the close
  RawConnection again(server_->port());
  again.send("GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
  EXPECT_EQ(again.receive(10, nullptr, "\r\n\r\n").rfind("HTTP/1.1 200", 0), 0u);
}

TEST_F(ServerLimits, TheConnectionAndTimeoutLimitsMustBePositive) {
  for (const char* option : {"--request-timeout 0", "--max-connections 0", "--max-connections-per-client -1"}) {
    const std::string said = refused_start(option);
    EXPECT_NE(said.find("must be"), std::string::npos) << option << ": " << said;
  }
}

// A value past an option's upper bound is refused naming the bound (the message named only the
// lower one: "--max-body-mb 1e12 must be a size in MB, > 0").
TEST_F(ServerLimits, AnOptionPastItsUpperBoundNamesTheBound) {
  const std::pair<const char*, const char*> cases[] = {{"--max-body-mb 1e12", "at most 4096"},
                                                       {"--threads-per-job 100000", "from 0 to 1024"},
                                                       {"--max-connections 2000000", "from 1 to 1e6"}};
  for (const auto& [option, says] : cases) {
    const std::string said = refused_start(option);
    EXPECT_NE(said.find(says), std::string::npos) << option << ": " << said;
  }
}

}  // namespace
}  // namespace dem::test

namespace dem::test {
namespace {

// Checking a submission builds its simulation (the checks of dem validate): for a large scene that
// takes a while, and it must not hold the connections' threads. Two large submissions once held
// /api/health for 2.6 s.
TEST_F(ServerLimits, LargeSubmissionsBeingCheckedDoNotHoldOtherRequests) {
  start_server();
  const std::string big = pouring_spec(0.0012, 10, 10);  // about 450,000 spheres: a second or two to check
  std::vector<std::thread> submitters;
  std::atomic<int> created{0};
  for (int k = 0; k < 2; ++k)
    submitters.emplace_back([&] {
      client::HttpClient c(server_->url());
      if (c.request("POST", "/api/jobs", big, "application/json", {}).status == 201) ++created;
    });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // both are being checked now
  double slowest = 0;
  for (int k = 0; k < 10; ++k) {
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(client_->get("/api/health").status, 200);
    slowest = std::max(slowest, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  for (auto& t : submitters) t.join();
  EXPECT_EQ(created.load(), 2);
  std::printf("slowest /api/health while two large submissions were checked: %.3f s\n", slowest);
  EXPECT_LT(slowest, 0.25);
}

}  // namespace
}  // namespace dem::test
