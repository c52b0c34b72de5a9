// A bounded load test on loopback: 50 clients polling and 20 viewers streaming while jobs run, in
// two rounds. No request may fail, and the server's memory after the second round must be that of
// the first (no leak per request or per viewer).
#include <atomic>
#include <thread>

#include "dem.pb.h"
#include "support/server_test.hpp"

namespace dem::test {
namespace {

class ServerLoad : public ServerTest {
 protected:
  struct Counts {
    std::atomic<long> polls{0}, frames{0}, errors{0};
  };

  // Runs three jobs under load; returns when all have succeeded.
  void round(Counts& counts) {
    std::vector<long> ids;
    for (int k = 0; k < 3; ++k) ids.push_back(submit_json(pouring_spec(0.008, 1500, 25))["id"]);
    std::atomic<bool> done{false};
    std::vector<std::thread> clients;
    for (int c = 0; c < 50; ++c)
      clients.emplace_back([&, c] {
        while (!done) {
          try {
            const client::Response r = client_->get(c % 2 ? "/api/jobs" : "/api/jobs/" + std::to_string(ids[c % 3]));
            if (r.status != 200) ++counts.errors;
            ++counts.polls;
          } catch (const std::exception&) {
            ++counts.errors;
          }
          std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
      });
    for (int v = 0; v < 20; ++v)
      clients.emplace_back([&, v] {
        for (long id : ids) {  // each viewer follows the jobs one after another
          if (v % 2 && id == ids.front()) continue;
          try {
            client::FrameStream stream(
                *client_, "/api/jobs/" + std::to_string(id) + "/frames" + (v % 4 == 0 ? "?forceChains=1" : ""));
            while (std::optional<std::string> bytes = stream.next()) {
              api::Frame frame;
              if (!frame.ParseFromString(*bytes) || frame.job() != id) ++counts.errors;
              ++counts.frames;
            }
          } catch (const std::exception&) {
            ++counts.errors;
          }
        }
      });
    for (long id : ids) EXPECT_EQ(wait_for(id, "succeeded,failed", 300)["state"], "succeeded");
    done = true;
    for (std::thread& t : clients) t.join();
  }
};

TEST_F(ServerLoad, FiftyPollersAndTwentyViewersWhileJobsRunWithoutErrorsOrLeaks) {
  start_server();
  const long start = server_->resident_kib();
  Counts first, second;
  round(first);
  const long after_first = server_->resident_kib();
  round(second);
  const long after_second = server_->resident_kib();
  std::printf(
      "server memory: %ld KiB at start, %ld after round 1 (%ld polls, %ld frames), %ld after round 2 (%ld polls, %ld "
      "frames)\n",
      start, after_first, first.polls.load(), first.frames.load(), after_second, second.polls.load(),
      second.frames.load());
  EXPECT_EQ(first.errors + second.errors, 0);
  EXPECT_GT(first.frames, 20 * 2);
  EXPECT_GT(second.polls, 50);
  EXPECT_LT(after_second - after_first, 4 * 1024) << "memory grew between two equal rounds";
}

}  // namespace
}  // namespace dem::test
