// Parameter studies on the real server (/api/studies): one request queues a job per run; the study
// shows their states, gives the results table (JSON, CSV) and the figure from the jobs' results;
// cancel and resume act on all its jobs; a bad study or a bad run is refused whole, by name; the
// studies outlive a restart. And a job's record carries its results, as dem run's results.json.
#include "support/command.hpp"
#include "support/server_test.hpp"

namespace dem::test {
namespace {

class ServerStudies : public ServerTest {
 protected:
  nlohmann::json study_of(const std::string& base, const std::string& path, const nlohmann::json& values) {
    return {{"name", "radius study"},
            {"base", nlohmann::json::parse(base)},
            {"parameters", {{{"path", path}, {"values", values}}}}};
  }
  client::Response post(const nlohmann::json& study) {
    return client_->request("POST", "/api/studies", study.dump(), "application/json");
  }
  nlohmann::json get(const std::string& target) { return nlohmann::json::parse(client_->get(target).body); }
  nlohmann::json wait_finished(long id, double seconds = 300) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    nlohmann::json s;
    while (std::chrono::steady_clock::now() < end) {
      s = get("/api/studies/" + std::to_string(id));
      if (s.value("finished", false)) return s;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    ADD_FAILURE() << "study " << id << " did not finish: " << s.dump();
    return s;
  }
};

TEST_F(ServerStudies, AStudyIsOneRequestAndItsTableComesFromItsJobsResults) {
  start_server();
  const client::Response r = post(study_of(pouring_spec(0.015, 200, 100), "lattices[0].radius", {0.012, 0.015, 0.02}));
  ASSERT_EQ(r.status, 201) << r.body;
  const nlohmann::json created = nlohmann::json::parse(r.body);
  const long id = created["id"];
  EXPECT_EQ(r.header("location"), "/api/v1/studies/" + std::to_string(id));
  ASSERT_EQ(created["jobs"].size(), 3u);
  const nlohmann::json done = wait_finished(id);
  EXPECT_EQ(done["counts"]["succeeded"], 3) << done.dump();
  EXPECT_EQ(done["progress"], 1.0);

  // each job's record has its results; the table has them with the run's value
  const nlohmann::json table = get("/api/studies/" + std::to_string(id) + "/results.json");
  ASSERT_EQ(table["rows"].size(), 3u);
  int previous = 1 << 30;
  for (int k = 0; k < 3; ++k) {
    const nlohmann::json& row = table["rows"][k];
    const long job_id = row["job"];
    const nlohmann::json job = this->job(job_id);
    EXPECT_EQ(job["results"]["particles"], job["particles"]);
    EXPECT_EQ(row["results"]["particles"], job["particles"]);
    EXPECT_EQ(row["results"]["steps"], 200);
    // larger spheres, fewer of them in the same box
    const int particles = row["results"]["particles"];
    EXPECT_LT(particles, previous);
    previous = particles;
    EXPECT_EQ(row["parameters"]["lattices[0].radius"], (std::vector<double>{0.012, 0.015, 0.02})[k]);
  }
  const client::Response csv = client_->get("/api/studies/" + std::to_string(id) + "/results.csv");
  ASSERT_EQ(csv.status, 200);
  EXPECT_EQ(csv.header("content-type"), "text/csv; charset=utf-8");
  EXPECT_EQ(csv.body.substr(0, 34), "run,job,lattices[0].radius,state,e");
  const client::Response svg = client_->get("/api/studies/" + std::to_string(id) + "/figure.svg");
  ASSERT_EQ(svg.status, 200);
  EXPECT_EQ(svg.header("content-type"), "image/svg+xml");
  EXPECT_EQ(svg.body.rfind("<svg", 0), 0u);

  // the same run locally gives the same results as the job
  const fs::path local =
      dem_run(replaced(pouring_spec(0.015, 200, 100), "\"radius\": 0.015", "\"radius\": 0.012"), "local");
  const nlohmann::json here = nlohmann::json::parse(read_bytes(local / "results.json"));
  EXPECT_EQ(here["motion"], table["rows"][0]["results"]["motion"]);
  EXPECT_EQ(here["energy"], table["rows"][0]["results"]["energy"]);

  // the studies and their results outlive a restart
  server_.reset();
  start_server();
  const nlohmann::json after = get("/api/studies/" + std::to_string(id));
  EXPECT_EQ(after["counts"]["succeeded"], 3) << after.dump();
  EXPECT_EQ(get("/api/studies/" + std::to_string(id) + "/results.json"), table);
  EXPECT_EQ(get("/api/studies")["studies"].size(), 1u);
}

// One value for several fields (the PDEM-EGD manual's bond strength C is the tensile and the shear
// one): each job gets the value in every field, and the table names the parameter by all of them.
TEST_F(ServerStudies, AParameterMaySetSeveralFieldsToOneValue) {
  start_server();
  nlohmann::json study = study_of(pouring_spec(0.015, 20, 10), "", {0.3, 0.6});
  study["parameters"][0]["path"] = {"interactions[0].friction", "interactions[1].friction"};
  const client::Response r = post(study);
  ASSERT_EQ(r.status, 201) << r.body;
  const long id = nlohmann::json::parse(r.body)["id"];
  const nlohmann::json done = wait_finished(id);
  EXPECT_EQ(done["counts"]["succeeded"], 2) << done.dump();
  EXPECT_EQ(done["parameters"][0], "interactions[0].friction = interactions[1].friction");
  const long second = done["jobs"][1]["job"];
  EXPECT_EQ(job(second)["name"], "radius study #2 (interactions[0].friction = interactions[1].friction = 0.6)");
  const client::Response csv = client_->get("/api/studies/" + std::to_string(id) + "/results.csv");
  EXPECT_EQ(csv.body.rfind("run,job,interactions[0].friction = interactions[1].friction,state", 0), 0u) << csv.body;
  // a bad field among them is named by its place in the list
  study["parameters"][0]["path"] = {"interactions[0].friction", "interactions[7].friction"};
  const client::Response bad = post(study);
  EXPECT_EQ(bad.status, 400);
  EXPECT_NE(bad.body.find("parameters[0].path[1]: \\\"interactions[7].friction\\\""), std::string::npos) << bad.body;
}

TEST_F(ServerStudies, CancelStopsEveryJobOfTheStudy) {
  start_server();
  const client::Response r = post(study_of(pouring_spec(0.012, 2000000, 1000), "numerics.threads", {1, 1, 1}));
  ASSERT_EQ(r.status, 201) << r.body;
  const long id = nlohmann::json::parse(r.body)["id"];
  const client::Response cancel = client_->request("POST", "/api/studies/" + std::to_string(id) + "/cancel", "", "");
  ASSERT_EQ(cancel.status, 200) << cancel.body;
  const nlohmann::json s = wait_finished(id, 60);
  EXPECT_EQ(s["counts"]["cancelled"], 3) << s.dump();
  EXPECT_EQ(client_->request("POST", "/api/studies/" + std::to_string(id) + "/resume", "", "").status, 200);
}

TEST_F(ServerStudies, ABadStudyOrABadRunIsRefusedWholeAndByName) {
  start_server();
  client::Response r = post(study_of(pouring_spec(0.015, 200, 100), "lattices[3].radius", {0.01}));
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(r.body.find("parameters[0].path: \\\"lattices[3].radius\\\""), std::string::npos) << r.body;
  // the second value is bad: no job is queued
  r = post(study_of(pouring_spec(0.015, 200, 100), "lattices[0].radius", {0.015, -0.01}));
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(r.body.find("run 2 (lattices[0].radius=-0.01)"), std::string::npos) << r.body;
  EXPECT_EQ(get("/api/jobs")["jobs"].size(), 0u);
  EXPECT_EQ(get("/api/studies")["studies"].size(), 0u);
  // a base by file name: the server reads no files of the client's
  nlohmann::json by_file = study_of(pouring_spec(0.015, 200, 100), "lattices[0].radius", {0.01});
  by_file["base"] = "spec.json";
  r = post(by_file);
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(r.body.find("base: the server takes the base spec inline"), std::string::npos) << r.body;
  EXPECT_EQ(client_->request("POST", "/api/studies", "{", "application/json").status, 400);
  EXPECT_EQ(client_->request("POST", "/api/studies", "{}", "text/plain").status, 415);
  EXPECT_EQ(client_->get("/api/studies/7").status, 404);
  EXPECT_EQ(client_->get("/api/studies/x/results.csv").status, 404);
  EXPECT_EQ(client_->get("/api/studies/1/other").status, 404);
  EXPECT_EQ(client_->request("DELETE", "/api/studies", "", "").status, 405);
}

// A base naming a file (a mesh, a clump template) is refused before the server opens it: it opened
// and parsed it, and its error showed the file's first word (an independent tester read a 0600
// file and /proc/self/environ that way, and /dev/zero took 3 GB).
TEST_F(ServerStudies, AFileNamedByTheBaseIsNeverOpened) {
  start_server();
  write_text(dir_ / "secret.txt", "hunter2 s3cr3t\n");
  nlohmann::json study = study_of(pouring_spec(0.015, 200, 100), "lattices[0].radius", {0.015});
  study["base"]["walls"][0] = {
      {"name", "floor"}, {"material", "steel"}, {"mesh", {{"file", (dir_ / "secret.txt").string()}}}};
  const client::Response r = post(study);
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(r.body.find("the server reads no files of the client's"), std::string::npos) << r.body;
  EXPECT_EQ(r.body.find("hunter2"), std::string::npos) << r.body;
  EXPECT_EQ(get("/api/jobs")["jobs"].size(), 0u);
}

// A retried POST with its Idempotency-Key gives the study made the first time; the same key for
// another study is refused (the key was ignored: two studies, twice the jobs).
TEST_F(ServerStudies, AnIdempotencyKeyMakesARetryGiveTheSameStudy) {
  start_server();
  const nlohmann::json study = study_of(pouring_spec(0.015, 200, 100), "lattices[0].radius", {0.015, 0.02});
  const client::Headers key{{"Idempotency-Key", "radius-1"}};
  const client::Response first = client_->request("POST", "/api/studies", study.dump(), "application/json", key);
  ASSERT_EQ(first.status, 201) << first.body;
  const client::Response again = client_->request("POST", "/api/studies", study.dump(), "application/json", key);
  EXPECT_EQ(again.status, 200) << again.body;
  EXPECT_EQ(again.header("idempotent-replayed"), "true");
  EXPECT_EQ(nlohmann::json::parse(again.body)["id"], nlohmann::json::parse(first.body)["id"]);
  nlohmann::json other = study;
  other["parameters"][0]["values"] = {0.012};
  EXPECT_EQ(client_->request("POST", "/api/studies", other.dump(), "application/json", key).status, 422);
  EXPECT_EQ(get("/api/studies")["studies"].size(), 1u);
  EXPECT_EQ(get("/api/jobs")["jobs"].size(), 2u);
}

// A server that died while it queued a study's runs queues the rest when it starts again, each run
// once (a kill -9 during a 5000-run POST left 567 jobs and no study). The record is written before
// the first job; here it is one left so.
TEST_F(ServerStudies, AStudyCutShortByACrashIsQueuedWhole) {
  start_server();  // makes the data folder
  const client::Response r = post(study_of(pouring_spec(0.015, 200, 100), "lattices[0].radius", {0.015}));
  ASSERT_EQ(r.status, 201) << r.body;
  server_.reset();
  nlohmann::json record = nlohmann::json::parse(read_bytes(dir_ / "data" / "studies" / "1.json"));
  ASSERT_EQ(record["complete"], true);
  record["id"] = 2;
  record["complete"] = false;
  record["study"]["parameters"][0]["values"] = {0.015, 0.02, 0.03};
  record["jobs"] = {1};  // the first run's job is there; the runs after it never were queued
  write_text(dir_ / "data" / "studies" / "2.json", record.dump());
  write_text(dir_ / "data" / "studies" / "7.json", "garbage");  // a damaged record is left out, not fatal
  start_server();
  const nlohmann::json study = wait_finished(2);
  ASSERT_EQ(study["jobs"].size(), 3u) << study.dump();
  EXPECT_EQ(study["jobs"][0]["job"], 1);
  EXPECT_EQ(study["counts"]["succeeded"], 3) << study.dump();
  EXPECT_EQ(get("/api/jobs")["jobs"].size(), 3u);
  EXPECT_EQ(get("/api/studies")["studies"].size(), 2u);
}

// A study record the server cannot read keeps its file and its id, and a record deleted by hand
// leaves its id used by its jobs' keys: a new study takes the next id and its runs are queued (a
// damaged 6.json was written over by a new study 6, whose runs' keys were the old study's jobs':
// none of its runs was queued, and nothing said so: an independent tester).
TEST_F(ServerStudies, ANewStudyTakesNoIdOfADamagedOrDeletedRecord) {
  start_server();
  const std::string base = pouring_spec(0.015, 200, 100);
  ASSERT_EQ(post(study_of(base, "lattices[0].radius", {0.015})).status, 201);
  ASSERT_EQ(post(study_of(base, "lattices[0].radius", {0.02})).status, 201);
  wait_finished(1);
  wait_finished(2);
  server_.reset();
  const fs::path studies = dir_ / "data" / "studies";
  const std::string damaged = read_bytes(studies / "2.json").substr(0, 200);  // a write cut short
  write_text(studies / "2.json", damaged);
  start_server();
  const client::Response third = post(study_of(base, "lattices[0].radius", {0.012}));
  ASSERT_EQ(third.status, 201) << third.body;
  ASSERT_EQ(nlohmann::json::parse(third.body)["id"], 3);
  EXPECT_EQ(read_bytes(studies / "2.json"), damaged) << "the damaged record was written over";
  nlohmann::json study = wait_finished(3);
  EXPECT_EQ(study["counts"]["succeeded"], 1) << study.dump();
  // the record of study 3 deleted by hand: its job's key still names it
  server_.reset();
  fs::remove(studies / "3.json");
  start_server();
  const client::Response fourth = post(study_of(base, "lattices[0].radius", {0.018}));
  ASSERT_EQ(fourth.status, 201) << fourth.body;
  ASSERT_EQ(nlohmann::json::parse(fourth.body)["id"], 4);
  study = wait_finished(4);
  EXPECT_EQ(study["counts"]["succeeded"], 1) << study.dump();
}

// A job cannot be planted under the key of a future study's run (it became that run: an
// independent tester); and no field that names a file is read, for jobs and studies alike.
TEST_F(ServerStudies, AStudysRunKeysAreTheServersOwnAndNoNamedFileIsRead) {
  start_server();
  const client::Response planted = client_->request("POST", "/api/jobs", pouring_spec(0.015, 200, 100),
                                                    "application/json", {{"Idempotency-Key", "study 1 run 1"}});
  EXPECT_EQ(planted.status, 400) << planted.body;
  EXPECT_NE(planted.body.find("are the server's own"), std::string::npos) << planted.body;
  write_text(dir_ / "secret.dat", "hunter2\n");
  const std::string secret = (dir_ / "secret.dat").string();
  nlohmann::json lattice = nlohmann::json::parse(pouring_spec(0.015, 200, 100));
  lattice["lattices"][0]["inside"] = {{"file", secret}};
  nlohmann::json staged = nlohmann::json::parse(pouring_spec(0.015, 200, 100));
  staged["stages"] = {{{"name", "one"}, {"steps", 100}},
                      {{"name", "two"},
                       {"steps", 100},
                       {"addWalls", {{{"name", "m"}, {"material", "steel"}, {"mesh", {{"file", secret}}}}}}}};
  staged["time"].erase("steps");
  for (const nlohmann::json& spec : {lattice, staged}) {
    const client::Response job = client_->request("POST", "/api/jobs", spec.dump(), "application/json");
    EXPECT_EQ(job.status, 400) << job.body;
    EXPECT_NE(job.body.find("the server reads no files of the client's"), std::string::npos) << job.body;
    EXPECT_EQ(job.body.find("hunter2"), std::string::npos) << job.body;
    nlohmann::json study = study_of(spec.dump(), "numerics.threads", {1});
    const client::Response r = post(study);
    EXPECT_EQ(r.status, 400) << r.body;
    EXPECT_EQ(r.body.find("hunter2"), std::string::npos) << r.body;
  }
}

TEST_F(ServerStudies, DemStudySubmitRunsTheStudyOnTheServerAndDownloadsItsTable) {
  start_server();
  write_text(dir_ / "base.json", pouring_spec(0.015, 200, 100));
  write_text(dir_ / "study.json",
             R"({"base": "base.json", "parameters": [{"path": "lattices[0].velocity.x", "values": [0, 0.3]}]})");
  const CommandResult r = run_command(shell_quoted(kDem) + " study " + shell_quoted(dir_ / "study.json") +
                                      " --submit --server " + server_->url() + " --out " + shell_quoted(dir_ / "out"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("submitted study 1: 2 jobs"), std::string::npos) << r.output;
  const nlohmann::json table = nlohmann::json::parse(read_bytes(dir_ / "out" / "study.json"));
  EXPECT_EQ(table["rows"].size(), 2u);
  EXPECT_EQ(table["rows"][1]["state"], "succeeded");
  EXPECT_TRUE(fs::exists(dir_ / "out" / "study.svg"));
  // with a key: the same command again gives the study first made (a client that gave up waiting
  // for a large study's checks asks again with the key it printed), not a second one
  const std::string keyed = shell_quoted(kDem) + " study " + shell_quoted(dir_ / "study.json") + " --submit --server " +
                            server_->url() + " --out " + shell_quoted(dir_ / "keyed") + " --idempotency-key bed-1";
  ASSERT_EQ(run_command(keyed).exit_code, 0);
  const CommandResult again = run_command(keyed);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("already submitted with idempotency key bed-1: study 2: 2 jobs"), std::string::npos)
      << again.output;
  EXPECT_EQ(get("/api/studies")["studies"].size(), 2u);
  // the folder is this command's from before the study is made: another dem study writing into it
  // is refused, and nothing is sent to the server
  fs::create_directories(dir_ / "held");
  const CommandResult held =
      run_command("flock " + shell_quoted(dir_ / "held" / ".dem-study.lock") + " " + shell_quoted(kDem) + " study " +
                  shell_quoted(dir_ / "study.json") + " --submit --server " + server_->url() + " --out " +
                  shell_quoted(dir_ / "held"));
  EXPECT_EQ(held.exit_code, 1) << held.output;
  EXPECT_NE(held.output.find("another dem study is writing into"), std::string::npos) << held.output;
  EXPECT_EQ(get("/api/studies")["studies"].size(), 2u);
  // a server that is not there: nothing was sent, so no key to ask again with
  const CommandResult refused = run_command(shell_quoted(kDem) + " study " + shell_quoted(dir_ / "study.json") +
                                            " --submit --server http://127.0.0.1:1 --out " + shell_quoted(dir_ / "no"));
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_EQ(refused.output.find("--idempotency-key"), std::string::npos) << refused.output;
}

// A retry with the key of a study still being made (its runs being checked: seconds for hundreds)
// gets 409, not a second study: the key took effect only once the first was made, exactly when a
// client that gave up waiting retries (an independent tester's second round).
TEST_F(ServerStudies, AKeyIsTheStudysFromItsRequestsStart) {
  start_server();
  std::vector<double> radii;
  for (int k = 0; k < 400; ++k) radii.push_back(0.012 + 1e-6 * k);
  const nlohmann::json study = study_of(pouring_spec(0.015, 20, 10), "lattices[0].radius", radii);
  const client::Headers key{{"Idempotency-Key", "slow-1"}};
  client::Response first;
  std::thread making([&] { first = client_->request("POST", "/api/studies", study.dump(), "application/json", key); });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  client::HttpClient second(server_->url());
  const client::Response again = second.request("POST", "/api/studies", study.dump(), "application/json", key);
  making.join();
  EXPECT_EQ(first.status, 201) << first.body;
  EXPECT_TRUE(again.status == 409 || again.status == 200) << again.status << " " << again.body;
  if (again.status == 409) {
    EXPECT_NE(again.body.find("is still being made"), std::string::npos) << again.body;
  }
  EXPECT_EQ(get("/api/studies")["studies"].size(), 1u);
}

}  // namespace
}  // namespace dem::test
