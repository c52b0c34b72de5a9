// The conventions of REST that clients rely on, against the real server: the versioned path and its
// alias, pages of jobs and their filters (state, name, tags), errors as RFC 9457 problem details, a
// job's results, and artifacts by ETag and byte range (RFC 9110 13 and 14).
#include "dem/version.hpp"
#include "server/api_routes.hpp"
#include "support/command.hpp"
#include "support/raw_http.hpp"
#include "support/server_test.hpp"

namespace dem::test {
namespace {

class ServerRest : public ServerTest {
 protected:
  // A short pouring job with this name and these tags (a JSON array's text).
  long submit_tagged(const std::string& name, const std::string& tags, long steps = 200) {
    std::string spec = pouring_spec(0.02, steps, 100);
    spec = replaced(spec, "{", "{\"tags\": " + tags + ", ");
    spec = replaced(spec, R"("name": "pouring test")", R"("name": ")" + name + "\"");
    return submit_json(spec)["id"];
  }
  nlohmann::json list(const std::string& query) {
    const client::Response r = client_->get("/api/v1/jobs" + query);
    EXPECT_EQ(r.status, 200) << query << ": " << r.body;
    return nlohmann::json::parse(r.body);
  }
  static std::vector<long> ids(const nlohmann::json& page) {
    std::vector<long> out;
    for (const auto& j : page["jobs"]) out.push_back(j["id"]);
    return out;
  }
};

TEST_F(ServerRest, TheVersionedPathAndItsAliasAreTheSameApiAndLinksUseTheVersionedOne) {
  start_server();
  const long id = submit_tagged("a", "[]");
  const client::Response r = client_->request("POST", "/api/v1/jobs", pouring_spec(0.02, 200, 100), "application/json");
  ASSERT_EQ(r.status, 201) << r.body;
  EXPECT_EQ(r.header("location"), "/api/v1/jobs/" + std::to_string(nlohmann::json::parse(r.body)["id"].get<long>()));
  wait_for(id, "succeeded,failed");
  nlohmann::json versioned = nlohmann::json::parse(client_->get("/api/v1/jobs/" + std::to_string(id)).body);
  nlohmann::json alias = nlohmann::json::parse(client_->get("/api/jobs/" + std::to_string(id)).body);
  EXPECT_EQ(versioned, alias);
  EXPECT_EQ(versioned["links"]["self"], "/api/v1/jobs/" + std::to_string(id));
  EXPECT_EQ(versioned["links"]["results"], "/api/v1/jobs/" + std::to_string(id) + "/results");
  EXPECT_EQ(versioned["links"]["log"], "/api/v1/jobs/" + std::to_string(id) + "/log");
  const nlohmann::json artifacts =
      nlohmann::json::parse(client_->get("/api/v1/jobs/" + std::to_string(id) + "/artifacts").body);
  ASSERT_FALSE(artifacts["artifacts"].empty());
  const std::string url = artifacts["artifacts"][0]["url"];
  EXPECT_EQ(url.rfind("/api/v1/jobs/", 0), 0u) << url;
  EXPECT_EQ(client_->get(url).status, 200);
  EXPECT_EQ(client_->get("/api/v1/health").status, 200);
  EXPECT_EQ(client_->get("/api/v2/jobs").status, 404);  // no such version
}

TEST_F(ServerRest, PagesOfJobsFollowTheirNextLinksToTheEndAndKeepTheirFilters) {
  start_server({"--jobs", "1"});
  std::vector<long> tagged;
  for (int k = 0; k < 5; ++k) {
    const long id = submit_tagged(k % 2 ? "odd" : "even", k % 2 ? R"(["batch:1", "odd"])" : R"(["batch:1"])");
    tagged.push_back(id);
  }
  const long untagged = submit_tagged("even", "[]");
  for (long id : tagged) wait_for(id, "succeeded,failed");
  wait_for(untagged, "succeeded,failed");

  // pages of 2 with a filter: the next links carry it, and the pages together are the filtered list
  std::vector<long> seen;
  std::string next = "/api/v1/jobs?limit=2&tag=batch:1";
  int pages = 0;
  while (!next.empty() && pages < 10) {
    const client::Response r = client_->get(next);
    ASSERT_EQ(r.status, 200) << next << ": " << r.body;
    const nlohmann::json page = nlohmann::json::parse(r.body);
    for (long id : ids(page)) seen.push_back(id);
    next = page.value("next", "");
    if (!next.empty()) {
      EXPECT_EQ(r.header("link"), "<" + next + ">; rel=\"next\"");
      EXPECT_NE(next.find("tag=batch%3A1"), std::string::npos) << next;
    } else {
      EXPECT_EQ(r.header("link"), "");
    }
    ++pages;
  }
  EXPECT_EQ(seen, tagged);
  EXPECT_EQ(pages, 3);  // 2 + 2 + 1

  EXPECT_EQ(ids(list("?tag=batch:1,odd")), (std::vector<long>{tagged[1], tagged[3]}));  // every tag given
  EXPECT_EQ(ids(list("?name=even")), (std::vector<long>{tagged[0], tagged[2], tagged[4], untagged}));
  EXPECT_EQ(ids(list("?name=even&tag=batch:1")), (std::vector<long>{tagged[0], tagged[2], tagged[4]}));
  EXPECT_EQ(ids(list("?state=succeeded,failed")).size(), 6u);
  EXPECT_TRUE(ids(list("?state=queued,running")).empty());
  EXPECT_EQ(ids(list("?after=" + std::to_string(tagged[3]))), (std::vector<long>{tagged[4], untagged}));
  const nlohmann::json whole = list("");  // no limit: every job, and no next
  EXPECT_EQ(whole["jobs"].size(), 6u);
  EXPECT_FALSE(whole.contains("next"));
  const nlohmann::json job = whole["jobs"][1];
  EXPECT_EQ(job["tags"], nlohmann::json::parse(R"(["batch:1", "odd"])"));
  EXPECT_EQ(whole["jobs"][5]["tags"], nlohmann::json::array());
}

TEST_F(ServerRest, ABadQueryOrSpecIsAProblemDetailNamingWhatIsWrong) {
  start_server();
  for (const auto& [query, says] :
       std::vector<std::pair<std::string, std::string>>{{"?limit=0", "limit=0"},
                                                        {"?limit=1001", "limit=1001"},
                                                        {"?limit=two", "limit=two"},
                                                        {"?after=-3", "after=-3"},
                                                        {"?state=done", "\"done\" is not a job state"},
                                                        {"?state=succeeded,,failed", "\"\" is not a job state"},
                                                        {"?tag=a,,b", "\"\" is not a tag"},
                                                        {"?stat=running", "\"stat\" is not a parameter"}}) {
    const client::Response r = client_->get("/api/v1/jobs" + query);
    EXPECT_EQ(r.status, 400) << query;
    EXPECT_EQ(r.header("content-type"), "application/problem+json") << query;
    const nlohmann::json problem = nlohmann::json::parse(r.body);
    EXPECT_EQ(problem["type"], "about:blank");
    EXPECT_EQ(problem["title"], "Bad Request");
    EXPECT_EQ(problem["status"], 400);
    EXPECT_EQ(problem["instance"], "/api/v1/jobs" + query);
    EXPECT_NE(problem["detail"].get<std::string>().find(says), std::string::npos) << query << ": " << r.body;
    EXPECT_EQ(problem["error"], problem["detail"]);  // what the first clients read
  }
  // a spec's problems keep their field paths
  const std::string bad_tags = replaced(pouring_spec(0.02, 200, 100), "{", R"({"tags": ["ok", "no spaces", "ok"], )");
  const client::Response r = client_->request("POST", "/api/v1/jobs", bad_tags, "application/json");
  ASSERT_EQ(r.status, 400) << r.body;
  EXPECT_EQ(r.header("content-type"), "application/problem+json");
  const nlohmann::json problem = nlohmann::json::parse(r.body);
  EXPECT_EQ(problem["detail"], "invalid spec");
  ASSERT_EQ(problem["problems"].size(), 2u) << r.body;
  EXPECT_NE(problem["problems"][0].get<std::string>().find("tags[1]"), std::string::npos) << r.body;
  EXPECT_NE(problem["problems"][1].get<std::string>().find("tags[2]: \"ok\" is given twice"), std::string::npos)
      << r.body;
  // unknown paths and methods too
  const client::Response missing = client_->get("/api/v1/nothing");
  EXPECT_EQ(missing.status, 404);
  EXPECT_EQ(missing.header("content-type"), "application/problem+json");
  const client::Response wrong = client_->request("PUT", "/api/v1/jobs");
  EXPECT_EQ(wrong.status, 405);
  EXPECT_EQ(nlohmann::json::parse(wrong.body)["title"], "Method Not Allowed");
}

// An independent tester's findings: a filter given twice kept the last silently (dropping the
// other); '+' (form encoding: curl --data-urlencode, Python's urlencode) was not read as a space; a
// tag no job can have was accepted; empty pairs were refused or not depending on where they stood.
TEST_F(ServerRest, AFilterGivenTwiceOrNotATagIsRefusedAndPlusIsASpace) {
  start_server({"--jobs", "1"});
  const long spaced = submit_tagged("a b", "[]");
  const long plus = submit_tagged("a+b", "[]");
  wait_for(spaced, "succeeded,failed");
  wait_for(plus, "succeeded,failed");
  EXPECT_EQ(ids(list("?name=a+b")), std::vector<long>{spaced});
  EXPECT_EQ(ids(list("?name=a%20b")), std::vector<long>{spaced});
  EXPECT_EQ(ids(list("?name=a%2Bb")), std::vector<long>{plus});
  EXPECT_EQ(ids(list("?limit=5&")).size(), 2u);  // empty pairs are nothing, wherever they stand
  EXPECT_EQ(ids(list("?&limit=5")).size(), 2u);
  EXPECT_EQ(ids(list("?&&")).size(), 2u);
  const std::string many_tags = [] {
    std::string t;
    for (int k = 0; k < 33; ++k) t.append(k ? "," : "").append(std::to_string(k));  // GCC 12: no "," + string
    return t;
  }();
  for (const auto& [query, says] : std::vector<std::pair<std::string, std::string>>{
           {"?state=succeeded&state=queued", "state= is given more than once"},
           {"?name=a&name=b", "name= is given more than once"},
           {"?tag=x&tag=y", "tag= is given more than once"},
           {"?limit=5&limit=1000", "limit= is given more than once"},
           {"?tag=a%20b", "\"a b\" is not a tag"},
           {"?tag=" + std::string(65, 'x'), "is not a tag"},
           {"?tag=%C3%A9", "is not a tag"},
           {"?tag=" + many_tags, "at most 32 tags"}}) {
    const client::Response r = client_->get("/api/v1/jobs" + query);
    EXPECT_EQ(r.status, 400) << query;
    EXPECT_NE(nlohmann::json::parse(r.body)["detail"].get<std::string>().find(says), std::string::npos)
        << query << ": " << r.body;
  }
}

// Refusals made before the request is routed carry its path too (they had no instance).
TEST_F(ServerRest, ARefusalBeforeRoutingNamesTheRequestsPath) {
  start_server();
  RawConnection raw(server_->port());
  raw.send("FOO /api/v1/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n");
  const std::string unknown = raw.receive(10);
  EXPECT_EQ(unknown.rfind("HTTP/1.1 501", 0), 0u) << unknown;
  EXPECT_NE(unknown.find("\"instance\": \"/api/v1/jobs\""), std::string::npos) << unknown;
  const client::Response expect = client_->request("GET", "/api/v1/health", "", "", {{"Expect", "foo"}});
  EXPECT_EQ(expect.status, 417);
  EXPECT_EQ(nlohmann::json::parse(expect.body).value("instance", ""), "/api/v1/health") << expect.body;
}

TEST_F(ServerRest, AJobsResultsAreItsResultsJsonOnceItEnds) {
  start_server({"--jobs", "1"});
  const long first = submit_tagged("long", "[]");
  const long queued = submit_tagged("queued", "[]");
  const client::Response early = client_->get("/api/v1/jobs/" + std::to_string(queued) + "/results");
  if (job(queued)["state"] == "queued") {
    EXPECT_EQ(early.status, 404);
    EXPECT_NE(early.body.find("no results yet: it is queued"), std::string::npos) << early.body;
  }
  for (long id : {first, queued}) {
    const nlohmann::json done = wait_for(id, "succeeded,failed");
    ASSERT_EQ(done["state"], "succeeded") << done.dump();
    const client::Response r = client_->get("/api/v1/jobs/" + std::to_string(id) + "/results");
    ASSERT_EQ(r.status, 200) << r.body;
    const nlohmann::json results = nlohmann::json::parse(r.body);
    EXPECT_EQ(results, done["results"]);
    const client::Response file = client_->get("/api/v1/jobs/" + std::to_string(id) + "/artifacts/results.json");
    ASSERT_EQ(file.status, 200);
    EXPECT_EQ(results, nlohmann::json::parse(file.body));
  }
  EXPECT_EQ(client_->request("POST", "/api/v1/jobs/" + std::to_string(first) + "/results").status, 405);
  // a job that ended without results says so, not "yet" (long enough to be cancelled: one of 200
  // steps could end before its cancel came, on a fresh clone's test run)
  const long cancelled = submit_tagged("cancelled", "[]", 5000000);
  client_->request("POST", "/api/v1/jobs/" + std::to_string(cancelled) + "/cancel");
  ASSERT_EQ(wait_for(cancelled, "cancelled,succeeded")["state"], "cancelled");
  const client::Response none = client_->get("/api/v1/jobs/" + std::to_string(cancelled) + "/results");
  EXPECT_EQ(none.status, 404);
  EXPECT_NE(none.body.find("ended (cancelled) without results"), std::string::npos) << none.body;
  EXPECT_EQ(client_->get("/api/v1/jobs/999/results").status, 404);
}

TEST_F(ServerRest, AnArtifactIsAskedAgainByItsETagAndReadInRanges) {
  start_server();
  const long id = submit_tagged("ranges", "[]");
  ASSERT_EQ(wait_for(id, "succeeded,failed")["state"], "succeeded");
  const std::string url = "/api/v1/jobs/" + std::to_string(id) + "/artifacts/ANIMATION_3D.dat";
  const client::Response whole = client_->get(url);
  ASSERT_EQ(whole.status, 200);
  const std::string bytes = whole.body;
  ASSERT_GT(bytes.size(), 100u);
  const std::string size = std::to_string(bytes.size());
  const std::string tag = whole.header("etag");
  ASSERT_EQ(tag.front(), '"') << tag;
  EXPECT_EQ(whole.header("accept-ranges"), "bytes");

  auto get = [&](const client::Headers& headers) { return client_->request("GET", url, "", "", headers); };
  const client::Response same = get({{"If-None-Match", tag}});
  EXPECT_EQ(same.status, 304);
  EXPECT_TRUE(same.body.empty());
  EXPECT_EQ(same.header("etag"), tag);
  EXPECT_EQ(get({{"If-None-Match", "\"other\", W/" + tag}}).status, 304);  // in a list, compared weakly
  EXPECT_EQ(get({{"If-None-Match", "\"other\""}}).status, 200);

  struct Case {
    std::string range;
    std::size_t first, length;
  };
  for (const Case& c : std::vector<Case>{{"bytes=0-9", 0, 10},
                                         {"bytes=10-19", 10, 10},
                                         {"bytes=50-", 50, bytes.size() - 50},
                                         {"bytes=-7", bytes.size() - 7, 7},
                                         {"bytes=-999999999", 0, bytes.size()},
                                         {"bytes=20-999999999", 20, bytes.size() - 20},
                                         // past 2^64 - 1 (they were answered whole): read as the largest number
                                         {"bytes=20-99999999999999999999999", 20, bytes.size() - 20},
                                         {"bytes=-99999999999999999999999", 0, bytes.size()},
                                         {"bytes=000000000000000000000003-4", 3, 2}}) {
    const client::Response part = get({{"Range", c.range}});
    ASSERT_EQ(part.status, 206) << c.range;
    EXPECT_EQ(part.body, bytes.substr(c.first, c.length)) << c.range;
    EXPECT_EQ(part.header("content-range"),
              "bytes " + std::to_string(c.first) + "-" + std::to_string(c.first + c.length - 1) + "/" + size)
        << c.range;
  }
  // answered whole: several ranges, another unit, malformed; and a Range under a stale If-Range
  for (const char* range : {"bytes=0-1,4-5", "lines=1-2", "bytes=5-2", "bytes=x-3", "bytes=-"}) {
    const client::Response r = get({{"Range", range}});
    EXPECT_EQ(r.status, 200) << range;
    EXPECT_EQ(r.body, bytes) << range;
  }
  EXPECT_EQ(get({{"Range", "bytes=0-1"}, {"If-Range", "\"stale\""}}).status, 200);
  EXPECT_EQ(get({{"Range", "bytes=0-1"}, {"If-Range", tag}}).status, 206);
  EXPECT_EQ(get({{"Range", "bytes=99999999999999999999-"}}).status, 416);
  EXPECT_EQ(get({{"Range", "bytes=18446744073709551615-"}}).status, 416);
  // a header given on two lines is one list (RFC 9110 5.3); two Range lines are two ranges: whole
  auto status_of = [&](const std::string& headers) {
    RawConnection raw(server_->port());
    raw.send("GET " + url + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n" + headers + "\r\n");
    return raw.receive(10, nullptr, "\r\n").substr(0, 12);
  };
  EXPECT_EQ(status_of("If-None-Match: \"other\"\r\nIf-None-Match: " + tag + "\r\n"), "HTTP/1.1 304");
  EXPECT_EQ(status_of("Range: bytes=0-9\r\nRange: bytes=10-19\r\n"), "HTTP/1.1 200");
  EXPECT_EQ(status_of("Range: bytes=0-9\r\n"), "HTTP/1.1 206");
  const client::Response past = get({{"Range", "bytes=" + size + "-"}});
  EXPECT_EQ(past.status, 416);
  EXPECT_EQ(past.header("content-range"), "bytes */" + size);
  EXPECT_EQ(past.header("content-type"), "application/problem+json");
  // HEAD of a range: its headers and length, no body
  const client::Response head = client_->request("HEAD", url, "", "", {{"Range", "bytes=0-9"}});
  EXPECT_EQ(head.status, 200);  // a Range is for GET alone (RFC 9110 14.2)
  EXPECT_EQ(head.header("content-length"), size);
}

// The OpenAPI description and the routes are the same set: every path and method it describes is
// routed, and every route is described (what HEAD and OPTIONS add aside).
TEST_F(ServerRest, TheOpenApiDescriptionListsEveryRouteAndNoOther) {
  start_server();
  const nlohmann::json description = nlohmann::json::parse(client_->get("/api/v1/openapi.json").body);
  std::set<std::string> described;
  for (const auto& [path, operations] : description["paths"].items()) {
    ASSERT_EQ(path.rfind("/api/v1/", 0), 0u) << path;
    std::vector<std::string> segments{"api"};
    std::stringstream rest(path.substr(std::string("/api/v1/").size()));
    for (std::string s; std::getline(rest, s, '/');)
      segments.push_back(s == "{id}" ? "7" : s == "{name}" ? "x.dat" : s);
    const char* allowed = server::allowed_methods(segments);
    ASSERT_NE(allowed, nullptr) << path << " is described but not routed";
    std::set<std::string> methods;
    for (const auto& [method, operation] : operations.items())
      if (method != "parameters") methods.insert(method);
    std::set<std::string> routed;
    std::stringstream list(allowed);
    for (std::string m; std::getline(list, m, ',');) {
      m.erase(0, m.find_first_not_of(' '));
      std::transform(m.begin(), m.end(), m.begin(), [](unsigned char c) { return std::tolower(c); });
      if (m != "head" && m != "options") routed.insert(m);
    }
    EXPECT_EQ(methods, routed) << path;
    described.insert(path);
  }
  // every route the server has, by the paths a client would write
  for (const char* route : {"/api/v1/health",
                            "/api/v1/openapi.json",
                            "/api/v1/cases",
                            "/api/v1/cases/{name}",
                            "/api/v1/jobs",
                            "/api/v1/jobs/{id}",
                            "/api/v1/jobs/{id}/cancel",
                            "/api/v1/jobs/{id}/resume",
                            "/api/v1/jobs/{id}/frames",
                            "/api/v1/jobs/{id}/results",
                            "/api/v1/jobs/{id}/log",
                            "/api/v1/jobs/{id}/artifacts",
                            "/api/v1/jobs/{id}/artifacts/{name}",
                            "/api/v1/studies",
                            "/api/v1/studies/{id}",
                            "/api/v1/studies/{id}/cancel",
                            "/api/v1/studies/{id}/resume",
                            "/api/v1/studies/{id}/results.json",
                            "/api/v1/studies/{id}/results.csv",
                            "/api/v1/studies/{id}/figure.svg"})
    EXPECT_TRUE(described.count(route)) << route << " is routed but not described";
  EXPECT_EQ(described.size(), 20u);
  EXPECT_EQ(description["info"]["version"], nlohmann::json::parse(client_->get("/api/v1/health").body)["version"]);
}

TEST(ServerCommandLine, VersionAndHelpAreAnswered) {
  const CommandResult version = run_command(shell_quoted(DEM_BINARY_DIR "/dem-server") + " --version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.output, std::string("dem-server ") + kVersion + "\n");
  const CommandResult help = run_command(shell_quoted(DEM_BINARY_DIR "/dem-server") + " --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_EQ(help.output.rfind("usage: dem-server", 0), 0u) << help.output;
}

}  // namespace
}  // namespace dem::test
