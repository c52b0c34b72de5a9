// Tests of the dem command's client verbs (cli/client_commands.cpp) that need no server: bad
// arguments, a server nobody answers for, and specs refused before anything is sent. They run the
// built binary as tests/unit/test_cli.cpp does; tests/server/test_client_verbs.cpp drives a real
// dem-server.
#include <gtest/gtest.h>

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <initializer_list>
#include <string>

#include "support/command.hpp"

namespace test_cli_client {
namespace {

using dem::test::kDem;
using dem::test::shell_quoted;
using Result = dem::test::CommandResult;

// Runs `dem ARGS` through the shell, capturing both streams. DEM_SERVER and DEM_SERVER_TOKEN are
// cleared so that the caller's environment does not pick the server.
Result dem(const std::string& args, const std::string& environment = "") {
  return dem::test::run_command("env -u DEM_SERVER -u DEM_SERVER_TOKEN " + environment + " " + shell_quoted(kDem) +
                                " " + args);
}

bool has(const Result& r, const std::string& text) { return r.output.find(text) != std::string::npos; }

// `dem ARGS` is a usage error: exit status 2, and its output holds each of `texts`.
void expect_usage_error(const std::string& args, std::initializer_list<std::string> texts) {
  const Result r = dem(args);
  EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
  for (const std::string& text : texts) EXPECT_TRUE(has(r, text)) << args << ": " << r.output;
}

// A loopback port nobody listens on: the kernel's pick for a socket that is closed at once.
int free_port() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = 0;
  socklen_t size = sizeof address;
  if (fd < 0 || bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
      getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size) != 0) {
    ADD_FAILURE() << "cannot find a free port";
    if (fd >= 0) close(fd);
    return 1;
  }
  close(fd);
  return ntohs(address.sin_port);
}

const char* kGoodSpec = R"({
  "materials": [{"name": "glass", "density": 2500, "normalStiffness": 1e5}],
  "interactions": [{"a": "glass", "b": "glass", "restitution": 0.5, "friction": 0.3}],
  "particles": [
    {"position": {"x": 0}, "radius": 0.01, "material": "glass"},
    {"position": {"x": 0.03}, "radius": 0.01, "material": "glass"}
  ],
  "time": {"steps": 12}
})";

// A private folder per test, removed afterwards.
class CliClient : public dem::test::DemCommandTest {};

// ---------------------------------------------------------------------------------------------
// bad arguments: exit 2 with the verb's usage line

TEST_F(CliClient, HelpListsTheClientVerbs) {
  const Result r = dem("help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* verb : {"dem submit", "dem status", "dem list", "dem cancel", "dem resume", "dem watch", "dem fetch",
                           "--server URL", "DEM_SERVER"})
    EXPECT_TRUE(has(r, verb)) << verb << " is not in\n" << r.output;
}

TEST_F(CliClient, SubmitWithoutASpecIsAUsageError) { expect_usage_error("submit", {"usage: dem submit SPEC.json"}); }

TEST_F(CliClient, SubmitOfTwoSpecsIsAUsageError) { expect_usage_error("submit a.json b.json", {"\"b.json\""}); }

TEST_F(CliClient, AnUnknownOptionIsAUsageError) {
  expect_usage_error("watch 1 --fast", {"unknown option --fast", "usage: dem watch ID"});
}

TEST_F(CliClient, AJobIdIsAWholeNumber) {
  for (const char* verb : {"status", "cancel", "resume", "watch", "fetch"})
    expect_usage_error(std::string(verb) + " twelve", {"a job id is a whole number (got \"twelve\")"});
}

TEST_F(CliClient, VerbsOfOneJobNeedItsId) {
  for (const char* verb : {"status", "cancel", "resume", "watch", "fetch"})
    expect_usage_error(verb, {"missing the job id"});
  EXPECT_EQ(dem("cancel 1 2").exit_code, 2);
}

TEST_F(CliClient, ListOfAnUnknownStateIsAUsageError) {
  expect_usage_error("list --state done", {"--state is one or more of queued, running", "(got \"done\")"});
  expect_usage_error("list --state succeeded,,failed", {"(got \"\")"});
}

