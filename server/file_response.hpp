// A file as an HTTP response, with what clients of large files rely on: an ETag to ask again
// cheaply (If-None-Match: 304), byte ranges (Range: 206) to resume a download or read a part, and
// for text, gzip on request (Accept-Encoding), compressed as it is sent.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <boost/beast/http.hpp>

#include "server/http_util.hpp"

namespace dem::server {

// The file at `path`, with `headers`, ETag and Accept-Ranges: 304 when If-None-Match names its
// ETag, 206 with the bytes a single Range asks for (when If-Range, if given, is its ETag), 416 when
// that range starts past the end, else 200 with it whole (for HEAD: the headers alone). Several
// ranges or a malformed Range are answered whole (RFC 9110 14.2 lets a server ignore them).
// Nothing when it is not a regular file or cannot be opened.
//
// With GzipWhenAccepted (text, which compresses about threefold), the answer varies by
// Accept-Encoding (Vary): a client that accepts gzip is sent the file gzipped, chunked (its length is
// not known before it is compressed), with an ETag of its own (the file's with "-gzip" inside the
// quotes: a cache must not take one representation for the other). A request with a Range, and an
// HTTP/1.0 request (no chunked), get the file as it is: ranges are of the file's bytes.
using Headers = std::vector<std::pair<http::field, std::string>>;
enum class Compression { None, GzipWhenAccepted };
std::optional<http::message_generator> file_response(const Request& req, const std::filesystem::path& path,
                                                     const Headers& headers,
                                                     Compression compression = Compression::None);

// The bytes [first, last] of a file of `size` bytes a Range header asks for.
struct ByteRange {
  std::uint64_t first = 0, last = 0;
};
// Nothing to do with the range (answer whole): no "bytes=", several ranges, or malformed.
// Unsatisfiable (416): a range starting at or past the end, or an empty file.
struct RangeRequest {
  enum Kind { Whole, Part, Unsatisfiable } kind = Whole;
  ByteRange range;
};
RangeRequest parse_range(std::string_view header, std::uint64_t size);

}  // namespace dem::server
