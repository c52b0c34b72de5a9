// Small pieces of HTTP the server needs: splitting a target into path and query, decoding percent
// escapes, JSON answers, and comparing tokens in constant time.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <boost/beast/http.hpp>
#include <nlohmann/json.hpp>

namespace dem::server {

namespace http = boost::beast::http;
using Request = http::request<http::string_body>;

struct Target {
  std::vector<std::string> segments;  // the path's segments, percent-decoded
  // The query's parameters, percent-decoded, '+' read as a space (HTML's form encoding, which
  // browsers, curl --data-urlencode and Python's urlencode send); empty pairs ("a=1&&b=2") skipped.
  std::map<std::string, std::string> query;
  std::vector<std::string> repeated;  // parameters given more than once (query keeps the last)
};

// Empty optional when the path has a bad escape ("%zz"), an encoded NUL, or a segment that decodes
// to a path separator.
std::optional<Target> parse_target(std::string_view target);
std::optional<std::string> percent_decode(std::string_view text);
// `text` as a query value: anything but letters, digits and - _ . ~ percent-escaped (RFC 3986 2.3).
std::string percent_encode(std::string_view text);

// A response with `body` (for HEAD: its headers alone, Content-Length included).
http::response<http::string_body> text_response(const Request& req, http::status status,
                                                const std::string& content_type, std::string body);
http::response<http::string_body> json_response(const Request& req, http::status status, const nlohmann::json& body);
// RFC 9457 problem details (application/problem+json): type, title, status, detail (= message),
// instance (the request's target), "error" (= message, as the first answers had it) and "problems"
// (each a field path and what is wrong with it) when given.
http::response<http::string_body> error_response(const Request& req, http::status status, const std::string& message,
                                                 const std::vector<std::string>& problems = {});

// A job id as it appears in a path: decimal digits only.
std::optional<std::int64_t> parse_job_id(const std::string& text);

// Bytes from a request made safe to quote in an answer: at most 40, anything but printable ASCII as '?'.
std::string printable(std::string_view bytes);

bool tokens_equal(std::string_view a, std::string_view b);  // time independent of where they differ
// The token of a request: "Authorization: Bearer T", or ?access_token=T (browsers cannot set
// headers on a WebSocket), or the cookie dem_token=T that a page opened with ?access_token= gets.
std::string request_token(const Request& req, const Target& target);

}  // namespace dem::server
