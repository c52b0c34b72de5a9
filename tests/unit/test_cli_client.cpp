// Tests of the dem command's client verbs (cli/client_commands.cpp) that need no server: bad
// arguments, a server nobody answers for, and specs refused before anything is sent. They run the
// built binary as tests/unit/test_cli.cpp does; tests/server/test_client_verbs.cpp drives a real
// dem-server.
#include <gtest/gtest.h>

#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

const std::string kDem = DEM_BINARY_DIR "/dem";

struct Result {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// A path in single quotes for the shell (test paths hold no quote). Built by appending: GCC 12
// warns falsely (-Wrestrict) about "'" + string.
std::string shell_quoted(const fs::path& p) {
  std::string s = "'";
  s += p.string();
  s += "'";
  return s;
}

// Runs `dem ARGS` through the shell, capturing both streams. DEM_SERVER and DEM_SERVER_TOKEN are
// cleared so that the caller's environment does not pick the server.
Result dem(const std::string& args, const std::string& environment = "") {
  Result r;
  const std::string command =
      "env -u DEM_SERVER -u DEM_SERVER_TOKEN " + environment + " " + shell_quoted(kDem) + " " + args + " 2>&1";
  std::FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) {
    ADD_FAILURE() << "popen failed for " << command;
    return r;
  }
  char buffer[4096];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) r.output.append(buffer, n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

bool has(const Result& r, const std::string& text) { return r.output.find(text) != std::string::npos; }

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

class CliClient : public testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(kDem)) << kDem << " is not built";
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("dem_cli_client_" + std::string(info->name()) + "_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write_spec(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    std::ofstream(path) << text;
    return path;
  }

  fs::path dir_;
};

// ---------------------------------------------------------------------------------------------
// bad arguments: exit 2 with the verb's usage line

TEST_F(CliClient, HelpListsTheClientVerbs) {
  const Result r = dem("help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* verb : {"dem submit", "dem status", "dem list", "dem cancel", "dem resume", "dem watch", "dem fetch",
                           "--server URL", "DEM_SERVER"})
    EXPECT_TRUE(has(r, verb)) << verb << " is not in\n" << r.output;
}

TEST_F(CliClient, SubmitWithoutASpecIsAUsageError) {
  const Result r = dem("submit");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r, "usage: dem submit SPEC.json")) << r.output;
}

TEST_F(CliClient, SubmitOfTwoSpecsIsAUsageError) {
  const Result r = dem("submit a.json b.json");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r, "\"b.json\"")) << r.output;
}

TEST_F(CliClient, AnUnknownOptionIsAUsageError) {
  const Result r = dem("watch 1 --fast");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r, "unknown option --fast")) << r.output;
  EXPECT_TRUE(has(r, "usage: dem watch ID")) << r.output;
}

TEST_F(CliClient, AJobIdIsAWholeNumber) {
  for (const char* verb : {"status", "cancel", "resume", "watch", "fetch"}) {
    const Result r = dem(std::string(verb) + " twelve");
    EXPECT_EQ(r.exit_code, 2) << verb << ": " << r.output;
    EXPECT_TRUE(has(r, "a job id is a whole number (got \"twelve\")")) << verb << ": " << r.output;
  }
}

TEST_F(CliClient, VerbsOfOneJobNeedItsId) {
  for (const char* verb : {"status", "cancel", "resume", "watch", "fetch"}) {
    const Result r = dem(verb);
    EXPECT_EQ(r.exit_code, 2) << verb << ": " << r.output;
    EXPECT_TRUE(has(r, "missing the job id")) << verb << ": " << r.output;
  }
  EXPECT_EQ(dem("cancel 1 2").exit_code, 2);
}

TEST_F(CliClient, ListOfAnUnknownStateIsAUsageError) {
  const Result r = dem("list --state done");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r, "--state is one of queued, running")) << r.output;
  EXPECT_TRUE(has(r, "(got \"done\")")) << r.output;
}

TEST_F(CliClient, FetchRefusesANameOutsideTheOutputFolder) {
  const Result r = dem("fetch 1 ../ANIMATION_3D.dat --out " + shell_quoted(dir_));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r, "\"../ANIMATION_3D.dat\" is not an artifact name")) << r.output;
}

TEST_F(CliClient, AnOptionWithoutItsValueIsAUsageError) {
  for (const char* args : {"status 1 --server", "status 1 --token", "fetch 1 --out", "list --state",
                           "submit s.json --idempotency-key"}) {
    const Result r = dem(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_TRUE(has(r, "needs a value")) << args << ": " << r.output;
  }
}

TEST_F(CliClient, AServerThatIsNotHttpIsAUsageError) {
  const Result r = dem("list --server https://example.org");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r, "only http:// is supported")) << r.output;
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
