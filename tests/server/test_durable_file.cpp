// write_file_durably: the whole file or the old one, and never a half-written temporary left behind
// (a failed checkpoint on a full disk left checkpoint.dat.tmp in the job's folder).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "server/durable_file.hpp"

namespace dem::test {
namespace {

namespace fs = std::filesystem;

TEST(DurableFile, AFailedWriteKeepsTheOldFileAndLeavesNoTemporary) {
  const fs::path dir = fs::temp_directory_path() / ("dem_durable_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path path = dir / "checkpoint.dat";
  server::write_file_durably(path, "the old state");
  fs::create_symlink("/dev/full", dir / "checkpoint.dat.tmp");  // every write to it: ENOSPC
  EXPECT_THROW(server::write_file_durably(path, std::string(100000, 'x')), std::runtime_error);
  EXPECT_FALSE(fs::exists(fs::symlink_status(dir / "checkpoint.dat.tmp")));
  std::ifstream in(path);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "the old state");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace dem::test
