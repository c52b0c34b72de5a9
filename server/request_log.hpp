// The request log: a line per request answered, as a web server's access log has it,
//   127.0.0.1 "GET /api/v1/jobs/7/log?tail=20 HTTP/1.1" 200 1532 0.84 ms
// the client's address, the request line (method, target, version), the status, the bytes sent
// (header and body) and the time from the request's header to the answer's last byte; the time of
// day is the log line's (server_log.hpp). A query parameter whose name holds "token" (the
// access_token of browsers' WebSockets) has its value replaced by REDACTED, and no header is logged
// (the Authorization header and the viewer's cookie carry the token).
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <boost/beast/core/error.hpp>
#include <boost/beast/http/message_generator.hpp>

namespace dem::server {

// What the log says of a request; "-" for what was not read (a request refused before its header).
struct RequestLine {
  std::string client = "-";  // the peer's address
  std::string method = "-";
  std::string target = "-";  // as sent, before redaction
  unsigned version = 11;
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  std::string secret;  // the server's token: never written, however the target holds it
};

// The target with every token in its query redacted, and bytes outside printable ASCII, '"' and
// '\' written as \xHH (a line of the log stays one line, and its quotes stay its own); at most 2000
// characters.
// Past the query's parameters, a safety net: a target that holds `secret` anywhere (raw or
// percent-decoded: "?x=1?access_token=T", "http://user:T@host/", "%54") is written as its path
// alone with "?REDACTED", or as "REDACTED" when the path holds it.
std::string loggable_target(std::string_view target, const std::string& secret = "");

// Logs the line of a request answered with `status` (0: nothing was answered) after `bytes` sent
// (none: not known, a WebSocket's handshake).
void log_request(const RequestLine& request, unsigned status, std::optional<std::uint64_t> bytes);

// An answer as it is written, reading its status from its first bytes for the log (a
// message_generator hides its message). A BuffersGenerator of Beast's, as message_generator is.
class StatusReadingAnswer {
 public:
  using const_buffers_type = boost::beast::http::message_generator::const_buffers_type;
  StatusReadingAnswer(boost::beast::http::message_generator&& answer, unsigned& status)
      : answer_(std::move(answer)), status_(status) {}
  bool is_done() const { return answer_.is_done(); }
  const_buffers_type prepare(boost::beast::error_code& ec);
  void consume(std::size_t n) { answer_.consume(n); }

 private:
  boost::beast::http::message_generator answer_;
  unsigned& status_;  // 0 until the status line has been prepared
};

}  // namespace dem::server
