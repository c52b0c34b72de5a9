// Live frames over WebSocket: in order, the radii once, force chains when asked, the same positions
// as the archived ANIMATION_3D.dat; a slow viewer skips frames while a fast one gets them all.
#include <cstring>
#include <sstream>
#include <thread>

#include "dem.pb.h"
#include "legacy/legacy_formats.hpp"
#include "support/server_test.hpp"

namespace dem::test {
namespace {

class ServerFrames : public ServerTest {
 protected:
  // Queues `spec` behind a job that holds the queue, so viewers can join before its first step;
  // `release()` cancels the holder and the job starts.
  long queue_held(const std::string& spec) {
    holder_ = submit_json(pouring_spec(0.015, 100000000, 100000))["id"];
    wait_for(holder_, "running");
    return submit_json(spec)["id"];
  }
  void release() {
    ASSERT_EQ(client_->request("POST", "/api/jobs/" + std::to_string(holder_) + "/cancel").status, 200);
  }

  // Every frame until the server closes the stream.
  static std::vector<api::Frame> read_all(client::FrameStream& stream, int pause_ms = 0) {
    std::vector<api::Frame> frames;
    while (std::optional<std::string> bytes = stream.next()) {
      api::Frame f;
      EXPECT_TRUE(f.ParseFromString(*bytes));
      frames.push_back(std::move(f));
      if (pause_ms > 0) std::this_thread::sleep_for(std::chrono::milliseconds(pause_ms));
    }
    return frames;
  }

