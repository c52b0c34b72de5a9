#include "spec/clump_template.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace dem::spec {
namespace {

// The whole word as a finite number, or nothing.
bool parse_number(const std::string& word, double& value) {
  const char* end = word.data() + word.size();
  const auto [stop, error] = std::from_chars(word.data(), end, value);
  return error == std::errc() && stop == end && std::isfinite(value);
}

}  // namespace

std::vector<MemberSphere> read_clump_template(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open clump template " + path);
  std::vector<MemberSphere> spheres;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    line = line.substr(0, line.find('#'));
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream split(line);
    std::vector<std::string> words;
    for (std::string w; split >> w;) words.push_back(w);
    if (words.empty()) continue;  // blank or comment
    double v[4];
    const auto where = path + " line " + std::to_string(number);
    if (words.size() != 4 || !std::all_of(words.begin(), words.end(),
                                          [&, k = 0](const std::string& w) mutable { return parse_number(w, v[k++]); }))
      throw std::runtime_error(where + ": expected four numbers \"x y z r\"");
    if (!(v[3] > 0)) throw std::runtime_error(where + ": the radius must be positive");
    spheres.push_back({Vec3(v[0], v[1], v[2]), v[3]});
  }
  if (in.bad()) throw std::runtime_error("cannot read clump template " + path);
  if (spheres.empty()) throw std::runtime_error("clump template " + path + " has no spheres");
  return spheres;
}

}  // namespace dem::spec
