// The Prefer header (RFC 7240) on the requests that create work: jobs and studies always run after
// the answer, so `respond-async` is applied and said so (Preference-Applied), whatever else the
// header holds and however it is spaced; other preferences (wait=N among them) are ignored.
#include "support/raw_http.hpp"
#include "support/server_test.hpp"

namespace dem::test {
namespace {

class ServerPreferences : public ServerTest {
 protected:
  client::Response submit_preferring(const std::string& prefer, const std::string& spec) {
    return client_->request("POST", "/api/v1/jobs", spec, "application/json", {{"Prefer", prefer}});
  }
};

TEST_F(ServerPreferences, RespondAsyncIsAppliedToASubmissionAndSaidSo) {
  start_server();
  const std::string spec = pouring_spec(0.02, 200, 100);
  for (const char* prefer :
       {"respond-async", "RESPOND-ASYNC", "respond-async, wait=10", "wait=5,respond-async", "  respond-async  ",
        "return=minimal; foo=\"a, b\" , respond-async;x=1", "handling=lenient,,respond-async", "respond-async=\"\""}) {
    const client::Response r = submit_preferring(prefer, spec);
    EXPECT_EQ(r.status, 201) << prefer << ": " << r.body;  // the job exists at once; its run comes after
    EXPECT_EQ(r.header("preference-applied"), "respond-async") << "Prefer: " << prefer;
    EXPECT_EQ(r.header("location").rfind("/api/v1/jobs/", 0), 0u);
  }
  for (const char* prefer : {"wait=10", "return=minimal", "respond-asynchronously", "x=\"respond-async\"",
                             "foo=\"a, respond-async\"", "handling=strict; respond-async", ""}) {
    const client::Response r = submit_preferring(prefer, spec);
    EXPECT_EQ(r.status, 201) << prefer;
    EXPECT_EQ(r.header("preference-applied"), "") << "Prefer: " << prefer;
  }
  EXPECT_EQ(client_->request("POST", "/api/v1/jobs", spec, "application/json").header("preference-applied"), "");
}

TEST_F(ServerPreferences, ARetriedOrRefusedSubmissionAndTwoPreferLinesAreHandledToo) {
  start_server();
  const std::string spec = pouring_spec(0.02, 200, 100);
  const client::Headers keyed = {{"Prefer", "respond-async"}, {"Idempotency-Key", "prefer-1"}};
  EXPECT_EQ(client_->request("POST", "/api/v1/jobs", spec, "application/json", keyed).status, 201);
  const client::Response replayed = client_->request("POST", "/api/v1/jobs", spec, "application/json", keyed);
  EXPECT_EQ(replayed.status, 200);
  EXPECT_EQ(replayed.header("idempotent-replayed"), "true");
  EXPECT_EQ(replayed.header("preference-applied"), "respond-async");
  // nothing was created: nothing to apply
  const client::Response refused = submit_preferring("respond-async", R"({"name": "no materials"})");
  EXPECT_EQ(refused.status, 400);
  EXPECT_EQ(refused.header("preference-applied"), "");
  // the lines of a list header are one list (RFC 9110 5.3)
  const std::string answer =
      raw_exchange(server_->port(),
                   "POST /api/v1/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
                   "Prefer: wait=3\r\nPrefer: respond-async\r\nConnection: close\r\nContent-Length: " +
                       std::to_string(spec.size()) + "\r\n\r\n" + spec);
  EXPECT_EQ(status_of(answer), 201) << answer.substr(0, 400);
  EXPECT_NE(answer.find("\r\nPreference-Applied: respond-async\r\n"), std::string::npos) << answer.substr(0, 400);
}

TEST_F(ServerPreferences, RespondAsyncIsAppliedToAStudy) {
  start_server();
  const nlohmann::json study = {{"name", "prefer study"},
                                {"base", nlohmann::json::parse(pouring_spec(0.02, 100, 50))},
                                {"parameters", {{{"path", "lattices[0].radius"}, {"values", {0.02, 0.025}}}}}};
  const client::Response r = client_->request("POST", "/api/v1/studies", study.dump(), "application/json",
                                              {{"Prefer", "respond-async, wait=600"}});
  EXPECT_EQ(r.status, 201) << r.body;
  EXPECT_EQ(r.header("preference-applied"), "respond-async");
}

}  // namespace
}  // namespace dem::test
