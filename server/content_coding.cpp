#include "server/content_coding.hpp"

#include <charconv>
#include <optional>

namespace dem::server {
namespace {

// RFC 9110 12.4.2: "0", "0.5", "1.000"; at most three decimals. Anything else is unreadable.
std::optional<double> parse_qvalue(const std::string& text) {
  if (text.empty() || (text[0] != '0' && text[0] != '1')) return std::nullopt;
  if (text.size() > 1 && (text[1] != '.' || text.size() > 5)) return std::nullopt;
  double q = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), q);
  if (ec != std::errc() || end != text.data() + text.size() || q > 1) return std::nullopt;
  return q;
}

// The weight an element gives its coding: its q (1 when not given, 0 when unreadable).
double weight(const HeaderElement& element) {
  const std::optional<std::string> q = element.param("q");
  if (!q) return 1;
  return parse_qvalue(*q).value_or(0);
}

}  // namespace

bool accepts_gzip(const std::vector<HeaderElement>& accept_encoding) {
  std::optional<double> gzip, any, identity;
  for (const HeaderElement& e : accept_encoding) {
    if (e.name == "gzip" || e.name == "x-gzip")
      gzip = weight(e);
    else if (e.name == "*")
      any = weight(e);
    else if (e.name == "identity")
      identity = weight(e);
  }
  const double q = gzip ? *gzip : any.value_or(0);
  return q > 0 && (!identity || q >= *identity);
}

}  // namespace dem::server
