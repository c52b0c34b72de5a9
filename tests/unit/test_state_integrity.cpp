// A saved state (restart.dat, a server checkpoint) read back is either the state that was written
// or an error naming what is wrong: a changed byte is caught by the checksum, and a state whose
// bytes agree with their checksum but not with the job (written by hand, by another build, or by a
// bug) is refused before any index in it is followed. Nothing read from a file may crash the reader
// or the steps after it.
#include <gtest/gtest.h>

#include <boost/crc.hpp>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>

#include "sim/state_io.hpp"
#include "spec/spec_loader.hpp"
#include "support/everything_spec.hpp"

namespace dem::test {
namespace {

// Everything a state holds, small: loose spheres and a two-sphere clump on a mesh floor, a bonded
// pair, a loaded plate above them, rolling resistance (rolling springs), 60 steps in.
const std::string kSpec = everything_spec(0.05, 0.02);

// Loaded once: the clump's mass properties take a while to integrate, and thousands of reads follow.
Simulation fresh() {
  static const Scene scene = spec::to_scene(spec::parse_json(kSpec));
  return Simulation(scene);
}

std::string saved_state(int steps) {
  Simulation sim = fresh();
  for (int k = 0; k < steps; ++k) sim.step();
  std::ostringstream out;
  StateIO::write(sim, out);
  return std::move(out).str();
}

// The state's own checksum is its last four bytes: CRC-32 of all before them.
void reseal(std::string& state) {
  boost::crc_32_type crc;
  crc.process_bytes(state.data(), state.size() - 4);
  const std::uint32_t sum = crc.checksum();
  std::memcpy(state.data() + state.size() - 4, &sum, 4);
}

// Reads `state` into a fresh simulation and, if it is accepted, steps on: either may refuse it with
// an exception, neither may crash. Returns whether it was accepted.
bool read_and_step(const std::string& state) {
  Simulation sim = fresh();
  std::istringstream in(state);
  try {
    StateIO::read(sim, in);
  } catch (const std::runtime_error&) {
    return false;
  }
  for (int k = 0; k < 5 && sim.step_count() < sim.total_steps(); ++k) sim.step();
  return true;
}

TEST(StateIntegrity, TheSceneHasEverythingAStateHolds) {
  Simulation sim = fresh();
  for (int k = 0; k < 60; ++k) sim.step();
  EXPECT_FALSE(sim.state().bodies.empty());
  EXPECT_FALSE(sim.bonds().bonds().empty());
  EXPECT_FALSE(sim.meshes().empty());
  EXPECT_GT(sim.state().neighbors.pair_count(), 0u);
}

// A state is its values and nothing else: a struct's padding (a rigid clump's rotation has 8 bytes of
// it) took whatever memory held, so two runs that differed in nothing but an earlier allocation
// (`dem run --profile` against `dem run`) saved different bytes.
TEST(StateIntegrity, AStateHoldsNoByteTheRunDidNotSet) {
  Simulation sim = fresh();
  for (int k = 0; k < 60; ++k) sim.step();
  auto& rotations = const_cast<std::vector<RigidRotation>&>(sim.state().bodies.rotation);
  ASSERT_FALSE(rotations.empty());
  auto saved_with_memory_of = [&](unsigned char fill) {
    for (RigidRotation& r : rotations) {
      const RigidRotation value = r;
      std::memset(static_cast<void*>(&r), fill, sizeof r);  // padding bytes as an older use of the memory left them
      r.orientation = value.orientation;
      r.angular_momentum = value.angular_momentum;
    }
    std::ostringstream out;
    StateIO::write(sim, out);
    return std::move(out).str();
  };
  EXPECT_EQ(saved_with_memory_of(0x00), saved_with_memory_of(0xA5));
}

TEST(StateIntegrity, AChangedByteIsCaughtByTheChecksum) {
  const std::string good = saved_state(60);
  int caught = 0, tried = 0;
  for (std::size_t at = 8; at + 4 < good.size(); at += 97) {
    std::string bad = good;
    bad[at] = static_cast<char>(bad[at] ^ 0x10);
    Simulation sim = fresh();
    std::istringstream in(bad);
    ++tried;
    try {
      StateIO::read(sim, in);
    } catch (const std::runtime_error& e) {
      if (std::string(e.what()).find("checksum") != std::string::npos) ++caught;
    }
  }
  EXPECT_EQ(caught, tried);
}

TEST(StateIntegrity, AnIntactStateIsStillReadAndContinued) {
  const std::string good = saved_state(60);
  Simulation sim = fresh();
  std::istringstream in(good);
  StateIO::read(sim, in);
  EXPECT_EQ(sim.step_count(), 60);
}

// The version byte is named as a number (a damaged one was printed raw: invalid text on a terminal).
TEST(StateIntegrity, AStateOfAnotherVersionNamesItsVersionByte) {
  std::string state = saved_state(10);
  state[7] = static_cast<char>(0xCA);
  Simulation sim = fresh();
  std::istringstream in(state);
  try {
    StateIO::read(sim, in);
    FAIL() << "another version was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("format byte 202"), std::string::npos) << e.what();
  }
}

TEST(StateIntegrity, ACutStateIsRefused) {
  const std::string good = saved_state(60);
  for (std::size_t keep : {std::size_t{0}, std::size_t{7}, std::size_t{40}, good.size() / 2, good.size() - 1}) {
    Simulation sim = fresh();
    std::istringstream in(good.substr(0, keep));
    EXPECT_THROW(StateIO::read(sim, in), std::runtime_error) << keep << " bytes";
  }
}

// Every 4-byte word of the state set to a hostile value (a huge index, -1), the checksum made to
// agree: read and step must refuse or go on, never crash. (Today's crash: a partner index out of
// range, followed by the first step.)
TEST(StateIntegrity, NoWordOfASealedStateCrashesTheReaderOrTheSteps) {
  const std::string good = saved_state(60);
  int refused = 0;
  for (std::int32_t hostile : {std::int32_t{0x7fffffff}, std::int32_t{-1}, std::int32_t{1000}}) {
    for (std::size_t at = 8; at + 8 <= good.size(); at += 4) {
      std::string bad = good;
      std::memcpy(bad.data() + at, &hostile, 4);
      reseal(bad);
      if (!read_and_step(bad)) ++refused;
    }
  }
  EXPECT_GT(refused, 0);
}

// Every byte, one at a time, set to values no flag may hold (a bool copied from a file that is
// neither 0 nor 1 is undefined behaviour: the saved-state fuzzer found a wall's optional motion read
// that way, DEMSTAT7). Run by the sanitizer suite, where such a read stops the test.
TEST(StateIntegrity, NoByteOfASealedStateCrashesTheReaderOrTheSteps) {
  const std::string good = saved_state(60);
  int refused = 0;
  for (unsigned char hostile : {0x02, 0xdd}) {
    for (std::size_t at = 8; at + 4 < good.size(); ++at) {
      std::string bad = good;
      bad[at] = static_cast<char>(hostile);
      if (bad == good) continue;
      reseal(bad);
      if (!read_and_step(bad)) ++refused;
    }
  }
  EXPECT_GT(refused, 0);
}

// Every 8 bytes at every offset set to a NaN, the checksum made to agree: a state accepted must
// leave every wall and mesh somewhere. (The saved-state fuzzer found a mesh pose of NaN accepted:
// the mesh's vertices became NaN and its triangle grid converted them to cell indices.)
TEST(StateIntegrity, NoNotANumberPutsAWallOrAMeshNowhere) {
  const std::string good = saved_state(60);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  int refused = 0;
  for (std::size_t at = 8; at + 12 <= good.size(); ++at) {
    std::string bad = good;
    std::memcpy(bad.data() + at, &nan, 8);
    reseal(bad);
    Simulation sim = fresh();
    std::istringstream in(bad);
    try {
      StateIO::read(sim, in);
    } catch (const std::runtime_error&) {
      ++refused;
      continue;
    }
    for (const MeshWall& mesh : sim.meshes())
      for (const Vec3& v : mesh.vertices) ASSERT_TRUE(v.allFinite()) << "NaN at byte " << at << " was accepted";
    for (const Wall& wall : sim.walls()) {
      ASSERT_TRUE(wall.point.allFinite() && wall.normal.allFinite()) << "NaN at byte " << at << " was accepted";
      ASSERT_TRUE(wall.pose.velocity.allFinite()) << "NaN at byte " << at << " was accepted";
    }
  }
  EXPECT_GT(refused, 0);
}

TEST(StateIntegrity, AStepPastTheEndOfTheRunIsRefused) {
  std::string state = saved_state(60);
  // the step count follows the magic (8 bytes), three counts (8 each) and dt (8)
  const std::int64_t far = std::int64_t{1} << 62;
  std::memcpy(state.data() + 8 + 3 * 8 + 8, &far, 8);
  reseal(state);
  Simulation sim = fresh();
  std::istringstream in(state);
  try {
    StateIO::read(sim, in);
    StateIO::require_within_run(sim);
    FAIL() << "a step of 2^62 was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("step"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dem::test
