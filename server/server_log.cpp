#include "server/server_log.hpp"

#include <poll.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <chrono>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <spdlog/sinks/base_sink.h>
#include <spdlog/sinks/rotating_file_sink.h>
#include <spdlog/spdlog.h>

namespace dem::server {
namespace {

constexpr std::size_t kFileBytes = std::size_t{10} * 1024 * 1024;
constexpr std::size_t kOldFiles = 3;
// "2026-11-22T07:40:01.250Z [info] ...": the job records' time format, and the level
constexpr const char* kPattern = "%Y-%m-%dT%H:%M:%S.%eZ [%l] %v";
// Below this much free space in the data folder the file is not written (standard error still is):
// what is left is the job table's (its reserve, space_reserve.hpp, is taken again from 4 MB free).
constexpr unsigned long long kKeepFree = 8ull * 1024 * 1024;

// The log file, written only while its file system has room: a busy client's request lines must
// not take the space a full disk's job table is freed.
class FileUnlessDiskFull : public spdlog::sinks::base_sink<std::mutex> {
 public:
  explicit FileUnlessDiskFull(const std::filesystem::path& file)
      : folder_(file.parent_path()),
        file_(std::make_unique<spdlog::sinks::rotating_file_sink_st>(file.string(), kFileBytes, kOldFiles)) {}

 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    if (room()) file_->log(msg);
  }
  void flush_() override { file_->flush(); }
  void set_pattern_(const std::string& pattern) override { file_->set_pattern(pattern); }
  void set_formatter_(std::unique_ptr<spdlog::formatter> formatter) override {
    file_->set_formatter(std::move(formatter));
  }

 private:
  // Asked of the file system at most once a second (a request's line must stay cheap).
  bool room() {
    const auto now = std::chrono::steady_clock::now();
    if (now - checked_ < std::chrono::seconds(1)) return room_;
    checked_ = now;
    struct statvfs about {};
    room_ = ::statvfs(folder_.c_str(), &about) != 0 ||
            static_cast<unsigned long long>(about.f_bavail) * about.f_frsize >= kKeepFree;
    return room_;
  }

  std::filesystem::path folder_;
  std::unique_ptr<spdlog::sinks::rotating_file_sink_st> file_;
  std::chrono::steady_clock::time_point checked_{};
  bool room_ = true;
};

// Standard error, written only when a line can go at once: a launcher that captures it and never
// reads it (a pipe of 64 KB filled by request lines) must not stop the server answering. A pipe
// that polls writable has room for PIPE_BUF bytes, which a line (its target cut at 2,000 bytes) fits;
// lines that could not go are counted, and said when one can.
class StderrUnlessBlocked : public spdlog::sinks::base_sink<std::mutex> {
 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    pollfd out{STDERR_FILENO, POLLOUT, 0};
    if (::poll(&out, 1, 0) != 1 || (out.revents & POLLOUT) == 0) {
      ++dropped_;
      return;
    }
    if (dropped_ > 0) {
      const std::string note = "(" + std::to_string(dropped_) +
                               " log lines were not written here: standard error was not being read; the data "
                               "folder's server.log has them)\n";
      dropped_ = 0;
      write_all(note.data(), note.size());
    }
    spdlog::memory_buf_t line;
    formatter_->format(msg, line);
    write_all(line.data(), line.size());
  }
  void flush_() override {}

 private:
  static void write_all(const char* data, std::size_t size) {
    while (size > 0) {
      const ssize_t n = ::write(STDERR_FILENO, data, size);
      if (n <= 0) return;  // closed, or full after all: the line is lost, not waited for
      data += n;
      size -= static_cast<std::size_t>(n);
    }
  }
  std::size_t dropped_ = 0;
};

std::shared_ptr<spdlog::logger> make_logger(std::vector<spdlog::sink_ptr> sinks) {
  auto logger = std::make_shared<spdlog::logger>("dem-server", sinks.begin(), sinks.end());
  logger->set_pattern(kPattern, spdlog::pattern_time_type::utc);
  logger->flush_on(spdlog::level::trace);  // every line, at once
  return logger;
}

}  // namespace

ServerLog::ServerLog(const std::filesystem::path& data) {
  spdlog::set_default_logger(
      make_logger({std::make_shared<StderrUnlessBlocked>(), std::make_shared<FileUnlessDiskFull>(data / kFileName)}));
}

// Standard error alone, for what is logged after the server (a job manager's last words).
ServerLog::~ServerLog() { spdlog::set_default_logger(make_logger({std::make_shared<StderrUnlessBlocked>()})); }

}  // namespace dem::server
