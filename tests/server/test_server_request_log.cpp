// The server's log: a line per request answered (the client, the request line, the status, the
// bytes sent, the time taken) with the time of day, to standard error and DATA/server.log, never
// with the access token (a query's access_token is redacted, headers are not logged); and the
// server's own messages in the same log.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <regex>

#include "dem/version.hpp"
#include "support/raw_http.hpp"
#include "support/server_test.hpp"

namespace dem::test {
namespace {

const std::string kLogToken = "s3cr3t-t0ken-0123456789abcdef";

class ServerRequestLog : public ServerTest {
 protected:
  void start_logged_server(const std::vector<std::string>& extra = {}, const fs::path& stderr_file = {}) {
    server_ =
        std::make_unique<ServerProcess>(dir_ / "data", extra, stderr_file.empty() ? dir_ / "stderr.txt" : stderr_file);
    client_ = std::make_unique<client::HttpClient>(server_->url());
  }
  std::string server_log() { return read_bytes(dir_ / "data" / "server.log"); }
  // The log once it holds `text`: a request's line is written when its answer has been sent, which
  // may be just after the client has read it (at most 10 s).
  std::string server_log_with(const std::string& text) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    std::string log = server_log();
    while (log.find(text) == std::string::npos && std::chrono::steady_clock::now() < end) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      log = server_log();
    }
    return log;
  }
  // The log's lines that hold `text`.
  static std::vector<std::string> lines_with(const std::string& log, const std::string& text) {
    std::vector<std::string> found;
    std::istringstream in(log);
    for (std::string line; std::getline(in, line);)
      if (line.find(text) != std::string::npos) found.push_back(line);
    return found;
  }
};

// "2026-12-06T06:29:48.578Z [info] 127.0.0.1 "GET /api/v1/health HTTP/1.1" 200 331 0.12 ms"
const std::regex kRequestLine(
    R"re(^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z \[info\] (\S+) "(\S+) (\S+) (\S+)" (\d{3}|-) (\d+|-) (\d+\.\d\d) ms$)re");

TEST_F(ServerRequestLog, EachRequestAnsweredIsALineWithItsClientStatusBytesAndTime) {
  start_logged_server();
  const client::Response health = client_->get("/api/v1/health");
  ASSERT_EQ(health.status, 200);
  EXPECT_EQ(client_->get("/api/v1/jobs/999").status, 404);
  EXPECT_EQ(client_->request("HEAD", "/api/v1/health").status, 200);
  const std::string log = server_log_with("\"HEAD /api/v1/health HTTP/1.1\"");

  const std::vector<std::string> lines = lines_with(log, "\"GET /api/v1/health HTTP/1.1\"");
  ASSERT_EQ(lines.size(), 1u) << log;
  std::smatch m;
  ASSERT_TRUE(std::regex_match(lines[0], m, kRequestLine)) << lines[0];
  EXPECT_EQ(m[1], "127.0.0.1");
  EXPECT_EQ(m[5], "200");
  // the bytes sent: the body and a header of a few hundred bytes
  const std::size_t bytes = std::stoul(m[6]);
  EXPECT_GT(bytes, health.body.size());
  EXPECT_LT(bytes, health.body.size() + 1000);
  EXPECT_LT(std::stod(m[7]), 5000.0);

  const std::vector<std::string> missing = lines_with(log, "\"GET /api/v1/jobs/999 HTTP/1.1\" 404 ");
  EXPECT_EQ(missing.size(), 1u) << log;
  const std::vector<std::string> head = lines_with(log, "\"HEAD /api/v1/health HTTP/1.1\" 200 ");
  EXPECT_EQ(head.size(), 1u) << log;
  // the server's own messages are in the same log, and everything is on its standard error too
  EXPECT_FALSE(lines_with(log, "[info] dem-server " + std::string(kVersion) + " listening on").empty()) << log;
  const std::string stderr_text = read_bytes(dir_ / "stderr.txt");
  for (const std::string& line : lines) EXPECT_NE(stderr_text.find(line), std::string::npos) << stderr_text;
}

