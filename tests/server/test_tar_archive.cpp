// outputs.tar: a failed archive (a full disk) leaves no half-written outputs.tar.tmp behind in the
// job's folder (one survived restarts), and a link planted among the outputs is not followed into
// the archive (it would carry any file of the machine out with the job's files). Independent
// tester's findings, 2026-12-04.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <unistd.h>

#include "server/tar_archive.hpp"

namespace dem::test {
namespace {

namespace fs = std::filesystem;

class TarArchive : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dem_tar_archive_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "outputs");
    std::ofstream(dir_ / "outputs" / "Energy.dat") << "0 1 2\n";
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(TarArchive, AFailedArchiveLeavesNoTemporary) {
  fs::create_symlink("/dev/full", dir_ / "outputs.tar.tmp");  // every write to it: ENOSPC
  EXPECT_THROW(server::write_tar((dir_ / "outputs").string(), (dir_ / "outputs.tar").string()), std::runtime_error);
  EXPECT_FALSE(fs::exists(fs::symlink_status(dir_ / "outputs.tar.tmp")));
  EXPECT_FALSE(fs::exists(dir_ / "outputs.tar"));
}

TEST_F(TarArchive, ALinkAmongTheOutputsIsNotArchived) {
  std::ofstream(dir_ / "secret.txt") << "the machine's own file";
  fs::create_symlink(dir_ / "secret.txt", dir_ / "outputs" / "Leak.dat");
  server::write_tar((dir_ / "outputs").string(), (dir_ / "outputs.tar").string());
  std::ifstream in(dir_ / "outputs.tar", std::ios::binary);
  const std::string tar((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(tar.find("Energy.dat"), std::string::npos);
  EXPECT_EQ(tar.find("Leak.dat"), std::string::npos);
  EXPECT_EQ(tar.find("the machine's own file"), std::string::npos);
}

TEST_F(TarArchive, AHardLinkAmongTheOutputsIsNotArchived) {
  std::ofstream(dir_ / "secret.txt") << "the machine's own file";
  fs::create_hard_link(dir_ / "secret.txt", dir_ / "outputs" / "Hard.dat");
  server::write_tar((dir_ / "outputs").string(), (dir_ / "outputs.tar").string());
  std::ifstream in(dir_ / "outputs.tar", std::ios::binary);
  const std::string tar((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(tar.find("Energy.dat"), std::string::npos);
  EXPECT_EQ(tar.find("Hard.dat"), std::string::npos);
}

}  // namespace
}  // namespace dem::test
