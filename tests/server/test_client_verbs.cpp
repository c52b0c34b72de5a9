// The dem command's client verbs (cli/client_commands.cpp) against the real dem-server: what a
// script sees (exit status, stdout), and that a job sent with `dem submit` and brought back with
// `dem fetch` holds the bytes `dem run` writes.
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/command.hpp"
#include "support/server_test.hpp"

namespace dem::test {
namespace {

struct Result {
  int exit_code = -1;
  std::string out, err;
};

// The demo case (spheres poured into a box) cut to its first 0.15 s: 11,699 steps, the first
// contacts with the floor and between spheres, and seconds per run rather than most of a minute.
std::string short_demo_spec() {
  nlohmann::json spec = nlohmann::json::parse(read_bytes(DEM_SOURCE_DIR "/cases/demo/spec.json"));
  spec["time"]["duration"] = 0.15;
  return spec.dump(2);
}

class ClientVerbs : public ServerTest {
 protected:
  // Runs `dem ARGS --server URL` with stdout and stderr apart; `environment` goes before it
  // (DEM_SERVER and DEM_SERVER_TOKEN are cleared first).
  Result dem(const std::string& args, const std::string& environment = "") {
    const fs::path err = dir_ / "stderr.txt";
    const CommandResult r =
        run_command("env -u DEM_SERVER -u DEM_SERVER_TOKEN " + environment + " " + shell_quoted(kDem) + " " + args +
                    " --server " + server_->url() + " 2>" + shell_quoted(err));
    return {r.exit_code, r.output, read_bytes(err)};
  }

  fs::path write_file(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    write_text(path, text);
    return path;
  }

