#include "server/request_policy.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <cctype>
#include <ctime>
#include <string>
#include <vector>

namespace dem::server {
namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return std::tolower(c); });
  return out;
}

bool is_port(std::string_view p) {
  return !p.empty() && p.size() <= 5 &&
         std::all_of(p.begin(), p.end(), [](unsigned char c) { return std::isdigit(c); }) &&
         std::stoi(std::string(p)) <= 65535;
}

}  // namespace

std::optional<std::string> host_of_authority(std::string_view authority) {
  if (authority.empty()) return std::nullopt;
  if (authority[0] == '[') {  // an IPv6 literal, maybe with a port
    const std::size_t close = authority.find(']');
    if (close == std::string_view::npos) return std::nullopt;
    const std::string_view rest = authority.substr(close + 1);
    if (!rest.empty() && (rest[0] != ':' || !is_port(rest.substr(1)))) return std::nullopt;
    return lower(authority.substr(1, close - 1));
  }
  const std::size_t colon = authority.find(':');
  if (colon != std::string_view::npos && !is_port(authority.substr(colon + 1))) return std::nullopt;
  const std::string_view host = authority.substr(0, colon);
  if (host.empty()) return std::nullopt;
  return lower(host);
}

std::optional<std::string> authority_of_origin(std::string_view origin) {
  const std::size_t scheme = origin.find("://");
  if (scheme == std::string_view::npos) return std::nullopt;
  std::string_view rest = origin.substr(scheme + 3);
  rest = rest.substr(0, rest.find('/'));
  if (rest.empty()) return std::nullopt;
  return std::string(rest);
}

bool is_absolute_form(std::string_view target) {
  if (target.empty() || target[0] == '/') return false;
  const std::size_t scheme = target.find("://");
  return scheme != std::string_view::npos && target.find('/') > scheme;
}

std::optional<AbsoluteTarget> split_absolute_form(std::string_view target) {
  if (!is_absolute_form(target)) return std::nullopt;
  const std::size_t scheme_end = target.find("://");
  const std::string scheme = lower(target.substr(0, scheme_end));
  if (scheme != "http" && scheme != "https") return std::nullopt;
  const std::string_view rest = target.substr(scheme_end + 3);
  const std::size_t path = std::min(rest.find('/'), rest.find('?'));
  const std::string_view authority = rest.substr(0, path);
  // RFC 9110 4.2.4: userinfo in an http URI is not to be sent, and "user@evil" must not pass for a host
  if (authority.find('@') != std::string_view::npos || !host_of_authority(authority)) return std::nullopt;
  const std::string_view tail = path == std::string_view::npos ? std::string_view() : rest.substr(path);
  const bool from_root = !tail.empty() && tail[0] == '/';
  std::string origin_form = from_root ? std::string() : std::string(1, '/');
  origin_form.append(tail);
  return AbsoluteTarget{std::string(authority), std::move(origin_form)};
}

bool is_loopback_host(std::string_view host) {
  const std::string h = lower(host);
  if (h == "localhost") return true;
  in_addr v4{};
  if (inet_pton(AF_INET, h.c_str(), &v4) == 1) return (ntohl(v4.s_addr) >> 24) == 127;  // dotted quads only
  in6_addr v6{};
  if (inet_pton(AF_INET6, h.c_str(), &v6) == 1) {
    static const in6_addr loopback = IN6ADDR_LOOPBACK_INIT;
    if (std::equal(std::begin(v6.s6_addr), std::end(v6.s6_addr), std::begin(loopback.s6_addr))) return true;
    // ::ffff:127.x.y.z, an IPv4 loopback address written as IPv6
    const bool mapped = std::all_of(v6.s6_addr, v6.s6_addr + 10, [](unsigned char b) { return b == 0; }) &&
                        v6.s6_addr[10] == 0xff && v6.s6_addr[11] == 0xff;
    return mapped && v6.s6_addr[12] == 127;
  }
  return false;
}

bool same_authority(std::string_view a, std::string_view b) { return lower(a) == lower(b); }

bool is_cookie_safe(std::string_view token) {
  return !token.empty() && std::all_of(token.begin(), token.end(), [](unsigned char c) {
    return c > 0x20 && c < 0x7f && c != '"' && c != ',' && c != ';' && c != '\\';
  });
}

std::string http_date_now() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buf[40];
  std::strftime(buf, sizeof buf, "%a, %d %b %Y %H:%M:%S GMT", &utc);  // the C locale's English names
  return buf;
}

TransferCoding classify_transfer_coding(std::string_view value) {
  std::vector<std::string> codings;
  while (true) {
    const std::size_t comma = value.find(',');
    std::string coding(value.substr(0, comma));
    const auto blank = [](char c) { return c == ' ' || c == '\t'; };
    while (!coding.empty() && blank(coding.back())) coding.pop_back();
    std::size_t first = 0;
    while (first < coding.size() && blank(coding[first])) ++first;
    coding.erase(0, first);
    std::transform(coding.begin(), coding.end(), coding.begin(), [](unsigned char c) { return std::tolower(c); });
    if (!coding.empty()) codings.push_back(coding);  // RFC 9110 5.6.1: empty list elements are ignored
    if (comma == std::string_view::npos) break;
    value.remove_prefix(comma + 1);
  }
  if (codings.empty() || codings.back() != "chunked") return TransferCoding::NotChunkedLast;
  if (std::count(codings.begin(), codings.end(), "chunked") > 1) return TransferCoding::NotChunkedLast;
  return codings.size() == 1 ? TransferCoding::Chunked : TransferCoding::UnknownBeforeChunked;
}

}  // namespace dem::server
