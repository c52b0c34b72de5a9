#include "legacy/inpt_file.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

#include "legacy/legacy_formats.hpp"

namespace dem::legacy {
namespace {

// A file longer than any INPT.inp (the manuals' have 34 and 41 lines) is not one.
constexpr std::size_t kMaxLines = 1000;
constexpr std::size_t kMaxLineLength = 4096;

std::string trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string_view::npos) return "";
  const auto last = s.find_last_not_of(" \t");
  return std::string(s.substr(first, last - first + 1));
}

[[noreturn]] void refuse(int line, const std::string& what) {
  throw InptError("INPT.inp line " + std::to_string(line) + ": " + what);
}

std::string quoted(const InptLine& line) {
  std::string all;
  for (const std::string& v : line.values) all += (all.empty() ? "" : ", ") + v;
  return "\"" + all + "\"" + (line.comment.empty() ? "" : " (" + line.comment + ")");
}

const std::string& value_at(const InptLine& line, std::size_t index, const std::string& what) {
  if (index >= line.values.size())
    refuse(line.number, "has " + std::to_string(line.values.size()) + " value" + (line.values.size() == 1 ? "" : "s") +
                            ", and " + what + " is value " + std::to_string(index + 1) + ": " + quoted(line));
  return line.values[index];
}

}  // namespace

std::vector<InptLine> read_inpt(std::string_view text) {
  std::vector<std::string_view> raw;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    std::string_view line = text.substr(at, end - at);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    raw.push_back(line);
    at = end + 1;
  }
  while (!raw.empty() && trim(raw.back()).empty()) raw.pop_back();
  if (raw.empty()) throw InptError("INPT.inp is empty");
  if (raw.size() > kMaxLines)
    throw InptError("INPT.inp has " + std::to_string(raw.size()) + " lines, more than any INPT.inp (" +
                    std::to_string(kMaxLines) + "): is it the right file?");
  std::vector<InptLine> lines;
  for (std::size_t k = 0; k < raw.size(); ++k) {
    const int number = static_cast<int>(k) + 1;
    const std::string_view s = raw[k];
    if (s.size() > kMaxLineLength) refuse(number, "is longer than " + std::to_string(kMaxLineLength) + " characters");
    for (char c : s)
      if (static_cast<unsigned char>(c) < 0x20 && c != '\t') refuse(number, "holds a control character");
    InptLine line;
    line.number = number;
    std::string_view values = s;
    const std::size_t open = s.find('(');
    if (open != std::string_view::npos) {
      const std::size_t close = s.rfind(')');
      if (close == std::string_view::npos || close < open) refuse(number, "its comment's \"(\" is not closed");
      line.comment = trim(s.substr(open + 1, close - open - 1));
      if (const std::string after = trim(s.substr(close + 1)); !after.empty())
        refuse(number, "text follows its comment: \"" + after + "\"");
      values = s.substr(0, open);
    }
    // values between commas, or side by side: a comma with nothing before it is a missing value
    std::string token;
    bool since_comma = false;  // a value since the last comma (or the start)
    auto flush = [&] {
      if (!token.empty()) line.values.push_back(token);
      since_comma = since_comma || !token.empty();
      token.clear();
    };
    for (char c : values) {
      if (c == ',') {
        flush();
        if (!since_comma) refuse(number, "an empty value between two commas (or before the first)");
        since_comma = false;
      } else if (c == ' ' || c == '\t') {
        flush();
      } else {
        token += c;
      }
    }
    flush();
    if (line.values.empty())
      refuse(number, trim(s).empty() ? "is blank: INPT.inp has one parameter group on every line"
                                     : "has no value before its comment");
    lines.push_back(std::move(line));
  }
  return lines;
}

double inpt_real(const InptLine& line, std::size_t index, const std::string& what) {
  const std::string& v = value_at(line, index, what);
  const std::optional<double> x = parse_fortran_real(v);
  if (!x || !std::isfinite(*x)) refuse(line.number, what + " must be a number (got \"" + v + "\")");
  return *x;
}

long long inpt_integer(const InptLine& line, std::size_t index, const std::string& what) {
  const std::string& v = value_at(line, index, what);
  long long n = 0;
  const char* begin = v.data() + (v[0] == '+' ? 1 : 0);
  const auto [end, error] = std::from_chars(begin, v.data() + v.size(), n);
  if (error == std::errc() && end == v.data() + v.size()) return n;
  // a whole number written as a real ("0.0", "2.0E3") is the same count
  const std::optional<double> x = parse_fortran_real(v);
  if (x && std::isfinite(*x) && *x == std::floor(*x) && std::abs(*x) < 9e15) return static_cast<long long>(*x);
  refuse(line.number, what + " must be a whole number (got \"" + v + "\")");
}

bool inpt_logical(const InptLine& line, std::size_t index, const std::string& what) {
  std::string v = value_at(line, index, what);
  std::transform(v.begin(), v.end(), v.begin(), [](unsigned char c) { return std::tolower(c); });
  // Fortran reads a logical from its first letter after an optional period: .true., .t., t, true
  const std::size_t first = v[0] == '.' ? 1 : 0;
  if (first < v.size() && v[first] == 't') return true;
  if (first < v.size() && v[first] == 'f') return false;
  refuse(line.number, what + " must be .true. or .false. (got \"" + value_at(line, index, what) + "\")");
}

}  // namespace dem::legacy
