// How much live viewers slow a job down: the same spec run through dem-server alternately without
// viewers and with N WebSocket viewers (half of them asking for force chains), in pairs; prints
// each pair's job durations and their ratio. The job's duration is finishedAt - startedAt.
//
// usage: bench_stream_overhead --server URL --spec SPEC.json [--viewers N] [--pairs K]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "client/http_client.hpp"

namespace {

using dem::client::FrameStream;
using dem::client::HttpClient;

// Seconds since the epoch of "YYYY-MM-DDTHH:MM:SS.mmmZ".
double seconds_of(const std::string& iso) {
  std::tm tm{};
  int ms = 0;
  std::sscanf(iso.c_str(), "%d-%d-%dT%d:%d:%d.%dZ", &tm.tm_year, &tm.tm_mon, &tm.tm_mday, &tm.tm_hour, &tm.tm_min,
              &tm.tm_sec, &ms);
  tm.tm_year -= 1900;
  tm.tm_mon -= 1;
  return static_cast<double>(timegm(&tm)) + ms / 1000.0;
}

// Submits the spec, attaches `viewers` viewers, waits for the end; returns the job's duration.
double run_job(const HttpClient& client, const std::string& spec, int viewers, long& frames_received,
               double& stream_share) {
  const auto submitted = client.request("POST", "/api/jobs", spec, "application/json");
  if (submitted.status != 201) throw std::runtime_error("submit failed: " + submitted.body);
  const long id = nlohmann::json::parse(submitted.body)["id"];
  std::vector<std::thread> threads;
  std::vector<long> counts(viewers, 0);
  for (int v = 0; v < viewers; ++v)
    threads.emplace_back([&, v] {
      FrameStream stream(client, "/api/jobs/" + std::to_string(id) + "/frames" + (v % 2 ? "?forceChains=1" : ""));
      while (stream.next()) ++counts[v];
    });
  nlohmann::json job;
  for (;;) {
    job = nlohmann::json::parse(client.get("/api/jobs/" + std::to_string(id)).body);
    const std::string state = job["state"];
    if (state != "queued" && state != "running") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  for (std::thread& t : threads) t.join();
  if (job["state"] != "succeeded") throw std::runtime_error("job failed: " + job.dump());
  for (long c : counts) frames_received += c;
  stream_share = job["streamSeconds"].get<double>() / job["runSeconds"].get<double>();
  return seconds_of(job["finishedAt"]) - seconds_of(job["startedAt"]);
}

}  // namespace

int main(int argc, char** argv) {
  std::string server, spec_path;
  int viewers = 20, pairs = 3;
  for (int k = 1; k + 1 < argc; k += 2) {
    const std::string a = argv[k], v = argv[k + 1];
    if (a == "--server")
      server = v;
    else if (a == "--spec")
      spec_path = v;
    else if (a == "--viewers")
      viewers = std::stoi(v);
    else if (a == "--pairs")
      pairs = std::stoi(v);
  }
  if (server.empty() || spec_path.empty()) {
    std::fprintf(stderr, "usage: bench_stream_overhead --server URL --spec SPEC.json [--viewers N] [--pairs K]\n");
    return 2;
  }
  std::ifstream in(spec_path);
  std::stringstream spec;
  spec << in.rdbuf();
  const HttpClient client(server);
  std::vector<double> ratios, shares;
  try {
    for (int p = 0; p < pairs; ++p) {
      long unused = 0, frames = 0;
      double none = 0, share = 0;
      const double alone = run_job(client, spec.str(), 0, unused, none);
      const double watched = run_job(client, spec.str(), viewers, frames, share);
      ratios.push_back(watched / alone);
      shares.push_back(share);
      std::printf(
          "pair %d: no viewers %.3f s, %d viewers %.3f s (%ld frames received), ratio %.4f; "
          "the engine's own time on frames: %.2f%% of its loop\n",
          p + 1, alone, viewers, watched, frames, watched / alone, 100 * share);
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_stream_overhead: %s\n", e.what());
    return 1;
  }
  std::sort(ratios.begin(), ratios.end());
  std::sort(shares.begin(), shares.end());
  std::printf("median_slowdown_with_viewers: %.4f\n", ratios[ratios.size() / 2]);
  std::printf("median_engine_share_on_frames: %.4f\n", shares[shares.size() / 2]);
  return 0;
}
