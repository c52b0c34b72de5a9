// Fortran-style real numbers, as the legacy programs wrote them (docs/formats.md, "Numbers").
#include <charconv>
#include <system_error>

#include "legacy/legacy_formats.hpp"

namespace dem::legacy {
namespace {

// Longest token accepted. Far more than any program prints (%.6e gives at most 14 characters), and
// it lets the rewritten copy live on the stack.
constexpr std::size_t max_token_length = 128;

bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_sign(char c) { return c == '+' || c == '-'; }
bool is_exponent_letter(char c) { return c == 'e' || c == 'E' || c == 'd' || c == 'D'; }

// Rewrites a Fortran real into the form std::from_chars reads: drops a leading '+' (from_chars
// refuses it), turns a D exponent into 'e', and restores the 'e' that Fortran leaves out before a
// three-digit exponent ("1.0-100" is 1.0e-100). Checks the whole grammar on the way:
//   [sign] digits [. [digits]] | [sign] . digits, then optionally (e|E|d|D)[sign]digits or sign digits.
// Returns the rewritten length, or 0 if the token is not a real. `out` needs token.size() + 1 chars.
std::size_t rewrite_for_from_chars(std::string_view token, char* out) {
  std::size_t in = 0;
  std::size_t length = 0;
  auto copy_digits = [&] {
    std::size_t count = 0;
    while (in < token.size() && is_digit(token[in])) {
      out[length++] = token[in++];
      ++count;
    }
    return count;
  };

  if (in < token.size() && is_sign(token[in])) {
    if (token[in] == '-') out[length++] = '-';
    ++in;
  }
  std::size_t mantissa_digits = copy_digits();
  if (in < token.size() && token[in] == '.') {
    out[length++] = token[in++];
    mantissa_digits += copy_digits();
  }
  if (mantissa_digits == 0) return 0;  // ".", "+", "e5", "abc"

  if (in < token.size()) {
    if (is_exponent_letter(token[in])) {
      ++in;
    } else if (!is_sign(token[in])) {
      return 0;  // trailing junk such as "1.2.3" or "5x"
    }
    out[length++] = 'e';
    if (in < token.size() && is_sign(token[in])) out[length++] = token[in++];
    if (copy_digits() == 0) return 0;  // "1.0e", "1.0e+"
  }
  return in == token.size() ? length : 0;
}

}  // namespace

std::optional<double> parse_fortran_real(std::string_view token) {
  if (token.empty() || token.size() > max_token_length) return std::nullopt;
  char text[max_token_length + 1];
  const std::size_t length = rewrite_for_from_chars(token, text);
  if (length == 0) return std::nullopt;

  // std::from_chars is locale-independent (a decimal comma locale cannot change the result) and
  // fast. It reports values outside the range of double (1e400, 1e-400) as errors: no program
  // writing doubles or floats produces them, so such a token is rejected rather than guessed.
  double value = 0;
  const auto [end, error] = std::from_chars(text, text + length, value);
  if (error != std::errc{} || end != text + length) return std::nullopt;
  return value;
}

}  // namespace dem::legacy
