// Crashes and restarts: kill -9 during a run loses no job; the interrupted job resumes from its
// checkpoint and ends with the files of an uninterrupted run. SIGTERM checkpoints and re-queues.
#include <signal.h>

#include "support/server_test.hpp"

namespace dem::test {
namespace {

class ServerRecovery : public ServerTest {
 protected:
  // Waits until the running job has a checkpoint past `step`.
  nlohmann::json wait_for_checkpoint(long id, long step) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    nlohmann::json j;
    while (std::chrono::steady_clock::now() < end) {
      j = job(id);
      if (j.value("checkpointStep", -1L) > step) return j;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ADD_FAILURE() << "no checkpoint past step " << step << ": " << j.dump();
    return j;
  }

  void expect_same_files(long id, const fs::path& reference) {
    for (const char* name : {"ANIMATION_3D.dat", "ForceChain_3D.dat", "Masscenter.dat", "Disp_Max.dat", "Coord_OL.dat",
                             "particles.pvd", "contacts.pvd", "walls.vtp", "particles_0000030000.vtu"}) {
      const client::Response r = client_->get("/api/jobs/" + std::to_string(id) + "/artifacts/" + name);
      ASSERT_EQ(r.status, 200) << name;
      EXPECT_TRUE(r.body == read_bytes(reference / name)) << name << " differs from the uninterrupted run's";
    }
  }
};

const std::string kLongSpec = pouring_spec(0.012, 30000, 1000, true);

TEST_F(ServerRecovery, AJobKilledMidRunResumesFromItsCheckpointToTheSameFiles) {
  const fs::path reference = dem_run(kLongSpec, "uninterrupted");
  start_server({"--checkpoint-seconds", "0"});
  const long done = submit_json(pouring_spec(0.015, 100, 50))["id"];
  wait_for(done, "succeeded");
  const long id = submit_json(kLongSpec)["id"];
  const long waiting = submit_json(pouring_spec(0.015, 100, 50))["id"];
  wait_for_checkpoint(id, 2000);
  std::this_thread::sleep_for(std::chrono::milliseconds(150));  // mid-way between checkpoints
  EXPECT_EQ(server_->stop(SIGKILL), 128 + SIGKILL);

  start_server({"--checkpoint-seconds", "0"});
  EXPECT_EQ(job(done)["state"], "succeeded");
  const nlohmann::json interrupted = job(id);
  ASSERT_EQ(interrupted["state"], "interrupted") << interrupted.dump();
  EXPECT_TRUE(interrupted["resumable"].get<bool>());
  EXPECT_NE(interrupted["error"].get<std::string>().find("resume it to continue from its checkpoint"),
            std::string::npos);
  EXPECT_GE(interrupted["step"].get<long>(), interrupted["checkpointStep"].get<long>());
  // the step the table last saved, said as that (it read "at step 0" for a job killed at 84%)
  EXPECT_NE(interrupted["error"].get<std::string>().find(
                "(past step " + std::to_string(interrupted["step"].get<long>()) + ", the last it saved)"),
            std::string::npos)
      << interrupted["error"];
  EXPECT_EQ(wait_for(waiting, "succeeded")["state"], "succeeded");  // the queue went on

  const client::Response resumed = client_->request("POST", "/api/jobs/" + std::to_string(id) + "/resume");
  ASSERT_EQ(resumed.status, 200) << resumed.body;
  EXPECT_EQ(wait_for(id, "succeeded,failed")["state"], "succeeded");
  expect_same_files(id, reference);
  EXPECT_FALSE(fs::exists(dir_ / "data" / "jobs" / std::to_string(id) / "checkpoint.dat"));
}

// The same job in three stages (a side wall goes, gravity turns, the floor is shaken): killed
// inside the second stage, it resumes across the next boundary to the uninterrupted run's files.
// 30,000 steps (run twice): the second stage's 24,000 last 0.5 s in a release build, time enough to
// be killed inside it; under AddressSanitizer the test took 191 s with 58,000.
TEST_F(ServerRecovery, AStagedJobKilledInsideAStageResumesToTheSameFiles) {
  const std::string staged = replaced(kLongSpec, R"("time": {"steps": 30000},)",
                                      R"("stages": [{"name": "pour", "steps": 3000},
                  {"name": "open", "steps": 24000, "removeWalls": ["right"], "gravity": {"x": 2, "z": -9.81}},
                  {"name": "shake", "steps": 3000, "wallChanges": [{"wall": "floor",
                   "motion": {"amplitude": {"z": 0.05}, "frequency": 20}}]}],)");
  const fs::path reference = dem_run(staged, "uninterrupted");
  start_server({"--checkpoint-seconds", "0"});
  const long id = submit_json(staged)["id"];
  wait_for_checkpoint(id, 3500);  // inside the second stage (steps 3,000 to 27,000), killed at once
  EXPECT_EQ(server_->stop(SIGKILL), 128 + SIGKILL);