TEST_F(ServerRequestLog, TheTokenIsNeverLoggedAndRefusalsAreLoggedToo) {
  start_logged_server({"--token", kLogToken});
  client::HttpClient with_token(server_->url(), kLogToken);
  EXPECT_EQ(with_token.get("/api/v1/health").status, 200);  // Authorization: Bearer
  EXPECT_EQ(client_->get("/api/v1/health?access_token=" + kLogToken).status, 200);
  // the name escaped, as the server reads it; and with another parameter around it
  EXPECT_EQ(client_->get("/api/v1/jobs?limit=5&access%5Ftoken=" + kLogToken + "&state=queued").status, 200);
  EXPECT_EQ(client_->get("/api/v1/health?access_token=" + kLogToken + "-wrong").status, 401);
  EXPECT_EQ(client_->get("/api/v1/health").status, 401);
  // a browser's page keeps the token in a cookie: headers are not logged
  EXPECT_EQ(client_->request("GET", "/api/v1/health", "", "", {{"Cookie", "dem_token=" + kLogToken}}).status, 200);
  EXPECT_EQ(client_->get("/api/v1/health?last").status, 401);  // the last line: all before it are in
  const std::string log = server_log_with("\"GET /api/v1/health?last HTTP/1.1\"");
  const std::string stderr_text = read_bytes(dir_ / "stderr.txt");
  EXPECT_EQ(log.find(kLogToken), std::string::npos) << log;
  EXPECT_EQ(log.find("s3cr3t"), std::string::npos) << log;
  EXPECT_EQ(stderr_text.find("s3cr3t"), std::string::npos) << stderr_text;
  EXPECT_EQ(lines_with(log, "\"GET /api/v1/health?access_token=REDACTED HTTP/1.1\" 200 ").size(), 1u) << log;
  EXPECT_EQ(lines_with(log, "\"GET /api/v1/jobs?limit=5&access%5Ftoken=REDACTED&state=queued HTTP/1.1\" 200 ").size(),
            1u)
      << log;
  EXPECT_EQ(lines_with(log, "\"GET /api/v1/health?access_token=REDACTED HTTP/1.1\" 401 ").size(), 1u) << log;
  EXPECT_EQ(lines_with(log, "\"GET /api/v1/health HTTP/1.1\" 401 ").size(), 1u) << log;
  EXPECT_EQ(lines_with(log, "\"GET /api/v1/health HTTP/1.1\" 200 ").size(), 2u) << log;  // bearer, cookie
}

// What a request line cannot hold is escaped (a log line stays one line with its own quotes), and a
// request refused before its header was read says "-" for what it does not know.
TEST_F(ServerRequestLog, OddTargetsAreEscapedAndUnreadRequestsAreLoggedWithDashes) {
  start_logged_server({"--request-timeout", "1"});
  EXPECT_EQ(status_of(raw_exchange(server_->port(),
                                   "GET /api/v1/jobs?name=%22a%22&x=\"quoted\"&y=\xC3\xA9 HTTP/1.1\r\n"
                                   "Host: 127.0.0.1\r\n"
                                   "Connection: close\r\n\r\n")),
            400);
  {
    RawConnection slow(server_->port());
    slow.send("GET /api/v1/health HTTP/1.1\r\nHo");  // never finished: 408 after a second
    EXPECT_EQ(status_of(slow.receive(10)), 408);
  }
  const std::string log = server_log_with(R"("- - -" 408 )");
  EXPECT_EQ(lines_with(log, R"("GET /api/v1/jobs?name=%22a%22&x=\x22quoted\x22&y=\xC3\xA9 HTTP/1.1" 400 )").size(), 1u)
      << log;
  const std::vector<std::string> unread = lines_with(log, R"("- - -" 408 )");
  ASSERT_EQ(unread.size(), 1u) << log;
  std::smatch m;
  EXPECT_TRUE(std::regex_match(unread[0], m, kRequestLine)) << unread[0];
}

