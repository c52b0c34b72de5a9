// A small blocking client of dem-server over HTTP and WebSocket (Boost.Beast): the `dem` command's
// client verbs and the server's integration tests use it.
#pragma once

#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace dem::client {

class ClientError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Response {
  int status = 0;
  std::string body;
  std::map<std::string, std::string> headers;  // names in lower case
  std::string header(const std::string& lower_case_name) const;
};

using Headers = std::vector<std::pair<std::string, std::string>>;

class HttpClient {
 public:
  // `server`: "http://HOST:PORT" (a trailing slash is fine). `token`: sent as a bearer token if set.
  explicit HttpClient(const std::string& server, std::string token = "");

  // One request on a new connection; throws ClientError when the server cannot be reached.
  Response request(const std::string& method, const std::string& target, const std::string& body = "",
                   const std::string& content_type = "", const Headers& headers = {}) const;
  Response get(const std::string& target) const { return request("GET", target); }
  // GET into a file (streamed, written beside it and renamed when whole). The body is kept in the
  // response only when the status is not 200.
  Response download(const std::string& target, const std::string& path) const;

  // How long a request may wait for the whole answer (default 300 s; a download: for its next bytes,
  // 60 s or this, the shorter); past it a ClientError says the server did not answer in time.
  void set_answer_timeout(std::chrono::milliseconds timeout) { answer_timeout_ = timeout; }
  std::chrono::milliseconds answer_timeout() const { return answer_timeout_; }

  const std::string& host() const { return host_; }
  const std::string& port() const { return port_; }
  const std::string& token() const { return token_; }
  std::string url() const { return "http://" + host_ + ":" + port_; }

 private:
  std::string host_, port_, token_;
  std::chrono::milliseconds answer_timeout_{std::chrono::seconds(300)};
};

// The binary messages of a WebSocket (a job's frames), read one at a time.
class FrameStream {
 public:
  FrameStream(const HttpClient& client, const std::string& target);  // throws ClientError
  ~FrameStream();
  // The next binary message; empty when the server closed the stream (then close_reason() says why).
  std::optional<std::string> next();
  void send_text(const std::string& text);
  void close();
  const std::string& close_reason() const { return close_reason_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string close_reason_;
};

}  // namespace dem::client
