#include "cli/terminal_text.hpp"

#include <cstdio>

namespace dem::cli {

std::string printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t k = 0; k < text.size(); ++k) {
    const auto c = static_cast<unsigned char>(text[k]);
    // C1 controls (U+0080 to U+009F) are two bytes in UTF-8, 0xC2 then 0x80 to 0x9F; CSI (U+009B)
    // starts an escape sequence on terminals that read them
    const bool c1 = c == 0xC2 && k + 1 < text.size() && static_cast<unsigned char>(text[k + 1]) >= 0x80 &&
                    static_cast<unsigned char>(text[k + 1]) <= 0x9F;
    if (c >= 0x20 && c != 0x7F && !c1) {
      out += static_cast<char>(c);
      continue;
    }
    const unsigned code = c1 ? static_cast<unsigned char>(text[++k]) : c;
    char escape[8];
    std::snprintf(escape, sizeof escape, c1 ? "\\u%04x" : "\\x%02x", code);
    out += escape;
  }
  return out;
}

}  // namespace dem::cli
