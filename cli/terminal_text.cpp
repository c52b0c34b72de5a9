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
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

void print_problems(const std::vector<std::string>& problems) {
  for (const std::string& p : problems) std::fprintf(stderr, "  %s\n", printable(p).c_str());
}

}  // namespace dem::cli
