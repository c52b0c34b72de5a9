// The dem command's client verbs against a server that is not ours and not friendly: what it sends
// is input like any other. `dem fetch` without names wrote every artifact name the server listed,
// "../x" and absolute paths included, outside --out (an independent tester's finding); `dem list`
// printed job names with terminal escape sequences as they came.
#include <gtest/gtest.h>

#include <boost/asio.hpp>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

#include "support/command.hpp"

namespace dem::test {
namespace {

namespace fs = std::filesystem;
namespace asio = boost::asio;
using asio::ip::tcp;

// Answers every request on a loopback port, one request a connection: with what `answer(target)`
// gives (status 200, JSON when it starts with '{'), or as `behave(socket, target)` does.
class ScriptedServer {
 public:
  using Behaviour = std::function<void(tcp::socket&, const std::string&, const std::atomic<bool>& stopping)>;
  explicit ScriptedServer(std::function<std::string(const std::string&)> answer)
      : ScriptedServer(Behaviour([answer](tcp::socket& socket, const std::string& target, const std::atomic<bool>&) {
          const std::string body = answer(target);
          const std::string head = "HTTP/1.1 200 OK\r\nContent-Type: " +
                                   std::string(!body.empty() && body[0] == '{' ? "application/json" : "text/plain") +
                                   "\r\nContent-Length: " + std::to_string(body.size()) +
                                   "\r\nConnection: close\r\n\r\n";
          boost::system::error_code ec;
          asio::write(socket, asio::buffer(head + body), ec);
        })) {}
  explicit ScriptedServer(Behaviour behave)
      : behave_(std::move(behave)), acceptor_(io_, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0)) {
    thread_ = std::thread([this] { serve(); });
  }
  ~ScriptedServer() {
    stopping_ = true;
    boost::system::error_code ignored;
    tcp::socket poke(io_);
    poke.connect(acceptor_.local_endpoint(), ignored);  // wakes the accept
    thread_.join();
  }
  std::string url() const { return "http://127.0.0.1:" + std::to_string(acceptor_.local_endpoint().port()); }

 private:
  void serve() {
    while (!stopping_) {
      tcp::socket socket(io_);
      boost::system::error_code ec;
      acceptor_.accept(socket, ec);
      if (ec || stopping_) continue;
      asio::streambuf request;
      asio::read_until(socket, request, "\r\n\r\n", ec);
      if (ec) continue;
      std::istream lines(&request);
      std::string method, target;
      lines >> method >> target;
      behave_(socket, target, stopping_);
    }
  }

  Behaviour behave_;
  asio::io_context io_;
  tcp::acceptor acceptor_;
  std::atomic<bool> stopping_{false};
  std::thread thread_;
};

class ClientAgainstHostileServer : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dem_hostile_server_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "deep" / "out");
  }
  void TearDown() override { fs::remove_all(dir_); }
  CommandResult dem(const std::string& args, const std::string& url) {
    return run_command("env -u DEM_SERVER -u DEM_SERVER_TOKEN " + shell_quoted(DEM_BINARY_DIR "/dem") + " " + args +
                       " --server " + url);
  }
  fs::path dir_;
};

TEST_F(ClientAgainstHostileServer, FetchWritesOnlyPlainFileNamesInsideItsFolder) {
  const fs::path absolute = dir_ / "absolute.dat";
  ScriptedServer server([&](const std::string& target) -> std::string {
    if (target == "/api/v1/jobs/1/artifacts")
      return R"({"artifacts": [{"name": "../escaped.dat"}, {"name": ")" + absolute.string() +
             R"("}, {"name": ".."}, {"name": "good.dat"}]})";
    return "file contents\n";
  });
  const CommandResult r = dem("fetch 1 --out " + shell_quoted(dir_ / "deep" / "out"), server.url());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(fs::exists(dir_ / "deep" / "out" / "good.dat")) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "deep" / "escaped.dat")) << r.output;
  EXPECT_FALSE(fs::exists(absolute)) << r.output;
  EXPECT_NE(r.output.find("../escaped.dat"), std::string::npos) << "the refused name is named: " << r.output;
}

