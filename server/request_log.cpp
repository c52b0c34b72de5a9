#include "server/request_log.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>

#include <spdlog/spdlog.h>

#include "server/http_util.hpp"

namespace dem::server {
namespace {

constexpr std::size_t kLongestTarget = 2000;

std::string escaped(std::string_view bytes) {
  std::string out;
  for (const char ch : bytes) {
    const auto c = static_cast<unsigned char>(ch);
    if (c > 0x20 && c < 0x7f && c != '"' && c != '\\') {
      out.push_back(ch);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      out += hex;
    }
  }
  return out;
}

// A query parameter's name as the server reads it ('+' a space, escapes decoded), in lower case;
// as sent when it does not decode (its value is then redacted all the same if it names a token).
bool names_a_token(std::string_view raw_name) {
  std::string name(raw_name);
  std::replace(name.begin(), name.end(), '+', ' ');
  std::string decoded = percent_decode(name).value_or(name);
  std::transform(decoded.begin(), decoded.end(), decoded.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return decoded.find("token") != std::string::npos;
}

}  // namespace

namespace {

bool holds(std::string_view text, const std::string& secret) {
  if (secret.empty()) return false;
  if (text.find(secret) != std::string_view::npos) return true;
  std::string plus(text);
  std::replace(plus.begin(), plus.end(), '+', ' ');
  const std::optional<std::string> decoded = percent_decode(plus);
  return decoded && decoded->find(secret) != std::string::npos;
}

}  // namespace

std::string loggable_target(std::string_view target, const std::string& secret) {
  std::string redacted;
  const std::size_t question = target.find('?');
  redacted.append(target.substr(0, question));
  if (question != std::string_view::npos) {
    redacted.push_back('?');
    std::string_view query = target.substr(question + 1);
    for (bool first = true;; first = false) {
      const std::size_t amp = query.find('&');
      const std::string_view pair = query.substr(0, amp);
      const std::size_t eq = pair.find('=');
      if (!first) redacted.push_back('&');
      if (eq != std::string_view::npos && names_a_token(pair.substr(0, eq)))
        redacted.append(pair.substr(0, eq)).append("=REDACTED");
      else
        redacted.append(pair);
      if (amp == std::string_view::npos) break;
      query.remove_prefix(amp + 1);
    }
  }
  if (holds(redacted, secret)) {  // the token is still there, outside a parameter of its own
    const std::string_view path = target.substr(0, question);
    return holds(path, secret) ? "REDACTED" : loggable_target(path) + "?REDACTED";
  }
  std::string out = escaped(redacted);
  if (out.size() > kLongestTarget) out = out.substr(0, kLongestTarget) + "...";
  return out;
}

void log_request(const RequestLine& request, unsigned status, std::optional<std::uint64_t> bytes) {
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - request.start).count();
  const std::string status_text = status == 0 ? "-" : std::to_string(status);
  const std::string bytes_text = bytes ? std::to_string(*bytes) : "-";
  const std::string version = request.method == "-" ? "-" : request.version == 10 ? "HTTP/1.0" : "HTTP/1.1";
  spdlog::info("{} \"{} {} {}\" {} {} {:.2f} ms", request.client, escaped(request.method),
               request.target == "-" ? std::string("-") : loggable_target(request.target, request.secret), version,
               status_text, bytes_text, ms);
}

StatusReadingAnswer::const_buffers_type StatusReadingAnswer::prepare(boost::beast::error_code& ec) {
  const const_buffers_type buffers = answer_.prepare(ec);
  if (status_ == 0 && !ec) {
    // "HTTP/1.1 200 ...": the first 12 bytes, wherever the serializer split them
    char start[12];
    std::size_t have = 0;
    for (const auto& b : buffers) {
      const std::size_t take = std::min(b.size(), sizeof start - have);
      std::copy_n(static_cast<const char*>(b.data()), take, start + have);
      have += take;
      if (have == sizeof start) break;
    }
    if (have == sizeof start && std::isdigit(static_cast<unsigned char>(start[9])) &&
        std::isdigit(static_cast<unsigned char>(start[10])) && std::isdigit(static_cast<unsigned char>(start[11])))
      status_ = static_cast<unsigned>((start[9] - '0') * 100 + (start[10] - '0') * 10 + (start[11] - '0'));
  }
  return buffers;
}

}  // namespace dem::server
