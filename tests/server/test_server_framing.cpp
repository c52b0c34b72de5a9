// What an independent tester found in the server's HTTP after the first round of fixes: framing a
// proxy could read otherwise (a transfer coding other than chunked), headers given twice of which
// the first won, answers before the token was checked, and small departures from RFC 9110/9112
// (a 204 with a length, Allow lists that leave out HEAD, OPTIONS refused on the viewer's paths).
// Each failed before its fix.
#include "support/raw_http.hpp"
#include "support/server_test.hpp"

namespace dem::test {
namespace {

class ServerFraming : public ServerTest {
 protected:
  bool alive() { return client_->get("/api/health").status == 200; }
  std::string exchange(const std::string& request) { return raw_exchange(server_->port(), request); }
  static bool closes(const std::string& answer) {  // "Connection: close", or close among other options
    const std::size_t at = answer.find("\r\nConnection: ");
    return at != std::string::npos &&
           answer.substr(at, answer.find("\r\n", at + 2) - at).find("close") != std::string::npos;
  }
  static bool has_header(const std::string& answer, const std::string& line) {
    const std::string head = answer.substr(0, answer.find("\r\n\r\n"));
    return head.find("\r\n" + line) != std::string::npos;
  }
};

// RFC 9112 6.1: a request whose last transfer coding is not chunked cannot be framed: 400, and the
// connection closes (what follows could be read as another request: smuggling). A coding the
// server does not implement before chunked is a 501.
TEST_F(ServerFraming, TransferCodingsOtherThanChunkedAreRefusedAndTheConnectionCloses) {
  start_server();
  const std::string body = "0\r\n\r\n";
  for (const std::string coding : {"gzip", "chunked, gzip", "identity"}) {
    const std::string answer =
        exchange("POST /api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\nTransfer-Encoding: " + coding + "\r\n\r\n" + body);
    EXPECT_EQ(status_of(answer), 400) << coding << ": " << answer;
    EXPECT_TRUE(closes(answer)) << coding << ": " << answer;
  }
  const std::string gzip_then_chunked =
      exchange("POST /api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\nTransfer-Encoding: gzip, chunked\r\n\r\n" + body);
  EXPECT_EQ(status_of(gzip_then_chunked), 501) << gzip_then_chunked;
  EXPECT_TRUE(closes(gzip_then_chunked)) << gzip_then_chunked;
  const std::string two_fields = exchange(
      "POST /api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\nTransfer-Encoding: chunked\r\nTransfer-Encoding: gzip\r\n\r\n" +
      body);
  EXPECT_EQ(status_of(two_fields), 400) << two_fields;
  EXPECT_TRUE(alive());
}

// A header that names one thing (who asks, where from, which submission) given twice: which one
// counts depends on the reader, so neither does.
TEST_F(ServerFraming, HeadersGivenTwiceAreRefused) {
  start_server();
  for (const std::string header : {"Origin: http://127.0.0.1", "Authorization: Bearer x", "Idempotency-Key: k"}) {
    const std::string answer =
        exchange("GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\n" + header + "\r\n" + header + "\r\n\r\n");
    EXPECT_EQ(status_of(answer), 400) << header << ": " << answer;
    EXPECT_NE(answer.find("more than one"), std::string::npos) << answer;
  }
  // an empty key is not "no key": the client meant one and would be told nothing
  const std::string spec = pouring_spec(0.015, 100, 50);
  const client::Response blank =
      client_->request("POST", "/api/jobs", spec, "application/json", {{"Idempotency-Key", "  "}});
  EXPECT_EQ(blank.status, 400) << blank.body;
  EXPECT_NE(blank.body.find("Idempotency-Key"), std::string::npos) << blank.body;
}

// With a token, nothing is answered to a request without it: OPTIONS * was, and an oversized body
// got its 413 before the 401 (telling a stranger the server's limit).
TEST_F(ServerFraming, WithATokenEveryAnswerWaitsForTheToken) {
  start_server({"--token", "s3cret"});
  EXPECT_EQ(status_of(exchange("OPTIONS * HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")), 401);
  const std::string big = exchange(
      "POST /api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
      "Content-Length: 999999999999\r\n\r\n");
  EXPECT_EQ(status_of(big), 401) << big;
  EXPECT_EQ(status_of(exchange("OPTIONS * HTTP/1.1\r\nHost: 127.0.0.1\r\nAuthorization: Bearer s3cret\r\n\r\n")), 204);
  // which methods the server implements is not told to a stranger either (501 came first)
  EXPECT_EQ(status_of(exchange("POST /api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\nTransfer-Encoding: gzip, chunked\r\n\r\n"
                               "0\r\n\r\n")),
            401);  // the codings it decodes are not told either
  for (const std::string method : {"TRACE", "FOO"})
    EXPECT_EQ(status_of(exchange(method + " /api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")), 401) << method;
  EXPECT_EQ(status_of(exchange("TRACE /api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\nAuthorization: Bearer s3cret\r\n\r\n")),
            501);
}

// RFC 9110 8.6: no Content-Length in a 204. RFC 9110 15.5.6: a 405's Allow lists what the resource
// answers (the viewer's files answer HEAD and OPTIONS too). TRACE and CONNECT are implemented on
// no resource: 501. A 426 keeps Connection: close when the client asked for it.
TEST_F(ServerFraming, SmallConformanceDetails) {
  start_server();
  const std::string options = exchange("OPTIONS /api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
  EXPECT_EQ(status_of(options), 204) << options;
  EXPECT_FALSE(has_header(options, "Content-Length:")) << options;
  const std::string star = exchange("OPTIONS * HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
  EXPECT_FALSE(has_header(star, "Content-Length:")) << star;
  const std::string page_options = exchange("OPTIONS / HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
  EXPECT_EQ(status_of(page_options), 204) << page_options;
  EXPECT_TRUE(has_header(page_options, "Allow: GET, HEAD, OPTIONS")) << page_options;
  const std::string post_page = exchange("POST /index.html HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 0\r\n\r\n");
  EXPECT_EQ(status_of(post_page), 405) << post_page;
  EXPECT_TRUE(has_header(post_page, "Allow: GET, HEAD, OPTIONS")) << post_page;
  for (const std::string method : {"TRACE", "CONNECT"}) {
    const std::string answer = exchange(method + " /api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
    EXPECT_EQ(status_of(answer), 501) << method << ": " << answer;
  }
  // RFC 9110 10.1.1 and 15.2: an HTTP/1.0 client's 100-continue is ignored, and it gets no 1xx
  const std::string old_client =
      exchange("GET /api/health HTTP/1.0\r\nHost: 127.0.0.1\r\nExpect: 100-continue\r\nContent-Length: 0\r\n\r\n");
  EXPECT_EQ(status_of(old_client), 200) << old_client;
  EXPECT_EQ(old_client.find(" 100 "), std::string::npos) << old_client;
  // RFC 6585 5: a header past the server's limit
  const std::string huge =
      exchange("GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Big: " + std::string(9000, 'x') + "\r\n\r\n");
  EXPECT_EQ(status_of(huge), 431) << huge.substr(0, 200);
  const long id = submit_json(pouring_spec(0.015, 100, 50))["id"];
  const std::string upgrade = exchange("GET /api/jobs/" + std::to_string(id) +
                                       "/frames HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(status_of(upgrade), 426) << upgrade;
  EXPECT_TRUE(closes(upgrade)) << upgrade;
  EXPECT_TRUE(alive());
}

}  // namespace
}  // namespace dem::test

namespace dem::test {
namespace {

// A link inside the viewer's folder (--web) was followed wherever it led: to the job data, or /etc.
TEST_F(ServerFraming, LinksOutOfTheViewersFolderAreNotServed) {
  const fs::path web = dir_ / "web";
  fs::create_directories(web / "inner");
  write_text(web / "index.html", "<!doctype html><title>v</title>");
  write_text(dir_ / "secret.txt", "not for the web");
  write_text(web / "inner" / "real.txt", "inside");
  fs::create_symlink(dir_ / "secret.txt", web / "leak.txt");
  fs::create_symlink(dir_, web / "up");
  fs::create_symlink(web / "inner" / "real.txt", web / "inside.txt");  // a link that stays inside is fine
  start_server({"--web", web.string()});
  EXPECT_EQ(client_->get("/index.html").status, 200);
  EXPECT_EQ(client_->get("/leak.txt").status, 404);
  EXPECT_EQ(client_->get("/up/secret.txt").status, 404);
  const client::Response inside = client_->get("/inside.txt");
  EXPECT_EQ(inside.status, 200);
  EXPECT_EQ(inside.body, "inside");
}

}  // namespace
}  // namespace dem::test

namespace dem::test {
namespace {

// A link planted among a job's outputs was listed and served: /etc/shadow to anyone who can reach the
// server (an independent tester's finding).
TEST_F(ServerFraming, LinksAmongAJobsOutputsAreNeitherListedNorServed) {
  start_server();
  const long id = submit_json(pouring_spec(0.015, 100, 50))["id"];
  wait_for(id, "succeeded");
  write_text(dir_ / "secret.txt", "not for the web");
  fs::create_symlink(dir_ / "secret.txt", dir_ / "data" / "jobs" / std::to_string(id) / "outputs" / "Leak.dat");
  const std::string artifacts = "/api/jobs/" + std::to_string(id) + "/artifacts";
  const client::Response list = client_->get(artifacts);
  EXPECT_EQ(list.status, 200);
  EXPECT_EQ(list.body.find("Leak.dat"), std::string::npos) << list.body;
  EXPECT_NE(list.body.find("ANIMATION_3D.dat"), std::string::npos) << list.body;
  EXPECT_EQ(client_->get(artifacts + "/Leak.dat").status, 404);
  // a hard link to a file elsewhere is a link too
  write_text(dir_ / "other.txt", "another file of the machine");
  fs::create_hard_link(dir_ / "other.txt", dir_ / "data" / "jobs" / std::to_string(id) / "outputs" / "Hard.dat");
  EXPECT_EQ(client_->get(artifacts).body.find("Hard.dat"), std::string::npos);
  EXPECT_EQ(client_->get(artifacts + "/Hard.dat").status, 404);
  // and the outputs folder itself replaced by a link to another folder
  const fs::path outputs = dir_ / "data" / "jobs" / std::to_string(id) / "outputs";
  fs::create_directories(dir_ / "fake");
  write_text(dir_ / "fake" / "ANIMATION_3D.dat", "TOPSECRET");
  fs::remove_all(outputs);
  fs::create_directory_symlink(dir_ / "fake", outputs);
  EXPECT_EQ(client_->get(artifacts).body.find("ANIMATION_3D.dat"), std::string::npos);
  EXPECT_EQ(client_->get(artifacts + "/ANIMATION_3D.dat").status, 404);
}

}  // namespace
}  // namespace dem::test