TEST_F(ClientAgainstHostileServer, ListAndStatusPrintNoControlCharacters) {
  const std::string job =
      R"({"id": 1, "name": "a\u001b]0;owned\u0007\u001b[2Jname\r\nfake line\u202etxt.exe", "state": "succeeded", "step": 1,)"
      R"( "totalSteps": 1, "progress": 1})";
  ScriptedServer server([&](const std::string& target) -> std::string {
    if (target.rfind("/api/v1/jobs?", 0) == 0) return R"({"jobs": [)" + job + "]}";
    return job;
  });
  for (const std::string verb : {"list", "status 1"}) {
    const CommandResult r = dem(verb, server.url());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output.find('\x1b'), std::string::npos) << verb << ": " << r.output;
    EXPECT_EQ(r.output.find('\x07'), std::string::npos) << verb << ": " << r.output;
    EXPECT_EQ(r.output.find('\r'), std::string::npos) << verb << ": " << r.output;
    EXPECT_EQ(r.output.find("\xe2\x80\xae"), std::string::npos) << verb << ": a right-to-left override";
    EXPECT_NE(r.output.find("name"), std::string::npos) << verb << ": " << r.output;
  }
}

// A job list whose next page is one already read (a loop) is an error, not an endless listing.
TEST_F(ClientAgainstHostileServer, ListStopsAtANextPageThatLoops) {
  ScriptedServer server([&](const std::string& target) -> std::string {
    if (target.find("after=2") != std::string::npos)
      return R"({"jobs": [{"id": 3}], "next": "/api/v1/jobs?limit=200&after=1"})";
    return R"({"jobs": [{"id": 1}], "next": "/api/v1/jobs?limit=200&after=2"})";
  });
  const CommandResult r = dem("list", server.url());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("a page already read"), std::string::npos) << r.output;
}

// A server that accepts and never answers, or answers without end: the client gives up with a
// message (it waited for ever, or read an endless body into memory until bad_alloc at 2 GB).
TEST_F(ClientAgainstHostileServer, ASilentServerIsGivenUpOnAtTheTimeout) {
  ScriptedServer silent([](tcp::socket&, const std::string&, const std::atomic<bool>& stopping) {
    while (!stopping) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  });
  const auto start = std::chrono::steady_clock::now();
  const CommandResult r = dem("status 1 --timeout 1", silent.url());
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("did not answer in time"), std::string::npos) << r.output;
  EXPECT_LT(waited, 10) << r.output;
  EXPECT_EQ(dem("status 1 --timeout nope", silent.url()).exit_code, 2);
}

// A study the server takes long to check (each run's scene is built): the client gives up at its
// timeout, and says the key with which the same command gets the study the server may go on to
// make, instead of making a second one (it sent no key, and the study it gave up on was made anyway:
// an independent tester).
TEST_F(ClientAgainstHostileServer, AStudyGivenUpOnNamesTheKeyThatGetsIt) {
  ScriptedServer silent([](tcp::socket&, const std::string&, const std::atomic<bool>& stopping) {
    while (!stopping) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  });
  const std::string base = R"({"materials": [{"name": "glass", "density": 2500, "normalStiffness": 1e5}],
    "interactions": [{"a": "glass", "b": "glass", "restitution": 0.5, "friction": 0.3}],
    "particles": [{"radius": 0.01, "material": "glass"}], "time": {"steps": 10}})";
  std::ofstream(dir_ / "base.json") << base;
  std::ofstream(dir_ / "study.json")
      << R"({"base": "base.json", "parameters": [{"path": "particles[0].radius", "values": [0.01, 0.02]}]})";
  const std::string submit =
      "study " + shell_quoted(dir_ / "study.json") + " --submit --timeout 1 --out " + shell_quoted(dir_ / "out");
  CommandResult r = dem(submit, silent.url());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("did not answer in time; the server may still make the study: the same command with "
                          "--idempotency-key dem-study-"),
            std::string::npos)
      << r.output;
  r = dem(submit + " --idempotency-key bed-1", silent.url());
  EXPECT_NE(r.output.find("the same command with --idempotency-key bed-1 gives that study"), std::string::npos)
      << r.output;
}