  // `dem submit SPEC --quiet` (and more options): the job id it prints.
  long submit(const fs::path& spec, const std::string& more = "") {
    const Result r = dem("submit " + shell_quoted(spec) + " --quiet " + more);
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    try {
      return std::stol(r.out);
    } catch (...) {
      ADD_FAILURE() << "no job id in \"" << r.out << "\"";
      return -1;
    }
  }
};

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST_F(ClientVerbs, SubmitWaitAndFetchGiveTheBytesOfDemRun) {
  start_server();
  const fs::path spec = write_file("demo.json", short_demo_spec()), local = dir_ / "local";
  const std::string run =
      shell_quoted(kDem) + " run " + shell_quoted(spec) + " --out " + shell_quoted(local) + " --quiet > /dev/null 2>&1";
  ASSERT_EQ(std::system(run.c_str()), 0) << run;

  // a script's `id=$(dem submit s.json --quiet --wait)`: only the id on stdout
  const Result submitted = dem("submit " + shell_quoted(spec) + " --wait --quiet");
  ASSERT_EQ(submitted.exit_code, 0) << submitted.out << submitted.err;
  ASSERT_FALSE(submitted.out.empty());
  const long id = std::stol(submitted.out);
  EXPECT_EQ(submitted.out, std::to_string(id) + "\n");
  EXPECT_EQ(submitted.err, "");

  const Result status = dem("status " + std::to_string(id));
  EXPECT_EQ(status.exit_code, 0) << status.err;
  EXPECT_TRUE(has(status.out, "job " + std::to_string(id) + " \"demo: spheres poured into a box\": succeeded"))
      << status.out;
  const Result raw = dem("status " + std::to_string(id) + " --json");
  ASSERT_EQ(raw.exit_code, 0) << raw.err;
  const nlohmann::json job = nlohmann::json::parse(raw.out);
  EXPECT_EQ(job["id"], id);
  EXPECT_EQ(job["state"], "succeeded");
  EXPECT_EQ(job["step"], job["totalSteps"]);

  const fs::path fetched = dir_ / "fetched";
  const Result fetch = dem("fetch " + std::to_string(id) + " --out " + shell_quoted(fetched));
  ASSERT_EQ(fetch.exit_code, 0) << fetch.out << fetch.err;
  EXPECT_TRUE(has(fetch.out, (fetched / "ANIMATION_3D.dat").string())) << fetch.out;
  for (const char* name : {"ANIMATION_3D.dat", "ForceChain_3D.dat"}) {
    ASSERT_TRUE(fs::exists(fetched / name)) << name;
    EXPECT_EQ(read_bytes(fetched / name), read_bytes(local / name)) << name << " differs from dem run's";
  }
  EXPECT_FALSE(fs::exists(fetched / "outputs.tar")) << "fetched without names, the archive is left out";
  for (const auto& entry : fs::directory_iterator(fetched))
    EXPECT_NE(entry.path().extension(), ".part") << "a partial download is left: " << entry.path();

  // by name: the archive, and a file that is not there (the others are still fetched)
  const Result named =
      dem("fetch " + std::to_string(id) + " outputs.tar Nothing.dat --out " + shell_quoted(dir_ / "named"));
  EXPECT_EQ(named.exit_code, 1);
  EXPECT_GT(fs::file_size(dir_ / "named" / "outputs.tar"), fs::file_size(local / "ANIMATION_3D.dat"));
  EXPECT_TRUE(has(named.err, "Nothing.dat: 404 Not Found")) << named.err;
  EXPECT_FALSE(fs::exists(dir_ / "named" / "Nothing.dat"));

  const Result list = dem("list --state succeeded");
  EXPECT_EQ(list.exit_code, 0) << list.err;
  bool listed = false;  // a row "ID  succeeded  100.0%  STEPS/STEPS  NAME"
  std::istringstream rows(list.out);
  for (std::string row; std::getline(rows, row);) {
    std::istringstream words(row);
    std::string first, state, progress;
    words >> first >> state >> progress;
    listed = listed || (first == std::to_string(id) && state == "succeeded" && progress == "100.0%");
  }
  EXPECT_TRUE(listed) << list.out;
  const Result none = dem("list --state running --json");
  EXPECT_EQ(none.exit_code, 0) << none.err;
  EXPECT_EQ(nlohmann::json::parse(none.out)["jobs"].size(), 0u) << none.out;

  // a finished job can be neither cancelled nor resumed: the server's 409 and its reason
  const Result cancel = dem("cancel " + std::to_string(id));
  EXPECT_EQ(cancel.exit_code, 1);
  EXPECT_TRUE(has(cancel.err, "dem cancel: 409 Conflict: ")) << cancel.err;
  EXPECT_EQ(dem("resume " + std::to_string(id)).exit_code, 1);
}

TEST_F(ClientVerbs, ARetriedSubmitWithTheSameKeyGivesTheSameJob) {
  start_server();
  const fs::path spec = write_file("demo.json", short_demo_spec());
  const long first = submit(spec, "--idempotency-key nightly-42");
  const long again = submit(spec, "--idempotency-key nightly-42");
  EXPECT_EQ(again, first);
  const Result said = dem("submit " + shell_quoted(spec) + " --idempotency-key nightly-42");
  EXPECT_EQ(said.exit_code, 0) << said.err;
  EXPECT_TRUE(has(said.out, "already submitted with idempotency key nightly-42: job " + std::to_string(first)))
      << said.out;
  EXPECT_NE(submit(spec, "--idempotency-key nightly-43"), first);
}

TEST_F(ClientVerbs, ASpecTheServerRefusesListsItsProblems) {
  start_server();
  std::string text = short_demo_spec();
  text.replace(text.find("\"radius\": 0.008"), 15, "\"radius\": -0.008");
  const Result r = dem("submit " + shell_quoted(write_file("bad.json", text)));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(has(r.err, "bad.json: invalid spec (the server answered 400 Bad Request: invalid spec):\n")) << r.err;
  EXPECT_TRUE(has(r.err, "\n  lattices[0].radius: ")) << r.err;
}

// A mesh given both as a file and inline is the spec's mistake, for the server to name: dem submit
// appended the file's triangles to the inline ones, numbering the wrong vertices, and the job ran
// (an independent tester's finding).
TEST_F(ClientVerbs, AMeshGivenAsAFileAndInlineIsRefusedNotMerged) {
  start_server();
  write_file("floor.dat", "4 2\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n1 2 3\n1 3 4\n");
  nlohmann::json spec = nlohmann::json::parse(short_demo_spec());
  spec["walls"].push_back(nlohmann::json::parse(R"({"name": "both", "material": "steel", "mesh": {"file": "floor.dat",
      "vertices": [{"x": 0}, {"x": 1}, {"y": 1}], "triangles": [{"i": 1, "j": 2, "k": 3}]}})"));
  spec["materials"].push_back(nlohmann::json::parse(R"({"name": "steel", "rigid": true})"));
  const Result r = dem("submit " + shell_quoted(write_file("both.json", spec.dump())));
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_TRUE(has(r.err, "walls[5].mesh.file: the server reads no files")) << r.err;  // left as given
}

// dem list takes the list's filters, several states at once, and reads every page.
TEST_F(ClientVerbs, ListFiltersByStateTagAndName) {
  start_server({"--jobs", "1"});
  nlohmann::json spec = nlohmann::json::parse(short_demo_spec());
  spec["time"]["duration"] = 0.01;
  const long plain = submit(write_file("plain.json", spec.dump()));
  spec["tags"] = {"bed:1"};
  spec["name"] = "tagged run";
  const long tagged = submit(write_file("tagged.json", spec.dump()));
  wait_for(plain, "succeeded,failed");
  wait_for(tagged, "succeeded,failed");
  const Result by_tag = dem("list --tag bed:1 --state succeeded,failed --json");
  ASSERT_EQ(by_tag.exit_code, 0) << by_tag.err;
  const nlohmann::json jobs = nlohmann::json::parse(by_tag.out)["jobs"];
  ASSERT_EQ(jobs.size(), 1u) << by_tag.out;
  EXPECT_EQ(jobs[0]["id"], tagged);
  const Result by_name = dem("list --name 'tagged run'");
  EXPECT_EQ(by_name.exit_code, 0) << by_name.err;
  EXPECT_TRUE(has(by_name.out, "tagged run")) << by_name.out;
  EXPECT_FALSE(has(by_name.out, std::to_string(plain) + "  ")) << by_name.out;
  EXPECT_EQ(nlohmann::json::parse(dem("list --json").out)["jobs"].size(), 2u);
  const Result none = dem("list --tag nothing");
  EXPECT_EQ(none.exit_code, 0);
  EXPECT_TRUE(has(none.err, "no jobs of these filters")) << none.err;
  EXPECT_EQ(dem("list --state done").exit_code, 2);
}

TEST_F(ClientVerbs, ACancelledJobEndsItsWatchWithStatusOne) {
  start_server();
  nlohmann::json spec = nlohmann::json::parse(short_demo_spec());
  spec["time"]["duration"] = 100.0;  // runs until cancelled
  const long id = submit(write_file("long.json", spec.dump()));
  const Result cancel = dem("cancel " + std::to_string(id));
  EXPECT_EQ(cancel.exit_code, 0) << cancel.err;
  EXPECT_TRUE(has(cancel.out, "job " + std::to_string(id))) << cancel.out;
  const Result watch = dem("watch " + std::to_string(id));
  EXPECT_EQ(watch.exit_code, 1);
  EXPECT_TRUE(has(watch.err, "dem watch: job " + std::to_string(id))) << watch.err;
  EXPECT_TRUE(has(watch.err, "cancelled")) << watch.err;
}

TEST_F(ClientVerbs, AnUnknownJobIsTheServers404) {
  start_server();
  const Result r = dem("status 999");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "dem status: 404 Not Found: no job 999\n");
  EXPECT_EQ(dem("watch 999").exit_code, 1);
  EXPECT_EQ(dem("fetch 999 --out " + shell_quoted(dir_ / "none")).exit_code, 1);
}

