// Text artifacts gzipped on request (Accept-Encoding, RFC 9110 12.5.3): the same bytes once
// inflated, an ETag of their own, Vary: Accept-Encoding, a Range answered as the file is, q=0 and
// identity respected, binary files never compressed, and a large file compressed as it is sent (the
// server's memory does not grow with it).
#include <zlib.h>

#include <atomic>
#include <random>

#include "support/raw_http.hpp"
#include "support/server_test.hpp"

namespace dem::test {
namespace {

// The bytes a gzip stream holds (empty and a failure when it is not one, whole).
std::string gunzipped(const std::string& gzip) {
  z_stream z{};
  if (inflateInit2(&z, 15 + 16) != Z_OK) return "";
  std::string out;
  char buffer[65536];
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(gzip.data()));
  z.avail_in = static_cast<uInt>(gzip.size());
  int rc = Z_OK;
  while (rc == Z_OK) {
    z.next_out = reinterpret_cast<Bytef*>(buffer);
    z.avail_out = sizeof buffer;
    rc = inflate(&z, Z_NO_FLUSH);
    out.append(buffer, sizeof buffer - z.avail_out);
  }
  inflateEnd(&z);
  EXPECT_EQ(rc, Z_STREAM_END) << "not a whole gzip stream";
  EXPECT_EQ(z.avail_in, 0u) << "bytes after the gzip stream";
  return out;
}

class ServerGzip : public ServerTest {
 protected:
  void SetUp() override {
    ServerTest::SetUp();
    start_server();
    id_ = submit_json(pouring_spec(0.02, 200, 100))["id"];
    ASSERT_EQ(wait_for(id_, "succeeded,failed")["state"], "succeeded");
  }
  std::string url(const std::string& name) { return "/api/v1/jobs/" + std::to_string(id_) + "/artifacts/" + name; }
  client::Response get(const std::string& target, const client::Headers& headers) {
    return client_->request("GET", target, "", "", headers);
  }
  long id_ = 0;
};

TEST_F(ServerGzip, ATextArtifactIsGzippedWhenAskedWithItsOwnETag) {
  for (const char* name : {"ANIMATION_3D.dat", "Energy.csv", "results.json", "particles.pvd"}) {
    const client::Response plain = client_->get(url(name));
    ASSERT_EQ(plain.status, 200) << name;
    EXPECT_EQ(plain.header("content-encoding"), "") << name;
    EXPECT_EQ(plain.header("vary"), "Accept-Encoding") << name;  // the answer depends on it either way
    const client::Response gzip = get(url(name), {{"Accept-Encoding", "gzip"}});
    ASSERT_EQ(gzip.status, 200) << name;
    EXPECT_EQ(gzip.header("content-encoding"), "gzip") << name;
    EXPECT_EQ(gzip.header("vary"), "Accept-Encoding") << name;
    EXPECT_EQ(gzip.header("transfer-encoding"), "chunked") << name;  // compressed as it is sent
    EXPECT_EQ(gzip.header("content-type"), plain.header("content-type")) << name;
    EXPECT_EQ(gzip.header("content-disposition"), plain.header("content-disposition")) << name;
    EXPECT_EQ(gunzipped(gzip.body), plain.body) << name;
    // a strong ETag names one representation's bytes: the gzipped one has its own
    const std::string tag = plain.header("etag");
    EXPECT_EQ(gzip.header("etag"), tag.substr(0, tag.size() - 1) + "-gzip\"") << name;
  }
  const client::Response plain = client_->get(url("ANIMATION_3D.dat"));
  const client::Response gzip = get(url("ANIMATION_3D.dat"), {{"Accept-Encoding", "gzip"}});
  EXPECT_LT(gzip.body.size() * 2, plain.body.size()) << "the animation compresses more than twofold";
}

TEST_F(ServerGzip, EachRepresentationIsAskedAgainByItsOwnETag) {
  const std::string file = url("ANIMATION_3D.dat");
  const std::string plain_tag = client_->get(file).header("etag");
  const std::string gzip_tag = get(file, {{"Accept-Encoding", "gzip"}}).header("etag");
  ASSERT_NE(plain_tag, gzip_tag);
  const client::Response same = get(file, {{"Accept-Encoding", "gzip"}, {"If-None-Match", gzip_tag}});
  EXPECT_EQ(same.status, 304);
  EXPECT_EQ(same.header("etag"), gzip_tag);
  EXPECT_EQ(same.header("vary"), "Accept-Encoding");
  EXPECT_TRUE(same.body.empty());
  EXPECT_EQ(get(file, {{"If-None-Match", plain_tag}}).status, 304);
  // a tag of the other representation is not this one's
  const client::Response other = get(file, {{"If-None-Match", gzip_tag}});
  EXPECT_EQ(other.status, 200);
  EXPECT_EQ(other.header("content-encoding"), "");
  const client::Response switched = get(file, {{"Accept-Encoding", "gzip"}, {"If-None-Match", plain_tag}});
  EXPECT_EQ(switched.status, 200);
  EXPECT_EQ(switched.header("content-encoding"), "gzip");
}

TEST_F(ServerGzip, ARangeIsAnsweredAsTheFileIsEvenWhenGzipIsAccepted) {
  const std::string file = url("ANIMATION_3D.dat");
  const client::Response plain = client_->get(file);
  const client::Response part = get(file, {{"Accept-Encoding", "gzip"}, {"Range", "bytes=10-29"}});
  EXPECT_EQ(part.status, 206);
  EXPECT_EQ(part.header("content-encoding"), "");
  EXPECT_EQ(part.header("vary"), "Accept-Encoding");
  EXPECT_EQ(part.header("etag"), plain.header("etag"));
  EXPECT_EQ(part.body, plain.body.substr(10, 20));
  // a Range that cannot be met, or is ignored, is answered as the file is too
  EXPECT_EQ(get(file, {{"Accept-Encoding", "gzip"}, {"Range", "bytes=999999999-"}}).status, 416);
  const client::Response ignored = get(file, {{"Accept-Encoding", "gzip"}, {"Range", "bytes=0-1,5-6"}});
  EXPECT_EQ(ignored.status, 200);
  EXPECT_EQ(ignored.header("content-encoding"), "");
  EXPECT_EQ(ignored.body, plain.body);
}

TEST_F(ServerGzip, AcceptEncodingIsReadWithItsWeightsAndIdentity) {
  const std::string file = url("Energy.dat");
  for (const auto& [accept, gzipped] : std::vector<std::pair<std::string, bool>>{{"gzip", true},
                                                                                 {"GZIP", true},
                                                                                 {"x-gzip", true},
                                                                                 {"deflate, gzip;q=1.0, br", true},
                                                                                 {"gzip ; q=0.5", true},
                                                                                 {"*", true},
                                                                                 {"identity;q=0, gzip;q=0.1", true},
                                                                                 {"br;q=1, *;q=0.3", true},
                                                                                 {"gzip;q=0", false},
                                                                                 {"gzip;q=0.000", false},
                                                                                 {"gzip;Q=0", false},
                                                                                 {"*;q=0", false},
                                                                                 {"*, gzip;q=0", false},
                                                                                 {"identity", false},
                                                                                 {"gzip;q=0.5, identity", false},
                                                                                 {"deflate, br", false},
                                                                                 {"gzip;q=high", false},
                                                                                 {"gzip;q=2", false},
                                                                                 {"", false}}) {
    const client::Response r = get(file, {{"Accept-Encoding", accept}});
    EXPECT_EQ(r.status, 200) << accept;
    EXPECT_EQ(r.header("content-encoding"), gzipped ? "gzip" : "") << "Accept-Encoding: " << accept;
  }
  // lines of one list header are one list (RFC 9110 5.3)
  const std::string two_lines = raw_exchange(server_->port(), "GET " + file +
                                                                  " HTTP/1.1\r\nHost: 127.0.0.1\r\nAccept-Encoding: "
                                                                  "br\r\nAccept-Encoding: gzip\r\nConnection: "
                                                                  "close\r\n\r\n");
  EXPECT_NE(two_lines.find("\r\nContent-Encoding: gzip\r\n"), std::string::npos) << two_lines.substr(0, 400);
  // HTTP/1.0 has no chunked framing: the file as it is, with its length
  const std::string old =
      raw_exchange(server_->port(), "GET " + file + " HTTP/1.0\r\nHost: 127.0.0.1\r\nAccept-Encoding: gzip\r\n\r\n");
  EXPECT_EQ(status_of(old), 200);
  EXPECT_EQ(old.find("Content-Encoding"), std::string::npos) << old.substr(0, 400);
  EXPECT_NE(old.find("Content-Length: "), std::string::npos) << old.substr(0, 400);
}

TEST_F(ServerGzip, BinaryFilesAndTheArchiveAreNeverGzippedAndHeadSaysWhatGetWould) {
  const nlohmann::json artifacts =
      nlohmann::json::parse(client_->get("/api/v1/jobs/" + std::to_string(id_) + "/artifacts").body);
  std::string vtu;
  for (const auto& a : artifacts["artifacts"])
    if (a["name"].get<std::string>().find(".vtu") != std::string::npos) vtu = a["name"];
  ASSERT_FALSE(vtu.empty()) << artifacts.dump();
  for (const std::string& name : {vtu, std::string("outputs.tar")}) {
    const client::Response r = get(url(name), {{"Accept-Encoding", "gzip"}});
    EXPECT_EQ(r.status, 200) << name;
    EXPECT_EQ(r.header("content-encoding"), "") << name;
    EXPECT_EQ(r.header("vary"), "") << name;  // one representation only
  }
  const client::Response head =
      client_->request("HEAD", url("ANIMATION_3D.dat"), "", "", {{"Accept-Encoding", "gzip"}});
  EXPECT_EQ(head.status, 200);
  EXPECT_EQ(head.header("content-encoding"), "gzip");
  EXPECT_EQ(head.header("etag"), get(url("ANIMATION_3D.dat"), {{"Accept-Encoding", "gzip"}}).header("etag"));
  EXPECT_EQ(head.header("content-length"), "");  // not known without compressing
  EXPECT_TRUE(head.body.empty());
  // the job's own log is text too
  const client::Response log = get("/api/v1/jobs/" + std::to_string(id_) + "/log", {{"Accept-Encoding", "gzip"}});
  EXPECT_EQ(log.header("content-encoding"), "gzip");
  EXPECT_EQ(gunzipped(log.body), client_->get("/api/v1/jobs/" + std::to_string(id_) + "/log").body);
}

// 200 MB of text compressed as it is sent: the server reads and deflates it a block at a time, so
// its memory stays near what it was (a copy of the file, or of its compressed bytes, would not).
TEST_F(ServerGzip, ALargeFileIsCompressedAsItIsSentNotInMemory) {
  const fs::path big = dir_ / "data" / "jobs" / std::to_string(id_) / "outputs" / "Large.dat";
  {
    std::ofstream out(big, std::ios::binary);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> coordinate(-1, 1);
    char line[96];
    for (std::size_t written = 0; written < (200u << 20);) {
      const int n = std::snprintf(line, sizeof line, "%9.6f %9.6f %9.6f %9.6f\n", coordinate(random),
                                  coordinate(random), coordinate(random), coordinate(random));
      out.write(line, n);
      written += static_cast<std::size_t>(n);
    }
  }
  const long before = server_->resident_kib();
  ASSERT_GT(before, 0);
  std::atomic<bool> done{false};
  std::atomic<long> peak{before};
  std::thread watch([&] {
    while (!done) {
      peak = std::max(peak.load(), server_->resident_kib());
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  });
  // read as it comes and counted, not kept (the test's memory is not the point)
  RawConnection raw(server_->port());
  raw.send("GET " + url("Large.dat") +
           " HTTP/1.1\r\nHost: 127.0.0.1\r\nAccept-Encoding: gzip\r\nConnection: close\r\n\r\n");
  std::uint64_t received = 0;
  std::string head;
  for (std::string more = raw.receive_some(30); !more.empty(); more = raw.receive_some(30)) {
    if (head.size() < 4096) head += more.substr(0, 4096 - head.size());
    received += more.size();
  }
  done = true;
  watch.join();
  EXPECT_EQ(status_of(head), 200) << head.substr(0, 300);
  EXPECT_NE(head.find("Content-Encoding: gzip"), std::string::npos) << head.substr(0, 300);
  EXPECT_GT(received, 20u << 20);   // all of it came, compressed
  EXPECT_LT(received, 150u << 20);  // about twofold for random digits
  EXPECT_LT(peak - before, 40 * 1024) << "the server's memory grew by " << (peak - before) / 1024 << " MB";
}

}  // namespace
}  // namespace dem::test
