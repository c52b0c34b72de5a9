// A checkpoint's list of output files (names and lengths) decides which files resuming cuts back
// or deletes: an edited or damaged list must be refused as the state itself is (an independent
// tester changed a length by hand and the resume cut a good file short; a name with "../" would
// reach outside the job's folder). Nothing is changed on disk when a checkpoint is refused.
#include <gtest/gtest.h>

#include <boost/crc.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <tuple>
#include <unistd.h>

#include "server/checkpoint.hpp"
#include "spec/spec_loader.hpp"

namespace dem::test {
namespace {

namespace fs = std::filesystem;

const char* kSpec = R"({"name": "two",
  "materials": [{"name": "rock", "density": 2600, "youngsModulus": 1e7, "poissonRatio": 0.25}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5, "friction": 0.5}],
  "contact": {"normal": "HERTZ"},
  "gravity": {"z": -9.81},
  "particles": [{"material": "rock", "position": {"z": 0.02}, "radius": 0.01}],
  "time": {"duration": 0.01}
})";

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}
void write(const fs::path& p, const std::string& bytes) { std::ofstream(p, std::ios::binary) << bytes; }

// The header's checksum (its own line: CRC-32 of the lines before it) made to match again, as a
// checkpoint written by hand or by a bug would.
std::string resealed(std::string bytes) {
  const std::size_t sum_at = bytes.find("header-crc32 ");
  EXPECT_NE(sum_at, std::string::npos);
  boost::crc_32_type crc;
  crc.process_bytes(bytes.data(), sum_at);
  const std::size_t line_end = bytes.find('\n', sum_at);
  bytes.replace(sum_at, line_end - sum_at, "header-crc32 " + std::to_string(crc.checksum()));
  return bytes;
}

class CheckpointHeader : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dem_checkpoint_header_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "outputs");
    write(dir_ / "outputs" / "ANIMATION_3D.dat", std::string(100, 'a'));
    write(dir_ / "outputs" / "Energy.dat", std::string(40, 'e'));
    Simulation sim(spec::to_scene(spec::parse_json(kSpec)));
    for (int k = 0; k < 5; ++k) sim.step();
    server::write_checkpoint(sim, (dir_ / "outputs").string(), checkpoint().string());
    // written after the checkpoint: resuming removes or cuts them
    write(dir_ / "outputs" / "ANIMATION_3D.dat", std::string(130, 'a'));
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path checkpoint() const { return dir_ / "checkpoint.dat"; }

  // The checkpoint with `from` replaced by `to` once, in its header.
  void edit(const std::string& from, const std::string& to) {
    std::string bytes = read(checkpoint());
    const std::size_t at = bytes.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    bytes.replace(at, from.size(), to);
    write(checkpoint(), bytes);
  }
  void expect_refused_and_untouched(const std::string& says) {
    Simulation sim(spec::to_scene(spec::parse_json(kSpec)));
    try {
      server::resume_from_checkpoint(sim, (dir_ / "outputs").string(), checkpoint().string());
      FAIL() << "the edited checkpoint was resumed";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
    EXPECT_EQ(read(dir_ / "outputs" / "ANIMATION_3D.dat").size(), 130u);
    EXPECT_EQ(read(dir_ / "outputs" / "Energy.dat").size(), 40u);
  }

  fs::path dir_;
};

TEST_F(CheckpointHeader, AnUntouchedCheckpointCutsTheOutputsBack) {
  Simulation sim(spec::to_scene(spec::parse_json(kSpec)));
  server::resume_from_checkpoint(sim, (dir_ / "outputs").string(), checkpoint().string());
  EXPECT_EQ(sim.step_count(), 5);
  EXPECT_EQ(read(dir_ / "outputs" / "ANIMATION_3D.dat").size(), 100u);
}

TEST_F(CheckpointHeader, AnEditedLengthIsRefused) {
  edit("ANIMATION_3D.dat 100", "ANIMATION_3D.dat 50");
  expect_refused_and_untouched("checksum");
}

TEST_F(CheckpointHeader, AnEditedNameIsRefused) {
  edit("Energy.dat 40", "Energy.dax 40");
  expect_refused_and_untouched("checksum");
}

