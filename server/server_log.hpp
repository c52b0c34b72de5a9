// The server's log (spdlog): the request log (request_log.hpp) and the server's own messages (a job
// folder moved aside, the job table's trouble, retention's deletions), a line each with the time
// in UTC and the level, to standard error and to DATA/server.log, rotated at 10 MB with three old
// files kept (server.1.log, the newest, to server.3.log). A job's own log is its folder's
// (job_log.hpp). Each line is flushed as it is written: the file is read while the server runs,
// and a crash must not lose the lines before it. With less than 8 MB free in the data folder the
// file is not written (standard error still is): that space is the job table's.
#pragma once

#include <filesystem>

namespace dem::server {

// Sends spdlog's default logger to standard error and the data folder's server.log while it lives;
// after, to standard error alone. Throws spdlog::spdlog_ex when the file cannot be opened.
class ServerLog {
 public:
  explicit ServerLog(const std::filesystem::path& data);
  ~ServerLog();
  ServerLog(const ServerLog&) = delete;
  ServerLog& operator=(const ServerLog&) = delete;

  static constexpr const char* kFileName = "server.log";
};

}  // namespace dem::server