TEST_F(ClientVerbs, TheTokenComesFromTheOptionOrTheEnvironment) {
  start_server({"--token", "s3cret"});
  const Result without = dem("list");
  EXPECT_EQ(without.exit_code, 1);
  EXPECT_TRUE(has(without.err, "dem list: 401")) << without.err;
  EXPECT_EQ(dem("list --token s3cret").exit_code, 0);
  EXPECT_EQ(dem("list", "DEM_SERVER_TOKEN=s3cret").exit_code, 0);
}

// Every client verb takes --json and prints the server's JSON, one document a script can parse
// (submit, cancel, resume, watch and fetch printed only lines of text, and refused --json).
TEST_F(ClientVerbs, EveryClientVerbPrintsJsonWhenAsked) {
  start_server();
  const fs::path spec = write_file("demo.json", short_demo_spec());
  const Result submitted = dem("submit " + shell_quoted(spec) + " --json --wait");
  ASSERT_EQ(submitted.exit_code, 0) << submitted.out << submitted.err;
  // --wait --json: the job as submitted, then as it ended, each a JSON document
  std::istringstream documents(submitted.out);
  nlohmann::json first, last;
  documents >> first >> last;
  const long id = first.at("id").get<long>();
  EXPECT_EQ(last.at("id").get<long>(), id);
  EXPECT_EQ(last.at("state"), "succeeded");

  const Result watched = dem("watch " + std::to_string(id) + " --json");
  EXPECT_EQ(watched.exit_code, 0) << watched.err;
  EXPECT_EQ(nlohmann::json::parse(watched.out).at("state"), "succeeded") << watched.out;

  const Result fetched =
      dem("fetch " + std::to_string(id) + " results.json --out " + shell_quoted(dir_ / "got") + " --json");
  EXPECT_EQ(fetched.exit_code, 0) << fetched.err;
  const nlohmann::json files = nlohmann::json::parse(fetched.out);
  ASSERT_EQ(files.at("fetched").size(), 1u) << fetched.out;
  EXPECT_EQ(files["fetched"][0].at("name"), "results.json");
  EXPECT_EQ(files["fetched"][0].at("bytes").get<std::uintmax_t>(), fs::file_size(dir_ / "got" / "results.json"));
  EXPECT_TRUE(files.at("notFetched").empty());

  const Result missing =
      dem("fetch " + std::to_string(id) + " nothere.dat --out " + shell_quoted(dir_ / "got") + " --json");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(nlohmann::json::parse(missing.out).at("notFetched")[0].at("name"), "nothere.dat") << missing.out;

  nlohmann::json long_spec = nlohmann::json::parse(short_demo_spec());
  long_spec["time"]["duration"] = 20;  // still running when cancelled
  const long queued = submit(write_file("long.json", long_spec.dump()));
  const Result cancelled = dem("cancel " + std::to_string(queued) + " --json");
  EXPECT_EQ(cancelled.exit_code, 0) << cancelled.err;
  EXPECT_EQ(nlohmann::json::parse(cancelled.out).at("id").get<long>(), queued) << cancelled.out;
  for (const char* verb : {"status", "list"}) {
    const Result r =
        dem(std::string(verb) + (std::string(verb) == "status" ? " " + std::to_string(id) : "") + " --json");
    EXPECT_EQ(r.exit_code, 0) << verb << r.err;
    EXPECT_TRUE(nlohmann::json::accept(r.out)) << verb << ": " << r.out;
  }
}

// CLI11 reads the command lines: --option=value is taken, and an option given twice is refused
// naming it (the last one was kept, silently).
TEST_F(ClientVerbs, AnOptionTakesEqualsAndIsRefusedTwice) {
  start_server();
  EXPECT_EQ(dem("list --state=queued").exit_code, 0);
  const Result twice = dem("list --name a --name b");
  EXPECT_EQ(twice.exit_code, 2);
  EXPECT_TRUE(has(twice.err, "--name is given 2 times (once at most)")) << twice.err;
}

}  // namespace
}  // namespace dem::test