TEST_F(ClientAgainstHostileServer, AnEndlessAnswerIsCutOff) {
  ScriptedServer endless([](tcp::socket& socket, const std::string&, const std::atomic<bool>& stopping) {
    boost::system::error_code ec;
    asio::write(socket,
                asio::buffer(std::string("HTTP/1.1 200 OK\r\nContent-Type: application/json\r\n"
                                         "Transfer-Encoding: chunked\r\n\r\n")),
                ec);
    const std::string chunk = "100000\r\n" + std::string(0x100000, ' ') + "\r\n";  // 1 MB a chunk
    while (!ec && !stopping) asio::write(socket, asio::buffer(chunk), ec);
  });
  // under `timeout` (not `ulimit -v`, which a sanitizer's shadow memory cannot start under): a client
  // without the cap reads on until it is killed
  const CommandResult r = run_command("timeout 60 env -u DEM_SERVER -u DEM_SERVER_TOKEN " +
                                      shell_quoted(DEM_BINARY_DIR "/dem") + " list --server " + endless.url());
  EXPECT_EQ(r.exit_code, 1) << r.output.substr(0, 500);
  EXPECT_NE(r.output.find("MB, more than any answer of dem-server"), std::string::npos) << r.output.substr(0, 500);
}

// Names the server's own rule would never make: a line break, ESC, a right-to-left mark, a space.
// None becomes a file; the good one still does.
TEST_F(ClientAgainstHostileServer, FetchRefusesNamesOutsideTheServersOwnRule) {
  ScriptedServer server([&](const std::string& target) -> std::string {
    if (target == "/api/v1/jobs/1/artifacts")
      return R"({"artifacts": [{"name": "a\nb.dat"}, {"name": "c\u001b[2Jd.dat"}, {"name": "e\u202ef.dat"},)"
             R"( {"name": "g h.dat"}, {"name": "good.dat"}]})";
    return "file contents\n";
  });
  const CommandResult r = dem("fetch 1 --out " + shell_quoted(dir_ / "deep" / "out"), server.url());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  std::vector<std::string> made;
  for (const auto& e : fs::directory_iterator(dir_ / "deep" / "out")) made.push_back(e.path().filename().string());
  EXPECT_EQ(made, std::vector<std::string>{"good.dat"}) << r.output;
  EXPECT_EQ(r.output.find('\x1b'), std::string::npos) << r.output;
}

// A field of the wrong type (a null name) is said in words, not as a JSON library's exception.
TEST_F(ClientAgainstHostileServer, AnAnswerOfTheWrongFormIsSaidSo) {
  ScriptedServer server(
      [](const std::string&) -> std::string { return R"({"jobs": [{"id": 1, "name": null, "state": "queued"}]})"; });
  const CommandResult r = dem("list", server.url());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("not of dem-server's form"), std::string::npos) << r.output;
}

// An independent tester's findings on --json: `status --json` printed any 200 answer (a proxy's
// page, `null`) and exited 0; an object that is no job was taken as one by submit and cancel.
TEST_F(ClientAgainstHostileServer, JsonIsPrintedOnlyWhenItIsAJob) {
  for (const std::string body : {"<html>a proxy's page</html>", "null", "[]", "{}", R"({"id": "7", "state": 1})"}) {
    ScriptedServer server([&](const std::string&) { return body; });
    for (const std::string verb : {"status 1 --json", "status 1", "cancel 1 --json", "resume 1"}) {
      const CommandResult r = dem(verb + " 2>&1", server.url());
      EXPECT_EQ(r.exit_code, 1) << verb << " given " << body << ": " << r.output;
      EXPECT_TRUE(r.output.find("not of dem-server's form") != std::string::npos ||
                  r.output.find("not JSON") != std::string::npos)
          << verb << ": " << r.output;
    }
  }
}

