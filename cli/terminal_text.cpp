#include "cli/terminal_text.hpp"

#include <cstdio>

namespace dem::cli {
namespace {

// The code point of a three-byte UTF-8 sequence at `k` that reorders a terminal line: the bidi
// embeddings and overrides (U+202A to U+202E), isolates (U+2066 to U+2069) and marks (U+200E,
// U+200F); 0 for anything else. A name with U+202E shows its end first.
unsigned bidi_control_at(std::string_view text, std::size_t k) {
  if (k + 2 >= text.size() || static_cast<unsigned char>(text[k]) != 0xE2) return 0;
  const auto b1 = static_cast<unsigned char>(text[k + 1]), b2 = static_cast<unsigned char>(text[k + 2]);
  const unsigned code = 0x2000u | ((b1 & 0x3Fu) << 6) | (b2 & 0x3Fu);
  const bool bidi =
      (code >= 0x202A && code <= 0x202E) || (code >= 0x2066 && code <= 0x2069) || code == 0x200E || code == 0x200F;
  return (b1 & 0xC0) == 0x80 && (b2 & 0xC0) == 0x80 && bidi ? code : 0;
}

// The length of the well-formed UTF-8 sequence of two to four bytes at `k`; 0 when the byte there
// does not start one (a lone 0x9B, which an 8-bit terminal reads as CSI, or 0xFF).
std::size_t utf8_sequence_at(std::string_view text, std::size_t k) {
  const auto c = static_cast<unsigned char>(text[k]);
  const std::size_t length = c >= 0xC2 && c <= 0xDF ? 2 : c >= 0xE0 && c <= 0xEF ? 3 : c >= 0xF0 && c <= 0xF4 ? 4 : 0;
  if (length == 0 || k + length > text.size()) return 0;
  for (std::size_t b = 1; b < length; ++b)
    if ((static_cast<unsigned char>(text[k + b]) & 0xC0) != 0x80) return 0;
  return length;
}

}  // namespace

std::string printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t k = 0; k < text.size(); ++k) {
    const auto c = static_cast<unsigned char>(text[k]);
    // C1 controls (U+0080 to U+009F) are two bytes in UTF-8, 0xC2 then 0x80 to 0x9F; CSI (U+009B)
    // starts an escape sequence on terminals that read them
    const bool c1 = c == 0xC2 && k + 1 < text.size() && static_cast<unsigned char>(text[k + 1]) >= 0x80 &&
                    static_cast<unsigned char>(text[k + 1]) <= 0x9F;
    const unsigned bidi = bidi_control_at(text, k);
    char escape[8];
    if (bidi) {
      std::snprintf(escape, sizeof escape, "\\u%04x", bidi);
      out += escape;
      k += 2;
    } else if (c1) {
      std::snprintf(escape, sizeof escape, "\\u%04x", static_cast<unsigned char>(text[++k]));
      out += escape;
    } else if (c < 0x20 || c == 0x7F) {
      std::snprintf(escape, sizeof escape, "\\x%02x", c);
      out += escape;
    } else if (c >= 0x80) {  // a whole UTF-8 character stays; a byte that is not one is escaped
      const std::size_t length = utf8_sequence_at(text, k);
      if (length == 0) {
        std::snprintf(escape, sizeof escape, "\\x%02x", c);
        out += escape;
      } else {
        out.append(text.substr(k, length));
        k += length - 1;
      }
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

void print_problems(const std::vector<std::string>& problems) {
  for (const std::string& problem : problems) {
    // a problem of several lines (a file's problems, joined under its name) stays on several lines
    std::size_t start = 0;
    for (std::size_t end = problem.find('\n');; end = problem.find('\n', start)) {
      const std::string line = problem.substr(start, end == std::string::npos ? std::string::npos : end - start);
      std::fprintf(stderr, "  %s\n", printable(line).c_str());
      if (end == std::string::npos) break;
      start = end + 1;
    }
  }
}

}  // namespace dem::cli
