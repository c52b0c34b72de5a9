// Requests no well-behaved client sends, and requests an attacker would: each gets a clear answer,
// never a crash, and never reflects its input into a header.
#include "support/raw_http.hpp"
#include "support/server_test.hpp"

namespace dem::test {
namespace {

class ServerHostile : public ServerTest {
 protected:
  bool alive() { return client_->get("/api/health").status == 200; }
  std::string exchange(const std::string& request) { return raw_exchange(server_->port(), request); }
};

// An unknown method (or a known one in the wrong case: methods are case-sensitive) once aborted the
// whole server, before the token was even checked.
TEST_F(ServerHostile, UnknownMethodsAreAnsweredNotFatal) {
  start_server();
  for (const std::string method : {"FOO", "get", "BREW", "G\x01T"}) {
    const std::string answer = exchange(method + " /api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
    const int status = status_of(answer);
    EXPECT_TRUE(status == 501 || status == 400) << method << ": " << answer;
    ASSERT_TRUE(alive()) << "after " << method;
  }
  EXPECT_NE(exchange("FOO /api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n").find("FOO is not a method this server knows"),
            std::string::npos);
}

TEST_F(ServerHostile, UnknownMethodsAreAnsweredWithATokenToo) {
  start_server({"--token", "s3cret"});
  const std::string answer = exchange("FOO / HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
  EXPECT_TRUE(status_of(answer) == 501 || status_of(answer) == 401) << answer;
  const client::HttpClient right(server_->url(), "s3cret");
  EXPECT_EQ(right.get("/api/health").status, 200);
}

// RFC 9112 3.2: a request of HTTP/1.1 without Host is a 400.
TEST_F(ServerHostile, Http11WithoutHostIs400) {
  start_server();
  EXPECT_EQ(status_of(exchange("GET /api/health HTTP/1.1\r\n\r\n")), 400);
  EXPECT_EQ(status_of(exchange("GET /api/health HTTP/1.0\r\n\r\n")), 200);  // 1.0 has no Host
}

// RFC 9112 3.2: more than one Host is a 400 too (which one names the server is ambiguous, and a proxy
// in front may have checked the other).
TEST_F(ServerHostile, TwoHostHeadersAre400) {
  start_server();
  const std::string answer = exchange("GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\nHost: evil.example\r\n\r\n");
  EXPECT_EQ(status_of(answer), 400) << answer;
  EXPECT_NE(answer.find("more than one Host"), std::string::npos) << answer;
  EXPECT_EQ(status_of(exchange("GET /api/health HTTP/1.0\r\nHost: a\r\nHost: b\r\n\r\n")), 400);
}

// RFC 9112 3.2.2: a server must accept a target in absolute form, and then its authority, not the
// Host header, names the server (so it is what the loopback check looks at).
TEST_F(ServerHostile, AbsoluteFormTargetsAreServed) {
  start_server();
  EXPECT_EQ(status_of(exchange("GET http://127.0.0.1/api/health HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")), 200);
  EXPECT_EQ(status_of(exchange("GET HTTP://LOCALHOST:9/api/jobs?state=succeeded HTTP/1.1\r\nHost: x\r\n\r\n")), 200);
  EXPECT_EQ(status_of(exchange("GET http://127.0.0.1 HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")), 200);  // the viewer
  EXPECT_EQ(status_of(exchange("GET http://evil.example/api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")), 403);
  EXPECT_EQ(status_of(exchange("GET http:///api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")), 400);
  EXPECT_EQ(status_of(exchange("GET ftp://127.0.0.1/api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")), 400);
}

// A target is a path from the root (or absolute, above); "api/health" is malformed, not a file.
TEST_F(ServerHostile, TargetsNotFromTheRootAre400) {
  start_server();
  EXPECT_EQ(status_of(exchange("GET api/health HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")), 400);
  EXPECT_EQ(status_of(exchange("GET * HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")), 400);
  const std::string server_options = exchange("OPTIONS * HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
  EXPECT_EQ(status_of(server_options), 204) << server_options;  // RFC 9110 9.3.7: the server as a whole
  EXPECT_NE(server_options.find("Allow: GET, HEAD, POST, DELETE, OPTIONS"), std::string::npos) << server_options;
  EXPECT_TRUE(alive());
}

// OPTIONS says what a resource allows; 405s list HEAD and OPTIONS with GET; every answer is dated.
TEST_F(ServerHostile, AllowListsEveryMethodAndAnswersAreDated) {
  start_server();
  const client::Response options = client_->request("OPTIONS", "/api/jobs");
  EXPECT_EQ(options.status, 204) << options.body;
  EXPECT_EQ(options.header("allow"), "GET, HEAD, POST, OPTIONS");
  const client::Response put = client_->request("PUT", "/api/jobs");
  EXPECT_EQ(put.status, 405);
  EXPECT_EQ(put.header("allow"), "GET, HEAD, POST, OPTIONS");
  const client::Response post = client_->request("POST", "/api/health");
  EXPECT_EQ(post.header("allow"), "GET, HEAD, OPTIONS");
  EXPECT_EQ(client_->request("HEAD", "/api/health").status, 200);
  EXPECT_EQ(client_->request("OPTIONS", "/api/nothing").status, 404);
  for (const client::Response& r : {options, put, post, client_->get("/api/health"), client_->get("/")}) {
    const std::string date = r.header("date");
    EXPECT_EQ(date.size(), 29u) << date;  // "Wed, 02 Dec 2026 10:00:00 GMT"
    EXPECT_EQ(date.substr(date.size() - 4), " GMT") << date;
  }
}

// A client that asks before sending its body (Expect: 100-continue, as curl does past 1 KB) is told to
// go on; one refused from its headers is told so before it sends the body.
TEST_F(ServerHostile, ExpectContinueIsAnswered) {
  start_server({"--max-body-mb", "0.01"});
  const std::string spec = pouring_spec(0.015, 100, 50);
  RawConnection c(server_->port());
  c.send("POST /api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nContent-Length: " +
         std::to_string(spec.size()) + "\r\nExpect: 100-continue\r\n\r\n");
  const std::string go_on = c.receive(5, nullptr, "\r\n\r\n");
  EXPECT_EQ(go_on.rfind("HTTP/1.1 100 Continue\r\n", 0), 0u) << go_on;
  c.send(spec);
  const std::string answer = c.receive(10, nullptr, "}\n");
  EXPECT_NE(answer.find("HTTP/1.1 201"), std::string::npos) << answer;
  // too large: 413 at once, no 100
  RawConnection big(server_->port());
  big.send(
      "POST /api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nContent-Length: 20000\r\n"
      "Expect: 100-continue\r\n\r\n");
  EXPECT_EQ(status_of(big.receive(5, nullptr, "\r\n\r\n")), 413);
  // an expectation the server cannot meet
  EXPECT_EQ(
      status_of(exchange("POST /api/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 2\r\nExpect: tea\r\n\r\n{}")),
      417);
}

// The DNS-rebinding check once took any host beginning with "127." for this machine.
TEST_F(ServerHostile, OnlyLiteralLoopbackHostsAreLocal) {
  start_server();
  for (const std::string host : {"127.attacker.example", "127.0.0.1.nip.io", "127.0.0.1.evil.example:80",
                                 "localhost.evil.example", "127.0.0.300", "0x7f.0.0.1"}) {
    EXPECT_EQ(client_->request("GET", "/api/jobs", "", "", {{"Host", host}}).status, 403) << host;
    EXPECT_EQ(client_->request("GET", "/api/jobs", "", "", {{"Origin", "http://" + host}}).status, 403) << host;
  }
  for (const std::string host :
       {"127.0.0.1", "127.0.0.1:8080", "127.1.2.3:9", "localhost", "LOCALHOST:1", "[::1]:8080"})
    EXPECT_EQ(client_->request("GET", "/api/jobs", "", "", {{"Host", host}}).status, 200) << host;
}

// A query value is never copied into a header: an access_token with CR/LF once became a header of
// the answer, and ";Domain=..." an attribute of the cookie.
TEST_F(ServerHostile, NoRequestValueIsReflectedIntoHeaders) {
  start_server({"--token", "s3cret"});
  const std::string injected = exchange(
      "GET /?access_token=s3cret%0d%0aX-Injected:%20yes HTTP/1.1\r\nHost: 127.0.0.1\r\nAuthorization: Bearer "
      "s3cret\r\n\r\n");
  EXPECT_EQ(injected.find("X-Injected"), std::string::npos) << injected;
  const std::string domain = exchange(
      "GET /?access_token=s3cret;Domain=evil.example HTTP/1.1\r\nHost: 127.0.0.1\r\nAuthorization: Bearer "
      "s3cret\r\n\r\n");
  EXPECT_EQ(domain.find("evil.example"), std::string::npos) << domain;
  const std::string page = exchange("GET /?access_token=s3cret HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
  EXPECT_NE(page.find("Set-Cookie: dem_token=s3cret; Path=/; HttpOnly; SameSite=Strict"), std::string::npos) << page;
}

// With a token, the cookie a page got is an ambient credential: another site's page (another port of
// this host included, which SameSite does not separate) must not ride on it, by HTTP or WebSocket.
TEST_F(ServerHostile, ATokenCookieFromAForeignOriginIsRefused) {
  start_server({"--token", "s3cret"});
  const client::Headers cookie = {{"Cookie", "dem_token=s3cret"}};
  const std::string self = "http://127.0.0.1:" + std::to_string(server_->port());
  auto with_origin = [&](const std::string& origin) {
    client::Headers h = cookie;
    h.emplace_back("Origin", origin);
    return h;
  };
  EXPECT_EQ(client_->request("GET", "/api/jobs", "", "", with_origin(self)).status, 200);
  EXPECT_EQ(client_->request("GET", "/api/jobs", "", "", cookie).status, 200);  // no Origin: not a page
  EXPECT_EQ(client_->request("POST", "/api/jobs", "{}", "application/json", with_origin("http://127.0.0.1:1")).status,
            403);
  EXPECT_EQ(client_->request("GET", "/api/jobs", "", "", with_origin("http://evil.example")).status, 403);
  const std::string upgrade = exchange(
      "GET /api/jobs/1/frames HTTP/1.1\r\nHost: 127.0.0.1\r\nCookie: dem_token=s3cret\r\n"
      "Origin: http://evil.example\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
      "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n");
  EXPECT_EQ(status_of(upgrade), 403) << upgrade;
}

// A number too large for a double is a malformed spec (400), not a server error (500).
TEST_F(ServerHostile, AnOverflowingNumberIsABadSpec) {
  start_server();
  const std::string spec = replaced(pouring_spec(0.015, 100, 50), "\"restitution\": 0.5", "\"restitution\": 1e999");
  const client::Response r = client_->request("POST", "/api/jobs", spec, "application/json");
  EXPECT_EQ(r.status, 400) << r.body;
  EXPECT_TRUE(alive());
}

}  // namespace
}  // namespace dem::test