// Every verb speaks /api/v1/ (a proxy that routes only the versioned paths): submit, status,
// cancel and fetch used the unversioned alias.
TEST_F(ClientAgainstHostileServer, EveryVerbUsesTheVersionedPaths) {
  std::vector<std::string> targets;
  std::mutex seen;
  ScriptedServer server([&](const std::string& target) -> std::string {
    const std::lock_guard<std::mutex> lock(seen);
    targets.push_back(target);
    if (target == "/api/v1/jobs/1/artifacts") return R"({"artifacts": [{"name": "a.dat"}]})";
    if (target.rfind("/api/v1/jobs/1/artifacts/", 0) == 0) return "1 2 3\n";
    return R"({"id": 1, "state": "succeeded", "name": "x", "step": 1, "totalSteps": 1})";
  });
  for (const std::string verb : {"status 1", "cancel 1", "resume 1", "watch 1"})
    EXPECT_EQ(dem(verb, server.url()).exit_code, 0) << verb;
  EXPECT_EQ(dem("fetch 1 --out " + shell_quoted(dir_ / "deep" / "out"), server.url()).exit_code, 0);
  const std::lock_guard<std::mutex> lock(seen);  // the server's thread writes the list
  for (const std::string& target : targets) EXPECT_EQ(target.rfind("/api/v1/", 0), 0u) << target;
}

// A local file that cannot be written is one file not fetched: the others are, --json lists it,
// and no .part is left (it ended the verb with no JSON and a .part behind).
TEST_F(ClientAgainstHostileServer, AFileThatCannotBeWrittenIsListedAsNotFetched) {
  ScriptedServer server([&](const std::string& target) -> std::string {
    if (target == "/api/v1/jobs/1/artifacts") return R"({"artifacts": [{"name": "a.dat"}, {"name": "b.dat"}]})";
    return "1 2 3\n";
  });
  const fs::path out = dir_ / "deep" / "out";
  fs::create_directories(out / "a.dat" / "in-the-way");  // a folder where a.dat would go
  const CommandResult r = dem("fetch 1 --json --out " + shell_quoted(out) + " 2>/dev/null", server.url());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(fs::is_regular_file(out / "b.dat"));
  EXPECT_FALSE(fs::exists(out / "a.dat.part"));
  const nlohmann::json listed = nlohmann::json::parse(r.output);
  ASSERT_EQ(listed.at("notFetched").size(), 1u) << r.output;
  EXPECT_EQ(listed["notFetched"][0].at("name"), "a.dat");
  EXPECT_EQ(listed.at("fetched").size(), 1u) << r.output;
}

// What would go into a request's headers is checked first: a line break in the token or the
// idempotency key sent a header of its own (X-Evil); a path or a password in --server was dropped.
TEST_F(ClientAgainstHostileServer, HeaderValuesAndServerUrlsAreCheckedBeforeSending) {
  std::atomic<int> requests{0};
  ScriptedServer server([&](const std::string&) {
    ++requests;
    return std::string(R"({"jobs": []})");
  });
  const std::string evil = "'abc\r\nX-Evil: 1'";
  for (const std::string& args :
       std::vector<std::string>{"list --token " + evil, "submit x.json --idempotency-key " + evil}) {
    const CommandResult r = dem(args + " 2>&1", server.url());
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find("control character"), std::string::npos) << r.output;
  }
  const CommandResult from_env =
      run_command("DEM_SERVER_TOKEN=$(printf 'a\\r\\nX-Evil: 1') " + shell_quoted(DEM_BINARY_DIR "/dem") +
                  " list --server " + server.url() + " 2>&1");
  EXPECT_EQ(from_env.exit_code, 2) << from_env.output;
  EXPECT_NE(from_env.output.find("DEM_SERVER_TOKEN"), std::string::npos) << from_env.output;
  for (const std::string& url : std::vector<std::string>{server.url() + "/prefix/", "http://user:pw@127.0.0.1:1"}) {
    const CommandResult r = run_command(shell_quoted(DEM_BINARY_DIR "/dem") + " list --server " + url + " 2>&1");
    EXPECT_EQ(r.exit_code, 2) << url << ": " << r.output;
    EXPECT_EQ(r.output.find("pw"), std::string::npos) << "the password is echoed: " << r.output;
  }
  EXPECT_EQ(requests.load(), 0);
}

}  // namespace
}  // namespace dem::test
