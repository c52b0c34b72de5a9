#include "server/file_response.hpp"

#include <charconv>
#include <chrono>
#include <cstdio>
#include <system_error>

#include <boost/beast/core/file.hpp>
#include <boost/beast/http/basic_file_body.hpp>

#include "server/content_coding.hpp"
#include "server/gzip_body.hpp"
#include "server/request_policy.hpp"

namespace dem::server {
namespace {

namespace beast = boost::beast;

// A window [begin, begin + length) of a file, as a File of Beast's basic_file_body: the body then
// sends that window alone, read from the disk as it goes out (a part of a 1 GB ANIMATION_3D.dat is
// never held in memory).
class FileWindow {
 public:
  FileWindow() = default;
  FileWindow(beast::file&& file, std::uint64_t begin, std::uint64_t length, beast::error_code& ec)
      : file_(std::move(file)), length_(length) {
    file_.seek(begin, ec);
  }
  bool is_open() const { return file_.is_open(); }
  void close(beast::error_code& ec) { file_.close(ec); }
  void open(const char* path, beast::file_mode mode, beast::error_code& ec) {
    file_.open(path, mode, ec);
    length_ = ec ? 0 : file_.size(ec);
    read_ = 0;
  }
  std::uint64_t size(beast::error_code& ec) const {
    ec = {};
    return length_;
  }
  std::uint64_t pos(beast::error_code& ec) const {
    ec = {};
    return read_;
  }
  void seek(std::uint64_t, beast::error_code& ec) { ec = beast::errc::make_error_code(beast::errc::not_supported); }
  std::size_t read(void* buffer, std::size_t n, beast::error_code& ec) {
    const std::uint64_t left = length_ - read_;
    const std::size_t got = file_.read(buffer, static_cast<std::size_t>(std::min<std::uint64_t>(n, left)), ec);
    read_ += got;
    return got;
  }
  std::size_t write(const void*, std::size_t, beast::error_code& ec) {
    ec = beast::errc::make_error_code(beast::errc::not_supported);
    return 0;
  }

 private:
  beast::file file_;
  std::uint64_t length_ = 0;
  std::uint64_t read_ = 0;
};

using WindowBody = http::basic_file_body<FileWindow>;

// Digits, as many as given: a number past 2^64 - 1 is read as that (a position past any file).
std::optional<std::uint64_t> parse_position(std::string_view text) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string_view::npos) return std::nullopt;
  std::uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec == std::errc::result_out_of_range) return UINT64_MAX;
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

// Every line of a header a client may repeat, as one list (RFC 9110 5.3).
std::string joined(const Request& req, http::field field) {
  std::string list;
  for (auto [at, end] = req.equal_range(field); at != end; ++at) {
    if (!list.empty()) list += ", ";
    list += std::string(at->value());
  }
  return list;
}

// A strong validator from the file's size and modification time (as nginx and Apache make theirs):
// the outputs are written once, or appended to while a job runs, and either changes both.
std::string entity_tag(std::uint64_t size, std::filesystem::file_time_type modified) {
  const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(modified.time_since_epoch()).count();
  char text[64];
  std::snprintf(text, sizeof text, "\"%llx-%llx\"", static_cast<unsigned long long>(size),
                static_cast<unsigned long long>(ns));
  return text;
}

// The gzipped representation's tag: another than the file's (RFC 9110 8.8.3: a strong validator
// names one representation's bytes), "SIZE-TIME-gzip".
std::string gzip_entity_tag(const std::string& tag) { return tag.substr(0, tag.size() - 1) + "-gzip\""; }

// If-None-Match: "*" or a list of tags (weak ones compared weakly, RFC 9110 13.1.2).
bool names_tag(std::string_view list, const std::string& tag) {
  if (list == "*") return true;
  while (!list.empty()) {
    const std::size_t comma = list.find(',');
    std::string_view item = list.substr(0, comma);
    while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
    while (!item.empty() && item.back() == ' ') item.remove_suffix(1);
    if (item.substr(0, 2) == "W/") item.remove_prefix(2);
    if (item == tag) return true;
    if (comma == std::string_view::npos) break;
    list.remove_prefix(comma + 1);
  }
  return false;
}

}  // namespace

RangeRequest parse_range(std::string_view header, std::uint64_t size) {
  constexpr std::string_view kUnit = "bytes=";
  if (header.substr(0, kUnit.size()) != kUnit) return {};
  const std::string_view spec = header.substr(kUnit.size());
  const std::size_t dash = spec.find('-');
  if (dash == std::string_view::npos || spec.find(',') != std::string_view::npos) return {};
  const std::string_view first_text = spec.substr(0, dash), last_text = spec.substr(dash + 1);
  RangeRequest r;
  if (first_text.empty()) {  // "-N": the last N bytes
    const std::optional<std::uint64_t> n = parse_position(last_text);
    if (!n) return {};
    if (*n == 0 || size == 0) return {RangeRequest::Unsatisfiable, {}};
    r.range = {size - std::min(*n, size), size - 1};
  } else {
    const std::optional<std::uint64_t> first = parse_position(first_text);
    const std::optional<std::uint64_t> last =
        last_text.empty() ? std::optional<std::uint64_t>(UINT64_MAX) : parse_position(last_text);
    if (!first || !last || *last < *first) return {};
    if (*first >= size) return {RangeRequest::Unsatisfiable, {}};
    r.range = {*first, std::min(*last, size - 1)};
  }
  r.kind = RangeRequest::Part;
  return r;
}

