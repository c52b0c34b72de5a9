// libFuzzer target: the server's request path before any job is touched: Beast's parser on the raw
// bytes, then the project's own parsing of what it gave (the target's path and query, the job id,
// the token, the Host and Origin checks, the transfer coding, the byte range of an artifact, the
// lists of Accept-Encoding and Prefer, the target as the request log writes it). Every input is
// parsed or refused; none crashes, a range kept lies inside the file, and a logged target is one
// line of printable ASCII.
#include <cstdint>
#include <string>

#include <boost/beast/http.hpp>

#include "server/content_coding.hpp"
#include "server/file_response.hpp"
#include "server/header_list.hpp"
#include "server/http_util.hpp"
#include "server/preferences.hpp"
#include "server/request_log.hpp"
#include "server/request_policy.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace http = boost::beast::http;
  using namespace dem::server;
  http::request_parser<http::string_body> parser;
  parser.body_limit(1 << 20);
  parser.eager(true);
  boost::beast::error_code error;
  parser.put(boost::asio::buffer(data, size), error);
  if (error || !parser.is_done()) return 0;
  const Request& req = parser.get();
  if (const auto absolute = split_absolute_form(req.target())) {
    if (absolute->origin_form.empty() || absolute->origin_form[0] != '/') __builtin_trap();
    parse_target(absolute->origin_form);
    host_of_authority(absolute->authority);
  }
  if (const auto target = parse_target(req.target())) {
    for (const std::string& s : target->segments) parse_job_id(s);
    request_token(req, *target);
  }
  if (const auto host = host_of_authority(req[http::field::host])) is_loopback_host(*host);
  if (const auto origin = authority_of_origin(req[http::field::origin]))
    same_authority(*origin, req[http::field::host]);
  classify_transfer_coding(req[http::field::transfer_encoding]);
  for (const std::uint64_t file_size : {std::uint64_t{0}, std::uint64_t{1}, std::uint64_t{1000}, UINT64_MAX}) {
    const RangeRequest r = parse_range(req[http::field::range], file_size);
    if (r.kind == RangeRequest::Part && (r.range.first > r.range.last || r.range.last >= file_size)) __builtin_trap();
  }
  accepts_gzip(header_list(req, http::field::accept_encoding));
  prefers_respond_async(req);
  for (const HeaderElement& e : parse_header_list(req.body()))
    if (e.name.empty()) __builtin_trap();  // an element without a name is dropped, never kept
  for (const char c : loggable_target(req.target()))
    if (c <= 0x20 || c >= 0x7f || c == '"') __builtin_trap();
  printable(req.body());
  return 0;
}