TEST_F(CheckpointHeader, ANameLeavingTheFolderIsRefusedEvenWithAMatchingChecksum) {
  // a checkpoint written by hand (or by a bug) with a consistent checksum: the names are still
  // checked before any file is touched
  std::string bytes = read(checkpoint());
  const std::size_t at = bytes.find("Energy.dat 40");
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at, 10, "../E.dat");
  write(checkpoint(), resealed(bytes));
  expect_refused_and_untouched("not a plain file name");
}

// What an independent tester found next (2026-12-04): a name listed twice (the other file then lost
// its length and was cut to the first's), and a link planted among the outputs, which resuming cut
// and appended to wherever it led.
TEST_F(CheckpointHeader, ANameListedTwiceIsRefused) {
  std::string bytes = read(checkpoint());
  const std::size_t at = bytes.find("Energy.dat 40");
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at, 13, "ANIMATION_3D.dat 40");
  write(checkpoint(), resealed(bytes));
  expect_refused_and_untouched("listed twice");
}

TEST_F(CheckpointHeader, ALinkAmongTheOutputsIsRefused) {
  write(dir_ / "victim.txt", std::string(200, 'v'));
  fs::remove(dir_ / "outputs" / "Energy.dat");
  fs::create_symlink(dir_ / "victim.txt", dir_ / "outputs" / "Energy.dat");
  Simulation sim(spec::to_scene(spec::parse_json(kSpec)));
  try {
    server::resume_from_checkpoint(sim, (dir_ / "outputs").string(), checkpoint().string());
    FAIL() << "resumed through a link";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
  }
  EXPECT_EQ(read(dir_ / "victim.txt").size(), 200u);
  EXPECT_EQ(read(dir_ / "outputs" / "ANIMATION_3D.dat").size(), 130u);
}

// The next round (2026-12-04): the outputs folder itself replaced by a link, a hard link to a file
// elsewhere among the outputs, a listed name starting with '.', a length not in decimal digits.
TEST_F(CheckpointHeader, AnOutputsFolderThatIsALinkIsRefused) {
  fs::rename(dir_ / "outputs", dir_ / "elsewhere");
  fs::create_directory_symlink(dir_ / "elsewhere", dir_ / "outputs");
  Simulation sim(spec::to_scene(spec::parse_json(kSpec)));
  try {
    server::resume_from_checkpoint(sim, (dir_ / "outputs").string(), checkpoint().string());
    FAIL() << "resumed into a linked folder";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("not a folder of the job's own"), std::string::npos) << e.what();
  }
  EXPECT_EQ(read(dir_ / "elsewhere" / "ANIMATION_3D.dat").size(), 130u);
}

TEST_F(CheckpointHeader, AHardLinkAmongTheOutputsIsRefused) {
  write(dir_ / "victim.txt", std::string(200, 'v'));
  fs::remove(dir_ / "outputs" / "Energy.dat");
  fs::create_hard_link(dir_ / "victim.txt", dir_ / "outputs" / "Energy.dat");
  Simulation sim(spec::to_scene(spec::parse_json(kSpec)));
  EXPECT_THROW(server::resume_from_checkpoint(sim, (dir_ / "outputs").string(), checkpoint().string()),
               std::runtime_error);
  EXPECT_EQ(read(dir_ / "victim.txt").size(), 200u);
}

TEST_F(CheckpointHeader, NamesStartingWithADotAndLengthsNotInDigitsAreRefused) {
  const std::string bytes = read(checkpoint());
  for (const auto& [from, to, says] :
       {std::tuple<std::string, std::string, std::string>{"Energy.dat 40", ".hidden 40", "not a plain file name"},
        {"ANIMATION_3D.dat 100", "ANIMATION_3D.dat 0x10", "is not NAME SIZE"},
        {"ANIMATION_3D.dat 100", "ANIMATION_3D.dat +100", "is not NAME SIZE"}}) {
    std::string edited = bytes;
    edited.replace(edited.find(from), from.size(), to);
    write(checkpoint(), resealed(edited));
    expect_refused_and_untouched(says);
  }
}

}  // namespace
}  // namespace dem::test