std::optional<http::message_generator> file_response(const Request& req, const std::filesystem::path& path,
                                                     const Headers& headers, Compression compression) {
  std::error_code fs_error;
  if (!std::filesystem::is_regular_file(path, fs_error)) return std::nullopt;
  const std::filesystem::file_time_type modified = std::filesystem::last_write_time(path, fs_error);
  if (fs_error) return std::nullopt;
  beast::error_code ec;
  beast::file file;
  file.open(path.c_str(), beast::file_mode::scan, ec);
  if (ec) return std::nullopt;
  const std::uint64_t size = file.size(ec);
  if (ec) return std::nullopt;
  const bool negotiated = compression == Compression::GzipWhenAccepted;
  // a range is of the file's bytes, and a compressed answer's length is unknown until sent (chunked,
  // which HTTP/1.0 does not have): those are answered as the file is
  const bool gzip = negotiated && req.version() >= 11 && req.count(http::field::range) == 0 &&
                    accepts_gzip(header_list(req, http::field::accept_encoding));
  const std::string tag = gzip ? gzip_entity_tag(entity_tag(size, modified)) : entity_tag(size, modified);

  auto fill = [&](auto& res) {
    res.set(http::field::date, http_date_now());
    for (const auto& [field, value] : headers) res.set(field, value);
    res.set(http::field::etag, tag);
    res.set(http::field::accept_ranges, "bytes");
    if (negotiated) res.set(http::field::vary, "Accept-Encoding");  // caches keep the two apart
    res.keep_alive(req.keep_alive());
  };
  if (req.count(http::field::if_none_match) > 0 && names_tag(joined(req, http::field::if_none_match), tag)) {
    http::response<http::empty_body> not_modified{http::status::not_modified, req.version()};
    fill(not_modified);  // no Content-Length in a 304 (RFC 9110 8.6)
    return http::message_generator(std::move(not_modified));
  }
  if (gzip) {
    if (req.method() == http::verb::head) {  // the compressed length is not known without compressing
      http::response<http::empty_body> head{http::status::ok, req.version()};
      fill(head);
      head.set(http::field::content_encoding, "gzip");
      return http::message_generator(std::move(head));
    }
    http::response<GzipFileBody> res{std::piecewise_construct, std::make_tuple(std::move(file), size),
                                     std::make_tuple(http::status::ok, req.version())};
    fill(res);
    res.set(http::field::content_encoding, "gzip");
    res.chunked(true);
    return http::message_generator(std::move(res));
  }
  RangeRequest range;
  const auto range_header = req.find(http::field::range);
  const auto if_range = req.find(http::field::if_range);
  // one Range and at most one If-Range: several lines are several ranges, answered whole
  if (req.method() == http::verb::get && req.count(http::field::range) == 1 && req.count(http::field::if_range) <= 1 &&
      (if_range == req.end() || if_range->value() == tag))
    range = parse_range(range_header->value(), size);
  if (range.kind == RangeRequest::Unsatisfiable) {
    http::response<http::string_body> res =
        error_response(req, http::status::range_not_satisfiable,
                       "the range \"" + printable(range_header->value()) + "\" selects none of the file's " +
                           std::to_string(size) + " bytes");
    res.set(http::field::content_range, "bytes */" + std::to_string(size));
    res.set(http::field::etag, tag);
    res.set(http::field::accept_ranges, "bytes");
    if (negotiated) res.set(http::field::vary, "Accept-Encoding");
    return http::message_generator(std::move(res));
  }
  const std::uint64_t first = range.kind == RangeRequest::Part ? range.range.first : 0;
  const std::uint64_t length = range.kind == RangeRequest::Part ? range.range.last - first + 1 : size;
  const http::status status = range.kind == RangeRequest::Part ? http::status::partial_content : http::status::ok;
  if (req.method() == http::verb::head) {
    http::response<http::empty_body> head{status, req.version()};
    fill(head);
    head.content_length(length);
    return http::message_generator(std::move(head));
  }
  WindowBody::value_type body;
  body.reset(FileWindow(std::move(file), first, length, ec), ec);
  if (ec) return std::nullopt;
  http::response<WindowBody> res{std::piecewise_construct, std::make_tuple(std::move(body)),
                                 std::make_tuple(status, req.version())};
  fill(res);
  if (range.kind == RangeRequest::Part)
    res.set(http::field::content_range,
            "bytes " + std::to_string(first) + "-" + std::to_string(first + length - 1) + "/" + std::to_string(size));
  res.content_length(length);
  return http::message_generator(std::move(res));
}

}  // namespace dem::server
