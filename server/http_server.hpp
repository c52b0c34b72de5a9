// dem-server: one port for the REST API, the frame WebSockets and the viewer's files. Runs until
// SIGTERM or SIGINT, then stops accepting, checkpoints running jobs (they run on after a restart)
// and closes the streams.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

namespace dem::server {

struct ServerOptions {
  std::string address = "127.0.0.1";
  unsigned short port = 8080;        // 0: any free port (printed)
  std::filesystem::path data;        // jobs.db and jobs/
  std::filesystem::path web;         // the viewer's files
  std::filesystem::path cases;       // the bundled cases offered at /api/cases
  std::string token;                 // required on every request when not empty
  int concurrency = 1;               // jobs at once
  int threads_per_job = 0;           // 0: the cores shared among the running jobs
  std::size_t max_body = 64u << 20;  // bytes of a request body
  double checkpoint_seconds = 10;
  double max_frame_rate = 30;                       // live frames a second per job; 0: every output frame
  double max_output_bytes = 10000.0 * 1024 * 1024;  // what one job's files may hold
  double max_job_memory_bytes = 0;                  // estimated from the particle count; 0: half the RAM
  double request_timeout = 10;                      // s for a request's header (its body gets 60 s more)
  std::size_t max_connections = 512;                // in all (WebSockets included)
  std::size_t max_connections_per_client = 128;     // from one address
  double keep_finished_days = 0;                    // finished jobs older than this are deleted; 0: kept
  std::size_t keep_finished_jobs = 0;               // only the newest this many finished jobs are kept; 0: all
  int io_threads = 2;
};

// Serves until a stop signal; returns the process's exit status. Prints the URL when listening.
int run_server(const ServerOptions& options);

// True for 127.0.0.0/8, ::1 and "localhost".
bool is_loopback(const std::string& address);

}  // namespace dem::server
