#include "import/line_fates.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <stdexcept>

namespace dem::import {

LineFates::LineFates(const std::vector<legacy::InptLine>& lines, const std::vector<Expected>& expected,
                     const std::string& program)
    : lines_(lines), fates_(expected.size()) {
  for (const Expected& e : expected) names_.push_back(e.name);
  if (lines.size() < names_.size()) {
    const std::size_t missing = lines.size();
    throw legacy::InptError("INPT.inp has " + std::to_string(lines.size()) + " lines, and " + program + "'s has " +
                            std::to_string(names_.size()) + ": it ends before line " + std::to_string(missing + 1) +
                            " (" + names_[missing] + ")");
  }
  if (lines.size() > names_.size())
    throw legacy::InptError("INPT.inp line " + std::to_string(names_.size() + 1) + ": " + program + "'s INPT.inp has " +
                            std::to_string(names_.size()) + " lines, and this one has " + std::to_string(lines.size()));
  for (std::size_t k = 0; k < expected.size(); ++k)
    if (lines[k].values.size() != expected[k].values) {
      std::string all;
      for (const std::string& v : lines[k].values) all += (all.empty() ? "" : ", ") + v;
      refuse(static_cast<int>(k) + 1, "has " + std::to_string(lines[k].values.size()) + " value" +
                                          (lines[k].values.size() == 1 ? "" : "s") + " where it holds " +
                                          std::to_string(expected[k].values) + ": \"" + all + "\"");
    }
}

void LineFates::refuse(int number, const std::string& what) const {
  throw legacy::InptError("INPT.inp line " + std::to_string(number) + " (" + names_[number - 1] + "): " + what);
}

double LineFates::real(int number, std::size_t index) const {
  return legacy::inpt_real(line(number), index, name(number));
}

long long LineFates::integer(int number, std::size_t index) const {
  return legacy::inpt_integer(line(number), index, name(number));
}

bool LineFates::logical(int number, std::size_t index) const {
  return legacy::inpt_logical(line(number), index, name(number));
}

std::string LineFates::word(int number, std::size_t index) const {
  if (index >= line(number).values.size()) refuse(number, "has no value " + std::to_string(index + 1));
  std::string w = line(number).values[index];
  std::transform(w.begin(), w.end(), w.begin(), [](unsigned char c) { return std::toupper(c); });
  return w;
}

std::vector<LineFate> LineFates::fates() const {
  std::vector<LineFate> out;
  for (std::size_t k = 0; k < names_.size(); ++k) {
    if (fates_[k].empty()) throw std::logic_error("the importer gave INPT line " + std::to_string(k + 1) + " no fate");
    std::string text;
    for (const std::string& v : lines_[k].values) text += (text.empty() ? "" : ", ") + v;
    out.push_back({static_cast<int>(k) + 1, names_[k], text, fates_[k]});
  }
  return out;
}

std::string show(double v) {
  char buf[32];
  const auto [end, error] = std::to_chars(buf, buf + sizeof buf, v);
  return error == std::errc() ? std::string(buf, end) : std::to_string(v);
}

}  // namespace dem::import
