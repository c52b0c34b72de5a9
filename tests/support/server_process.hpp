// Starts the real dem-server (build/dem-server) on a free loopback port for an integration test,
// and stops it (SIGTERM, or kill -9 on request) when the test is done.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace dem::test {

class ServerProcess {
 public:
  // `data`: the server's data folder; `extra`: more command-line options; `stderr_file`: where its
  // standard error goes (appended to), when not the test's own; `binary`: which dem-server.
  explicit ServerProcess(const std::filesystem::path& data, const std::vector<std::string>& extra = {},
                         const std::filesystem::path& stderr_file = {},
                         const std::filesystem::path& binary = DEM_BINARY_DIR "/dem-server") {
    int out[2];
    if (pipe(out) != 0) throw std::runtime_error("pipe failed");
    pid_ = fork();
    if (pid_ < 0) throw std::runtime_error("fork failed");
    if (pid_ == 0) {
      dup2(out[1], STDOUT_FILENO);
      close(out[0]);
      close(out[1]);
      if (!stderr_file.empty()) {
        const int err = open(stderr_file.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
        if (err < 0 || dup2(err, STDERR_FILENO) < 0) _exit(126);
      }
      std::vector<std::string> args = {binary.string(), "--port", "0", "--data", data.string()};
      args.insert(args.end(), extra.begin(), extra.end());
      std::vector<char*> argv;
      for (std::string& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      execv(argv[0], argv.data());
      _exit(127);
    }
    close(out[1]);
    stdout_ = fdopen(out[0], "r");
    // the first line says where it listens: "dem-server listening on http://127.0.0.1:PORT/ ..."
    char line[512];
    if (!std::fgets(line, sizeof line, stdout_)) {
      stop(SIGKILL);
      throw std::runtime_error("dem-server did not start");
    }
    const std::string text = line;
    const std::size_t colon = text.find(':', text.find("127.0.0.1"));
    if (colon == std::string::npos) throw std::runtime_error("unexpected first line of dem-server: " + text);
    port_ = static_cast<unsigned short>(std::stoi(text.substr(colon + 1)));
  }
  ~ServerProcess() { stop(SIGTERM); }
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;

  unsigned short port() const { return port_; }
  std::string url() const { return "http://127.0.0.1:" + std::to_string(port_); }
  pid_t pid() const { return pid_; }

  // Sends `signal` and waits for the process; returns its exit status (or 128 + the signal).
  int stop(int signal) {
    if (pid_ <= 0) return exit_status_;
    kill(pid_, signal);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    if (stdout_) std::fclose(stdout_);
    stdout_ = nullptr;
    exit_status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return exit_status_;
  }

  // Resident memory of the server in KiB (VmRSS of /proc/PID/status).
  long resident_kib() const {
    std::FILE* f = std::fopen(("/proc/" + std::to_string(pid_) + "/status").c_str(), "r");
    if (!f) return -1;
    char line[256];
    long kib = -1;
    while (std::fgets(line, sizeof line, f))
      if (std::sscanf(line, "VmRSS: %ld kB", &kib) == 1) break;
    std::fclose(f);
    return kib;
  }

 private:
  pid_t pid_ = -1;
  std::FILE* stdout_ = nullptr;
  unsigned short port_ = 0;
  int exit_status_ = -1;
};

}  // namespace dem::test