TEST_F(CliClient, FetchRefusesANameOutsideTheOutputFolder) {
  expect_usage_error("fetch 1 ../ANIMATION_3D.dat --out " + shell_quoted(dir_),
                     {"\"../ANIMATION_3D.dat\" is not an artifact name"});
}

TEST_F(CliClient, AnOptionWithoutItsValueIsAUsageError) {
  for (const char* args :
       {"status 1 --server", "status 1 --token", "fetch 1 --out", "list --state", "submit s.json --idempotency-key"})
    expect_usage_error(args, {"needs a value"});
}

TEST_F(CliClient, AServerThatIsNotHttpIsAUsageError) {
  expect_usage_error("list --server https://example.org", {"only http:// is supported"});
}

// ---------------------------------------------------------------------------------------------
// a server that cannot be reached: exit 1 with one line naming its URL

TEST_F(CliClient, EveryVerbNamesAServerItCannotReach) {
  const std::string url = "http://127.0.0.1:" + std::to_string(free_port());
  const std::string spec = shell_quoted(write_spec("good.json", kGoodSpec));
  for (const std::string& args : {"submit " + spec, "submit " + spec + " --wait --quiet", std::string("status 1"),
                                  std::string("list"), std::string("cancel 1"), std::string("resume 1"),
                                  std::string("watch 1"), "fetch 1 --out " + shell_quoted(dir_ / "out")}) {
    const Result r = dem(args + " --server " + url);
    EXPECT_EQ(r.exit_code, 1) << args << ": " << r.output;
    EXPECT_TRUE(has(r, "cannot reach the server at " + url)) << args << ": " << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << args << ": " << r.output;
  }
}

TEST_F(CliClient, TheServerComesFromDemServerWhenNotGiven) {
  const std::string url = "http://127.0.0.1:" + std::to_string(free_port());
  const Result r = dem("status 7", "DEM_SERVER=" + url);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has(r, "cannot reach the server at " + url)) << r.output;
  // --server wins over the environment
  const std::string other = "http://127.0.0.1:" + std::to_string(free_port());
  const Result r2 = dem("status 7 --server " + other, "DEM_SERVER=" + url);
  EXPECT_TRUE(has(r2, other)) << r2.output;
}

// ---------------------------------------------------------------------------------------------
// specs refused before anything is sent

TEST_F(CliClient, SubmitOfAMissingMeshFileNamesTheField) {
  const std::string spec = R"({
  "materials": [{"name": "glass", "density": 2500, "normalStiffness": 1e5}, {"name": "steel", "rigid": true}],
  "interactions": [{"a": "glass", "b": "steel", "restitution": 0.5, "friction": 0.3}],
  "particles": [{"position": {"z": 0.02}, "radius": 0.01, "material": "glass"}],
  "walls": [{"name": "floor", "material": "steel", "mesh": {"file": "no-such-floor.stl"}}],
  "time": {"steps": 12}
})";
  const std::string url = "http://127.0.0.1:" + std::to_string(free_port());
  const Result r = dem("submit " + shell_quoted(write_spec("mesh.json", spec)) + " --server " + url);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has(r, "walls[0].mesh.file")) << r.output;
  EXPECT_TRUE(has(r, "no-such-floor.stl")) << r.output;
  EXPECT_FALSE(has(r, "cannot reach")) << "the spec should be refused before contacting the server:\n" << r.output;
}

TEST_F(CliClient, SubmitOfAMissingSpecFileNamesIt) {
  const Result r = dem("submit " + shell_quoted(dir_ / "missing.json") + " --server http://127.0.0.1:1");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has(r, "missing.json: cannot open the spec file")) << r.output;
}

TEST_F(CliClient, SubmitOfAnUnknownFieldNamesIt) {
  std::string text = kGoodSpec;
  text.replace(text.find("\"radius\""), 8, "\"raduis\"");
  const Result r = dem("submit " + shell_quoted(write_spec("bad.json", text)) + " --server http://127.0.0.1:1");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has(r, "raduis")) << r.output;
  EXPECT_FALSE(has(r, "cannot reach")) << r.output;
}

}  // namespace
}  // namespace test_cli_client