  long holder_ = 0;
};

template <class T>
std::vector<T> array_of(const std::string& bytes) {
  std::vector<T> out(bytes.size() / sizeof(T));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
  return out;
}

TEST_F(ServerFrames, AViewerGetsEveryFrameInOrderWithTheArchivedPositions) {
  start_server({"--max-frame-rate", "0"});
  const long id = queue_held(pouring_spec(0.012, 8000, 250, true));  // the lowest layer lands on the floor
  client::FrameStream stream(*client_, "/api/jobs/" + std::to_string(id) + "/frames?forceChains=1");
  release();
  const std::vector<api::Frame> frames = read_all(stream);
  EXPECT_EQ(stream.close_reason(), "job succeeded");

  ASSERT_EQ(frames.size(), 33u);  // steps 0, 250, ..., 8000
  for (std::size_t k = 0; k < frames.size(); ++k) {
    EXPECT_EQ(frames[k].job(), id);
    EXPECT_EQ(frames[k].step(), static_cast<std::int64_t>(250 * k));
    EXPECT_EQ(frames[k].total_steps(), 8000);
    EXPECT_EQ(frames[k].positions().size(), 12u * frames[k].particle_count());
    EXPECT_EQ(frames[k].velocities().size(), 12u * frames[k].particle_count());
    EXPECT_EQ(frames[k].radii().empty(), k > 0) << "radii only in the first frame";
    EXPECT_EQ(frames[k].walls_size(), 1);  // the floor plate (planes are not drawn)
  }
  EXPECT_FLOAT_EQ(array_of<float>(frames[0].radii())[0], 0.012f);

  // the same positions as the archived file (written as %.6e), frame by frame
  std::istringstream file(client_->get("/api/jobs/" + std::to_string(id) + "/artifacts/ANIMATION_3D.dat").body);
  const auto archived = legacy::read_animation(file);
  ASSERT_EQ(archived.frames.size(), frames.size());
  for (std::size_t k : {std::size_t{0}, frames.size() - 1}) {
    const std::vector<float> x = array_of<float>(frames[k].positions());
    for (const legacy::AnimationParticle& p : archived.frames[k].particles)
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(x[3 * (p.id - 1) + d], p.position[d], 1e-6) << "particle " << p.id;
  }
  // force chains: records of i, j, Fn, Ft, the contacts of ForceChain_3D.dat
  std::istringstream file_chains(client_->get("/api/jobs/" + std::to_string(id) + "/artifacts/ForceChain_3D.dat").body);
  const auto chains = legacy::read_force_chains(file_chains);
  ASSERT_EQ(chains.frames.size(), frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    ASSERT_EQ(frames[k].force_chains().size(), 16 * chains.frames[k].chains.size()) << "frame " << k;
    struct Record {
      std::int32_t i, j;
      float normal, tangential;
    };
    const std::vector<Record> records = array_of<Record>(frames[k].force_chains());
    for (std::size_t c = 0; c < records.size(); ++c) {
      EXPECT_EQ(records[c].i + 1, chains.frames[k].chains[c].i);
      EXPECT_NEAR(records[c].normal, chains.frames[k].chains[c].normal_force,
                  1e-5 * std::abs(records[c].normal) + 1e-9);
    }
  }
  EXPECT_FALSE(frames.back().force_chains().empty()) << "the spheres should touch the floor by the last frame";
}

TEST_F(ServerFrames, ASlowViewerSkipsFramesWhileAFastOneGetsThemAll) {
  start_server({"--max-frame-rate", "0"});
  const long id = queue_held(pouring_spec(0.006, 1500, 30));  // ~3,900 spheres: 95 kB a frame
  const std::string target = "/api/jobs/" + std::to_string(id) + "/frames";
  client::FrameStream fast_stream(*client_, target), slow_stream(*client_, target);
  const long memory_before = server_->resident_kib();
  std::vector<api::Frame> fast, slow;
  std::thread fast_reader([&] { fast = read_all(fast_stream); });
  std::thread slow_reader([&] { slow = read_all(slow_stream, 400); });
  release();
  fast_reader.join();
  slow_reader.join();
  const long memory_after = server_->resident_kib();

  ASSERT_EQ(fast.size(), 51u);
  EXPECT_LT(slow.size(), fast.size() / 2) << "the slow viewer should have skipped frames";
  EXPECT_EQ(slow.back().step(), 1500) << "the last frame is never skipped";
  for (std::size_t k = 1; k < slow.size(); ++k) EXPECT_GT(slow[k].step(), slow[k - 1].step());
  EXPECT_FALSE(slow[0].radii().empty());
  // 51 frames of 95 kB went to the fast viewer; the slow one held at most two of them
  std::printf("server memory: %ld KiB before, %ld KiB after; slow viewer got %zu of %zu frames\n", memory_before,
              memory_after, slow.size(), fast.size());
  EXPECT_LT(memory_after - memory_before, 16 * 1024);
}

TEST_F(ServerFrames, LiveFramesAreCappedAtTheMaximumRateButTheLastOneAlwaysComes) {
  start_server({"--max-frame-rate", "2"});
  const long id = queue_held(pouring_spec(0.012, 8000, 10));  // 801 output frames in about a second
  client::FrameStream stream(*client_, "/api/jobs/" + std::to_string(id) + "/frames");
  const auto start = std::chrono::steady_clock::now();
  release();
  const std::vector<api::Frame> frames = read_all(stream);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_FALSE(frames.empty());
  EXPECT_LE(static_cast<double>(frames.size()), 2 * seconds + 3) << "over " << seconds << " s";
  EXPECT_EQ(frames.back().step(), 8000);
  EXPECT_EQ(read_bytes(dir_ / "data" / "jobs" / std::to_string(id) / "outputs" / "Masscenter.dat").empty(), false);
}

TEST_F(ServerFrames, LiveFramesComeBetweenTheFilesFramesWhenThoseAreFew) {
  start_server({"--max-frame-rate", "20"});
  const long id = queue_held(pouring_spec(0.012, 12000, 6000));  // file frames at steps 0, 6000, 12000 only
  client::FrameStream stream(*client_, "/api/jobs/" + std::to_string(id) + "/frames");
  release();
  const std::vector<api::Frame> frames = read_all(stream);
  ASSERT_GT(frames.size(), 3u) << "live frames should not wait for the files' frames";
  bool between = false;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    if (k > 0) {
      EXPECT_GT(frames[k].step(), frames[k - 1].step());
    }
    between = between || frames[k].step() % 6000 != 0;
  }
  EXPECT_TRUE(between);
  EXPECT_EQ(frames.back().step(), 12000);
}

TEST_F(ServerFrames, FramesOfClumpsCarryTheirPartsPositionsAndOrientations) {
  start_server({"--max-frame-rate", "0"});
  const long id = queue_held(R"({"name": "clumps",
    "materials": [{"name": "rock", "density": 2650, "normalStiffness": 2e5}, {"name": "steel", "rigid": true}],
    "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5, "friction": 0.5},
                     {"a": "rock", "b": "steel", "restitution": 0.5, "friction": 0.5}],
    "clumpShapes": [{"name": "pair", "spheres": [{"center": {"x": -0.006}, "radius": 0.01}, {"center": {"x": 0.006}, "radius": 0.01}]}],
    "clumps": [{"shape": "pair", "material": "rock", "position": {"z": 0.05}, "angularVelocity": {"z": 2}},
               {"shape": "pair", "material": "rock", "position": {"x": 0.1, "z": 0.05}}],
    "particles": [{"position": {"x": -0.1, "z": 0.05}, "radius": 0.01, "material": "rock"}],
    "walls": [{"material": "steel", "plane": {"point": {}, "normal": {"z": 1}}}],
    "gravity": {"z": -9.81}, "time": {"steps": 2000}, "outputs": {"everySteps": 500}})");
  client::FrameStream stream(*client_, "/api/jobs/" + std::to_string(id) + "/frames");
  release();
  const std::vector<api::Frame> frames = read_all(stream);
  // a viewer that falls behind skips frames (on a loaded machine this client can): the last one comes
  ASSERT_GE(frames.size(), 2u);
  EXPECT_EQ(frames.back().step(), 2000);
  for (const api::Frame& f : frames) {
    EXPECT_EQ(f.particle_count(), 5u);
    EXPECT_EQ(array_of<std::int32_t>(f.fragments()), (std::vector<std::int32_t>{0, 1, 1, 2, 2}));
    EXPECT_EQ(f.clump_positions().size(), 2u * 12);
    EXPECT_EQ(f.clump_orientations().size(), 2u * 16);
  }
  const std::vector<float> q = array_of<float>(frames.back().clump_orientations());
  EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0f, 1e-5f);
  const std::vector<float> q0 = array_of<float>(frames[0].clump_orientations());
  float turned = 0;  // the spinning clump's quaternion changed
  for (int c = 0; c < 4; ++c) turned = std::max(turned, std::abs(q[c] - q0[c]));
  EXPECT_GT(turned, 1e-3f);
}

TEST_F(ServerFrames, AFinishedJobClosesTheStreamSayingWhere) {
  start_server();
  const long id = submit_json(pouring_spec(0.015, 100, 50))["id"];
  wait_for(id, "succeeded");
  client::FrameStream stream(*client_, "/api/jobs/" + std::to_string(id) + "/frames");
  EXPECT_FALSE(stream.next().has_value());
  EXPECT_EQ(stream.close_reason(),
            "job " + std::to_string(id) +
                " is succeeded: its frames are in its ANIMATION_3D.dat (a 2D run's: ANIMATION_2D.dat)");
}

}  // namespace
}  // namespace dem::test
