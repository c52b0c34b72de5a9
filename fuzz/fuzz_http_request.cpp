// libFuzzer target: the server's request path before any job is touched: Beast's parser on the raw
// bytes, then the project's own parsing of what it gave (the target's path and query, the job id,
// the token, the Host and Origin checks, the transfer coding, the byte range of an artifact). Every
// input is parsed or refused; none crashes, and a range kept lies inside the file.
#include <cstdint>
#include <string>

#include <boost/beast/http.hpp>

#include "server/file_response.hpp"
#include "server/http_util.hpp"
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
  printable(req.body());
  return 0;
}
