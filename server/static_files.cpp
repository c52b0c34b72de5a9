#include "server/static_files.hpp"

#include <algorithm>
#include <map>
#include <system_error>

#include "server/file_response.hpp"
#include "server/request_policy.hpp"

namespace dem::server {
namespace fs = std::filesystem;
namespace {

std::string mime_type(const fs::path& path) {
  static const std::map<std::string, std::string> types = {{".html", "text/html; charset=utf-8"},
                                                           {".js", "text/javascript; charset=utf-8"},
                                                           {".mjs", "text/javascript; charset=utf-8"},
                                                           {".css", "text/css; charset=utf-8"},
                                                           {".json", "application/json"},
                                                           {".svg", "image/svg+xml"},
                                                           {".png", "image/png"},
                                                           {".ico", "image/x-icon"},
                                                           {".wasm", "application/wasm"},
                                                           {".map", "application/json"},
                                                           {".dat", "text/plain; charset=utf-8"},
                                                           {".txt", "text/plain; charset=utf-8"}};
  const auto it = types.find(path.extension().string());
  return it == types.end() ? "application/octet-stream" : it->second;
}

// Shown at / when no viewer is installed beside the server.
constexpr const char* kNoViewerPage =
    "<!doctype html><meta charset=utf-8><title>dem-server</title>"
    "<h1>dem-server</h1><p>The viewer (web/) is not installed here. The REST API is at "
    "<a href=\"/api/jobs\">/api/jobs</a>, described by <a href=\"/api/openapi.json\">/api/openapi.json</a>.</p>\n";

}  // namespace

http::message_generator serve_static(const Request& req, const Target& target, const fs::path& root,
                                     const std::string& set_cookie) {
  constexpr const char* kAllowed = "GET, HEAD, OPTIONS";
  if (req.method() == http::verb::options) {
    http::response<http::string_body> res{http::status::no_content, req.version()};
    res.set(http::field::allow, kAllowed);
    res.set(http::field::date, http_date_now());
    res.keep_alive(req.keep_alive());  // no Content-Length in a 204 (RFC 9110 8.6)
    return res;
  }
  if (req.method() != http::verb::get && req.method() != http::verb::head) {
    auto res = error_response(req, http::status::method_not_allowed, "only GET and HEAD serve files");
    res.set(http::field::allow, kAllowed);
    return res;
  }
  fs::path path = root;
  for (const std::string& segment : target.segments) {
    if (segment.empty() || segment[0] == '.' || segment.find('\\') != std::string::npos)
      return error_response(req, http::status::not_found, "no such file: " + std::string(req.target()));
    path /= segment;
  }
  std::error_code ec;
  if (fs::is_directory(path, ec)) path /= "index.html";
  bool found = fs::is_regular_file(path, ec);
  if (found) {  // a link in the viewer's folder must not lead out of it (to the data, or to /etc)
    const fs::path real = fs::canonical(path, ec), real_root = fs::canonical(root, ec);
    const auto [root_end, real_at] = std::mismatch(real_root.begin(), real_root.end(), real.begin(), real.end());
    found = !ec && root_end == real_root.end();
  }
  if (!found && target.segments.empty()) {
    return text_response(req, http::status::ok, "text/html; charset=utf-8", kNoViewerPage);
  }
  if (!found) return error_response(req, http::status::not_found, "no such file: " + std::string(req.target()));
  Headers headers{{http::field::content_type, mime_type(path)}};
  if (!set_cookie.empty()) headers.emplace_back(http::field::set_cookie, set_cookie);
  std::optional<http::message_generator> file = file_response(req, path, headers);
  if (!file) return error_response(req, http::status::not_found, "no such file: " + std::string(req.target()));
  return std::move(*file);
}

}  // namespace dem::server
