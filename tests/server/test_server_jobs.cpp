// The job lifecycle over REST against the real server: submit (JSON and protobuf), poll, download,
// the same bytes as `dem run`; idempotent retries; cancel, delete; artifacts and the archive.
#include <cstring>

#include "dem.pb.h"
#include "spec/spec_loader.hpp"
#include "support/command.hpp"
#include "support/server_test.hpp"

namespace dem::test {
namespace {

class ServerJobs : public ServerTest {};

// The names and sizes of the files in a ustar archive.
std::map<std::string, std::size_t> tar_listing(const std::string& tar) {
  std::map<std::string, std::size_t> files;
  std::size_t at = 0;
  while (at + 512 <= tar.size() && tar[at] != '\0') {
    const std::string name(tar.c_str() + at);
    const std::size_t size = std::stoul(tar.substr(at + 124, 11), nullptr, 8);
    files[name] = size;
    at += 512 + (size + 511) / 512 * 512;
  }
  return files;
}

TEST_F(ServerJobs, SubmittedAsJsonAndAsProtobufGiveTheBytesOfDemRun) {
  start_server();
  const std::string spec = pouring_spec(0.015, 600, 100, true);
  const fs::path local = dem_run(spec, "local");

  const long json_id = submit_json(spec)["id"];
  const std::string bytes = spec::parse_json(spec).SerializeAsString();
  const client::Response r = client_->request("POST", "/api/jobs", bytes, "application/x-protobuf");
  ASSERT_EQ(r.status, 201) << r.body;
  const long proto_id = nlohmann::json::parse(r.body)["id"];
  EXPECT_EQ(r.header("location"), "/api/v1/jobs/" + std::to_string(proto_id));

  for (long id : {json_id, proto_id}) {
    const nlohmann::json done = wait_for(id, "succeeded,failed");
    ASSERT_EQ(done["state"], "succeeded") << done.dump();
    EXPECT_EQ(done["progress"], 1.0);
    EXPECT_EQ(done["lengthUnit"], "m");
    EXPECT_FALSE(done["startedAt"].get<std::string>().empty());
    EXPECT_FALSE(done["finishedAt"].get<std::string>().empty());
    // the legacy files as text, ParaView's series as XML and its frames as binary
    for (const auto& [name, type] :
         std::vector<std::pair<std::string, std::string>>{{"ANIMATION_3D.dat", "text/plain; charset=utf-8"},
                                                          {"ForceChain_3D.dat", "text/plain; charset=utf-8"},
                                                          {"Masscenter.dat", "text/plain; charset=utf-8"},
                                                          {"Masscenter.csv", "text/csv; charset=utf-8"},
                                                          {"particles.pvd", "application/xml"},
                                                          {"particles_0000000600.vtu", "application/octet-stream"},
                                                          {"contacts_0000000600.vtp", "application/octet-stream"},
                                                          {"walls.vtp", "application/octet-stream"}}) {
      const client::Response file = client_->get("/api/jobs/" + std::to_string(id) + "/artifacts/" + name);
      ASSERT_EQ(file.status, 200) << name;
      EXPECT_EQ(file.header("content-type"), type) << name;
      EXPECT_EQ(file.body, read_bytes(local / name)) << "job " << id << ": " << name << " differs from dem run's";
    }
  }
}

TEST_F(ServerJobs, ArtifactsAreListedAndTheArchiveHoldsThemAll) {
  start_server();
  const long id = submit_json(pouring_spec(0.015, 300, 100))["id"];
  wait_for(id, "succeeded");
  const nlohmann::json list =
      nlohmann::json::parse(client_->get("/api/jobs/" + std::to_string(id) + "/artifacts").body);
  std::map<std::string, std::size_t> listed;
  for (const auto& a : list["artifacts"]) listed[a["name"]] = a["size"];
  ASSERT_TRUE(listed.count("ANIMATION_3D.dat"));
  ASSERT_TRUE(listed.count("outputs.tar"));

  const fs::path tar = dir_ / "outputs.tar";
  const client::Response r =
      client_->download("/api/jobs/" + std::to_string(id) + "/artifacts/outputs.tar", tar.string());
  ASSERT_EQ(r.status, 200);
  EXPECT_EQ(r.header("content-type"), "application/x-tar");
  std::map<std::string, std::size_t> archived = tar_listing(read_bytes(tar));
  listed.erase("outputs.tar");
  EXPECT_EQ(archived, listed);
  // the archive unpacks with tar itself, file for file
  const fs::path unpacked = dir_ / "unpacked";
  fs::create_directories(unpacked);
  ASSERT_EQ(std::system(("tar -xf '" + tar.string() + "' -C '" + unpacked.string() + "'").c_str()), 0);
  EXPECT_EQ(read_bytes(unpacked / "ANIMATION_3D.dat"),
            client_->get("/api/jobs/" + std::to_string(id) + "/artifacts/ANIMATION_3D.dat").body);
}

TEST_F(ServerJobs, ARetriedSubmissionWithTheSameIdempotencyKeyIsTheSameJob) {
  start_server();
  const std::string spec = pouring_spec(0.015, 100, 50);
  const client::Response first =
      client_->request("POST", "/api/jobs", spec, "application/json", {{"Idempotency-Key", "run-7"}});
  const client::Response again =
      client_->request("POST", "/api/jobs", spec, "application/json", {{"Idempotency-Key", "run-7"}});
  const client::Response other =
      client_->request("POST", "/api/jobs", spec, "application/json", {{"Idempotency-Key", "run-8"}});
  ASSERT_EQ(first.status, 201);
  ASSERT_EQ(again.status, 200);
  EXPECT_EQ(again.header("idempotent-replayed"), "true");
  EXPECT_EQ(nlohmann::json::parse(first.body)["id"], nlohmann::json::parse(again.body)["id"]);
  EXPECT_NE(nlohmann::json::parse(first.body)["id"], nlohmann::json::parse(other.body)["id"]);
  // the same key with another spec is a mistake, not a retry
  const client::Response reused = client_->request("POST", "/api/jobs", pouring_spec(0.015, 200, 50),
                                                   "application/json", {{"Idempotency-Key", "run-7"}});
  EXPECT_EQ(reused.status, 422);
  EXPECT_NE(reused.body.find("with another spec"), std::string::npos) << reused.body;
  // and after a restart
  server_.reset();
  start_server();
  const client::Response later =
      client_->request("POST", "/api/jobs", spec, "application/json", {{"Idempotency-Key", "run-7"}});
  EXPECT_EQ(later.status, 200);
  EXPECT_EQ(nlohmann::json::parse(first.body)["id"], nlohmann::json::parse(later.body)["id"]);
}

TEST_F(ServerJobs, JobsWaitInOrderAndCanBeCancelledOrDeleted) {
  start_server();
  const long running = submit_json(pouring_spec(0.012, 1000000, 1000))["id"];  // runs until cancelled
  const long waiting = submit_json(pouring_spec(0.015, 100, 50))["id"];
  wait_for(running, "running");
  EXPECT_EQ(job(waiting)["state"], "queued");  // one job at a time by default

  const nlohmann::json list = nlohmann::json::parse(client_->get("/api/jobs?state=queued").body);
  ASSERT_EQ(list["jobs"].size(), 1u);
  EXPECT_EQ(list["jobs"][0]["id"], waiting);

  const client::Response busy = client_->request("DELETE", "/api/jobs/" + std::to_string(running));
  EXPECT_EQ(busy.status, 409);
  EXPECT_NE(busy.body.find("cancel it first"), std::string::npos) << busy.body;

  const client::Response cancelled = client_->request("POST", "/api/jobs/" + std::to_string(running) + "/cancel");
  ASSERT_EQ(cancelled.status, 200) << cancelled.body;
  EXPECT_EQ(nlohmann::json::parse(cancelled.body)["state"], "cancelled");
  EXPECT_EQ(client_->request("POST", "/api/jobs/" + std::to_string(running) + "/cancel").status, 409);
  EXPECT_EQ(wait_for(waiting, "succeeded")["state"], "succeeded");  // the next one ran

  EXPECT_EQ(client_->request("DELETE", "/api/jobs/" + std::to_string(waiting)).status, 204);
  EXPECT_EQ(client_->get("/api/jobs/" + std::to_string(waiting)).status, 404);
  EXPECT_FALSE(fs::exists(dir_ / "data" / "jobs" / std::to_string(waiting)));
  EXPECT_EQ(client_->request("POST", "/api/jobs/" + std::to_string(running) + "/resume").status, 409);
}

TEST_F(ServerJobs, WithTwoJobsAtOnceBothRunAndTheThirdWaits) {
  start_server({"--jobs", "2"});
  std::vector<long> ids;
  for (int k = 0; k < 3; ++k) ids.push_back(submit_json(pouring_spec(0.015, 100000000, 100000))["id"]);
  wait_for(ids[0], "running");
  wait_for(ids[1], "running");
  EXPECT_EQ(job(ids[2])["state"], "queued");
  for (long id : ids) EXPECT_EQ(client_->request("POST", "/api/jobs/" + std::to_string(id) + "/cancel").status, 200);
  for (long id : ids) EXPECT_EQ(wait_for(id, "cancelled")["state"], "cancelled");
}

TEST_F(ServerJobs, ASecondServerOnTheSameDataFolderIsRefused) {
  start_server();
  const CommandResult r =
      run_command(std::string(DEM_BINARY_DIR) + "/dem-server --port 0 --data " + shell_quoted(dir_ / "data"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("another dem-server is using the data folder"), std::string::npos) << r.output;
  EXPECT_EQ(client_->get("/api/health").status, 200);
}

TEST_F(ServerJobs, BundledCasesAreOfferedWithTheirMeshesInlinedAndCanBeSubmitted) {
  start_server();
  const nlohmann::json cases = nlohmann::json::parse(client_->get("/api/cases").body)["cases"];
  std::vector<std::string> names;
  for (const auto& c : cases) names.push_back(c["name"]);
  EXPECT_NE(std::find(names.begin(), names.end(), "demo"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "landslide"), names.end());
  const client::Response landslide = client_->get("/api/cases/landslide");
  ASSERT_EQ(landslide.status, 200);
  const nlohmann::json spec = nlohmann::json::parse(landslide.body);
  bool inline_mesh = false;
  for (const auto& wall : spec["walls"])
    if (wall.contains("mesh")) inline_mesh = wall["mesh"].contains("vertices") && !wall["mesh"].contains("file");
  EXPECT_TRUE(inline_mesh);
  const client::Response submitted = client_->request("POST", "/api/jobs", landslide.body, "application/json");
  EXPECT_EQ(submitted.status, 201) << submitted.body;
  EXPECT_EQ(client_->get("/api/cases/nothing").status, 404);
  EXPECT_EQ(client_->get("/api/cases/..%2Fcases%2Fdemo").status, 400);  // an escaped separator: no such path
}

TEST_F(ServerJobs, HealthAndTheOpenApiDescriptionAreServed) {
  start_server();
  const client::Response health = client_->get("/api/health");
  ASSERT_EQ(health.status, 200);
  EXPECT_EQ(nlohmann::json::parse(health.body)["status"], "ok");
  const client::Response api = client_->get("/api/openapi.json");
  ASSERT_EQ(api.status, 200);
  const nlohmann::json description = nlohmann::json::parse(api.body);
  EXPECT_EQ(description["openapi"].get<std::string>().substr(0, 2), "3.");
  EXPECT_TRUE(description["paths"].contains("/api/v1/jobs"));  // ServerRest checks every path against the routes
}

}  // namespace
}  // namespace dem::test

namespace dem::test {
namespace {

// A job that fails part-way shows the step it reached, which its error names (it showed 0 when it
// failed before its first progress report: an independent tester's finding).
TEST_F(ServerJobs, AJobThatFailsPartWayShowsTheStepItReached) {
  start_server();
  // a step far past the stable limit: the stability guard stops it within a few hundred steps
  const std::string spec = replaced(pouring_spec(0.02, 3000, 100), R"("time": {"steps": 3000})",
                                    R"("time": {"steps": 3000, "dt": 2e-3, "allowUnstableDt": true})");
  const long id = submit_json(spec)["id"];
  const nlohmann::json j = wait_for(id, "failed,succeeded");
  ASSERT_EQ(j.value("state", ""), "failed") << j.dump();
  const long step = j.value("step", 0L);
  EXPECT_GT(step, 0) << j.dump();
  EXPECT_NE(j.value("error", "").find("step " + std::to_string(step)), std::string::npos) << j.dump();
}

}  // namespace
}  // namespace dem::test