  start_server({"--checkpoint-seconds", "0"});
  const nlohmann::json interrupted = job(id);
  ASSERT_EQ(interrupted["state"], "interrupted") << interrupted.dump();
  EXPECT_LT(interrupted["checkpointStep"].get<long>(), 27000);
  const client::Response resumed = client_->request("POST", "/api/jobs/" + std::to_string(id) + "/resume");
  ASSERT_EQ(resumed.status, 200) << resumed.body;
  // up to 26,000 steps to go: under AddressSanitizer on a busy machine 275 steps a second, past the default 120 s
  EXPECT_EQ(wait_for(id, "succeeded,failed", 600)["state"], "succeeded");
  expect_same_files(id, reference);
}

TEST_F(ServerRecovery, SigtermCheckpointsTheRunningJobWhichGoesOnAfterTheRestart) {
  const fs::path reference = dem_run(kLongSpec, "uninterrupted");
  start_server();
  const long id = submit_json(kLongSpec)["id"];
  wait_for(id, "running");
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  EXPECT_EQ(server_->stop(SIGTERM), 0);  // a clean exit

  start_server();
  EXPECT_EQ(wait_for(id, "succeeded,failed,interrupted")["state"], "succeeded");
  expect_same_files(id, reference);
}

TEST_F(ServerRecovery, ASubmissionCutShortByACrashLeavesNoTrace) {
  fs::create_directories(dir_ / "data" / "jobs" / "17" / "outputs");  // a folder whose row was never committed
  start_server();
  EXPECT_FALSE(fs::exists(dir_ / "data" / "jobs" / "17"));
  EXPECT_EQ(nlohmann::json::parse(client_->get("/api/jobs").body)["jobs"].size(), 0u);
}

// Half-written temporaries of a crash are removed at the next start (they were left for good).
TEST_F(ServerRecovery, HalfWrittenTemporariesOfACrashAreRemovedAtTheNextStart) {
  start_server();
  const long id = submit_json(pouring_spec(0.015, 100, 50))["id"];
  wait_for(id, "succeeded");
  EXPECT_EQ(server_->stop(SIGKILL), 128 + SIGKILL);
  const fs::path folder = dir_ / "data" / "jobs" / std::to_string(id);
  std::ofstream(folder / "checkpoint.dat.tmp") << "half a checkpoint";
  std::ofstream(folder / "outputs.tar.tmp") << "half an archive";
  start_server();
  EXPECT_EQ(job(id)["state"], "succeeded");
  EXPECT_FALSE(fs::exists(folder / "checkpoint.dat.tmp"));
  EXPECT_FALSE(fs::exists(folder / "outputs.tar.tmp"));
  EXPECT_TRUE(fs::exists(folder / "outputs.tar"));
}

// The job table lost (deleted, or replaced by an empty one) while the jobs' folders remain: the
// server starts, deletes nothing, and moves each folder with files aside (it deleted every one,
// outputs included).
TEST_F(ServerRecovery, AJobTableLostDeletesNoJobsFiles) {
  start_server();
  const long id = submit_json(pouring_spec(0.015, 100, 50))["id"];
  wait_for(id, "succeeded");
  EXPECT_EQ(server_->stop(SIGTERM), 0);
  const fs::path jobs = dir_ / "data" / "jobs";
  const std::string animation = read_bytes(jobs / std::to_string(id) / "outputs" / "ANIMATION_3D.dat");
  ASSERT_FALSE(animation.empty());
  fs::remove(dir_ / "data" / "jobs.db");

  start_server();
  const fs::path aside = dir_ / "data" / "unaccounted" / std::to_string(id);
  EXPECT_EQ(read_bytes(aside / "outputs" / "ANIMATION_3D.dat"), animation);
  EXPECT_TRUE(fs::exists(aside / "outputs.tar"));
  EXPECT_FALSE(fs::exists(jobs / std::to_string(id)));  // out of the way of the next job with that id
  const long next = submit_json(pouring_spec(0.015, 100, 50))["id"];
  EXPECT_EQ(next, id);
  wait_for(next, "succeeded");
  EXPECT_EQ(read_bytes(aside / "outputs" / "ANIMATION_3D.dat"), animation);
}

}  // namespace
}  // namespace dem::test