// The server's messages that were bare lines on its standard error (here: a job folder the job
// table has no row for, moved aside) are in its log with the time and the level.
TEST_F(ServerRequestLog, TheServersMessagesAreLoggedWithTheirLevel) {
  fs::create_directories(dir_ / "data" / "jobs" / "77" / "outputs");
  write_text(dir_ / "data" / "jobs" / "77" / "outputs" / "ANIMATION_3D.dat", "1 2 3\n");
  start_logged_server();
  const std::vector<std::string> moved = lines_with(server_log_with("moved to"), "has no row for it: moved to");
  ASSERT_EQ(moved.size(), 1u) << server_log();
  EXPECT_TRUE(std::regex_search(moved[0], std::regex(R"(^\d{4}-\d\d-\d\dT[\d:.]+Z \[warning\] )"))) << moved[0];
}

// An independent tester's findings. A target that holds the token other than as a query's
// access_token went into the log as it was: a client that appends "?access_token=" to a URL that
// has a query already, an escaped "=", a user's password in an absolute URL.
TEST_F(ServerRequestLog, TheTokenIsNotLoggedHoweverTheTargetHoldsIt) {
  start_logged_server({"--token", kLogToken});
  for (const std::string& target : std::vector<std::string>{
           "/api/v1/health?x=1?access_token=" + kLogToken, "/api/v1/health?access_token%3D" + kLogToken,
           "/api/v1/health;access_token=" + kLogToken, "/api/v1/health?" + kLogToken + "=access_token",
           "http://user:" + kLogToken + "@127.0.0.1/api/v1/health"}) {
    RawConnection raw(server_->port());
    raw.send("GET " + target + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n");
    (void)raw.receive(10, nullptr, "\r\n\r\n");
  }
  EXPECT_EQ(client_->get("/api/v1/health?last").status, 401);
  const std::string log = server_log_with("\"GET /api/v1/health?last HTTP/1.1\"");
  EXPECT_EQ(log.find("s3cr3t"), std::string::npos) << log;
  EXPECT_EQ(read_bytes(dir_ / "stderr.txt").find("s3cr3t"), std::string::npos);
  EXPECT_EQ(lines_with(log, "\"GET /api/v1/health?REDACTED HTTP/1.1\"").size(), 3u) << log;
  EXPECT_EQ(lines_with(log, "\"GET REDACTED HTTP/1.1\"").size(), 2u) << log;
}

// A launcher that captures the server's standard error and never reads it (a pipe of 64 KB filled
// by request lines) stopped the server answering after about 225 requests, and SIGTERM with it.
TEST_F(ServerRequestLog, AStandardErrorNobodyReadsDoesNotStopTheServer) {
  const fs::path fifo = dir_ / "unread-stderr";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);  // held open, never read
  ASSERT_GE(reader, 0);
  start_logged_server({}, fifo);
  const std::string padding(200, 'a');
  for (int k = 0; k < 1000; ++k) {
    RawConnection raw(server_->port());
    raw.send("GET /api/v1/health?x=" + padding + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n");
    const std::string answer = raw.receive(5, nullptr, "\r\n\r\n");
    ASSERT_EQ(answer.rfind("HTTP/1.1 200", 0), 0u) << "request " << k << " was not answered";
  }
  // the file has every line
  std::size_t logged = 0;
  for (const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(10);
       logged < 1000 && std::chrono::steady_clock::now() < end;
       std::this_thread::sleep_for(std::chrono::milliseconds(50)))
    logged = lines_with(server_log(), "\"GET /api/v1/health?x=a").size();
  EXPECT_EQ(logged, 1000u);
  const auto stopping = std::chrono::steady_clock::now();
  server_.reset();  // SIGTERM, and waits for the exit
  EXPECT_LT(std::chrono::steady_clock::now() - stopping, std::chrono::seconds(10));
  ::close(reader);
}

}  // namespace
}  // namespace dem::test
