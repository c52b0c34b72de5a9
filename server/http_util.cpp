#include "server/http_util.hpp"

#include "server/request_policy.hpp"

#include <algorithm>
#include <cctype>

namespace dem::server {
namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

std::optional<std::string> percent_decode(std::string_view text) {
  std::string out;
  for (std::size_t k = 0; k < text.size(); ++k) {
    if (text[k] != '%') {
      out.push_back(text[k]);
      continue;
    }
    const int hi = k + 1 < text.size() ? hex_value(text[k + 1]) : -1;
    const int lo = k + 2 < text.size() ? hex_value(text[k + 2]) : -1;
    if (hi < 0 || lo < 0) return std::nullopt;
    const char c = static_cast<char>(hi * 16 + lo);
    if (c == '\0') return std::nullopt;
    out.push_back(c);
    k += 2;
  }
  return out;
}

std::optional<Target> parse_target(std::string_view target) {
  Target out;
  const std::size_t q = target.find('?');
  const std::string_view path = target.substr(0, q);
  std::size_t start = 0;
  while (start <= path.size()) {
    std::size_t end = path.find('/', start);
    if (end == std::string_view::npos) end = path.size();
    if (end > start) {
      std::optional<std::string> segment = percent_decode(path.substr(start, end - start));
      // an escaped separator would let one segment name a path ("%2Fetc%2Fpasswd")
      if (!segment || segment->find_first_of("/\\") != std::string::npos) return std::nullopt;
      out.segments.push_back(std::move(*segment));
    }
    start = end + 1;
  }
  if (q != std::string_view::npos) {
    std::string_view query = target.substr(q + 1);
    while (!query.empty()) {
      const std::size_t amp = query.find('&');
      const std::string_view pair = query.substr(0, amp);
      const std::size_t eq = pair.find('=');
      std::string form(pair);
      std::replace(form.begin(), form.end(), '+', ' ');  // before decoding: "%2B" stays a '+'
      std::optional<std::string> key = percent_decode(std::string_view(form).substr(0, eq));
      std::optional<std::string> value = eq == std::string_view::npos
                                             ? std::optional<std::string>("")
                                             : percent_decode(std::string_view(form).substr(eq + 1));
      if (!key || !value) return std::nullopt;
      if (!pair.empty() && !out.query.emplace(*key, *value).second) {
        out.query[*key] = *value;
        if (std::find(out.repeated.begin(), out.repeated.end(), *key) == out.repeated.end())
          out.repeated.push_back(*key);
      }
      if (amp == std::string_view::npos) break;
      query = query.substr(amp + 1);
    }
  }
  return out;
}

std::string percent_encode(std::string_view text) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out;
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~') {
      out += ch;
    } else {
      out += '%';
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  return out;
}

http::response<http::string_body> text_response(const Request& req, http::status status,
                                                const std::string& content_type, std::string body) {
  http::response<http::string_body> res{status, req.version()};
  res.set(http::field::content_type, content_type);
  res.set(http::field::cache_control, "no-store");
  res.set(http::field::date, http_date_now());
  res.keep_alive(req.keep_alive());
  res.body() = std::move(body);
  res.prepare_payload();
  if (req.method() == http::verb::head) res.body().clear();  // the length stays in Content-Length
  return res;
}

http::response<http::string_body> json_response(const Request& req, http::status status, const nlohmann::json& body) {
  // bytes that are not UTF-8 (from a request's target or headers) are replaced, never thrown on
  return text_response(req, status, "application/json",
                       body.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

http::response<http::string_body> error_response(const Request& req, http::status status, const std::string& message,
                                                 const std::vector<std::string>& problems) {
  // RFC 9457: "about:blank" says the status is all the type there is, and the title is its phrase.
  // "error" repeats the detail for the clients written against the first answers ({"error"}).
  nlohmann::json body = {{"type", "about:blank"},
                         {"title", std::string(http::obsolete_reason(status))},
                         {"status", static_cast<unsigned>(status)},
                         {"detail", message},
                         {"error", message}};
  if (!req.target().empty()) body["instance"] = std::string(req.target());
  if (!problems.empty()) body["problems"] = problems;
  return text_response(req, status, "application/problem+json",
                       body.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

std::optional<std::int64_t> parse_job_id(const std::string& text) {
  if (text.empty() || text.size() > 18) return std::nullopt;
  for (char c : text)
    if (c < '0' || c > '9') return std::nullopt;
  return std::stoll(text);
}

std::string printable(std::string_view bytes) {
  std::string out;
  for (unsigned char c : bytes.substr(0, 40)) out.push_back(c >= 0x20 && c < 0x7f ? static_cast<char>(c) : '?');
  return out;
}

bool tokens_equal(std::string_view a, std::string_view b) {
  unsigned char differ = a.size() == b.size() ? 0 : 1;
  for (std::size_t k = 0; k < a.size(); ++k)
    differ |= static_cast<unsigned char>(a[k] ^ b[k % (b.size() ? b.size() : 1)]);
  return differ == 0 && !b.empty();
}

std::string request_token(const Request& req, const Target& target) {
  const auto header = req.find(http::field::authorization);
  if (header != req.end()) {
    const std::string_view value(header->value().data(), header->value().size());
    constexpr std::string_view bearer = "bearer ";
    if (value.size() <= bearer.size()) return "";
    for (std::size_t k = 0; k < bearer.size(); ++k)  // the scheme's name is case-insensitive (RFC 7235)
      if (std::tolower(static_cast<unsigned char>(value[k])) != bearer[k]) return "";
    return std::string(value.substr(bearer.size()));
  }
  const auto q = target.query.find("access_token");
  if (q != target.query.end()) return q->second;
  // the cookie the viewer's page was given (its scripts and styles cannot carry the token otherwise)
  const auto cookie = req.find(http::field::cookie);
  if (cookie != req.end()) {
    const std::string_view all(cookie->value().data(), cookie->value().size());
    constexpr std::string_view name = "dem_token=";
    for (std::size_t at = 0; at < all.size();) {
      while (at < all.size() && all[at] == ' ') ++at;
      const std::size_t end = std::min(all.find(';', at), all.size());
      if (all.substr(at, name.size()) == name) return std::string(all.substr(at + name.size(), end - at - name.size()));
      at = end + 1;
    }
  }
  return "";
}

}  // namespace dem::server
