// Running a command line through the shell for a test (the built dem or dem-server binary): its
// exit status and what it wrote to stdout and stderr; and a fixture for tests of the dem command.
#pragma once

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace dem::test {

struct CommandResult {
  int exit_code = -1;  // -1 when the command did not exit normally
  std::string output;  // stdout and stderr together
};

// A path in single quotes for the shell (test paths hold no quote). Built by appending: GCC 12
// warns falsely (-Wrestrict) about "'" + string.
inline std::string shell_quoted(const std::filesystem::path& p) {
  std::string s = "'";
  s += p.string();
  s += "'";
  return s;
}

// Runs `command_line` through the shell and waits for it. Its stdout and stderr are captured
// together, except what the command line sends elsewhere itself (`... 2>FILE` keeps stderr apart).
inline CommandResult run_command(const std::string& command_line) {
  CommandResult r;
  const std::string command = "{ " + command_line + "\n} 2>&1";
  std::FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) {
    ADD_FAILURE() << "popen failed for " << command_line;
    return r;
  }
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) r.output.append(buffer, n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// The built dem command.
inline const std::string kDem = DEM_BINARY_DIR "/dem";

// A test of the dem command with a private folder (ctest may run tests in parallel), removed afterwards.
class DemCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(std::filesystem::exists(kDem)) << kDem << " is not built";
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("dem_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" + std::to_string(getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Runs `dem ARGS` (the built binary) through the shell.
  CommandResult run_dem(const std::string& args) { return run_command(shell_quoted(kDem) + " " + args); }

  static std::string read(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }

  // Writes `text` to DIR/name and returns its path.
  std::filesystem::path write_spec(const std::string& name, const std::string& text) {
    const std::filesystem::path path = dir_ / name;
    std::ofstream(path) << text;
    return path;
  }

  std::filesystem::path dir_;
};

}  // namespace dem::test
