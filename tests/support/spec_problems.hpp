// The problems a JSON spec is refused with, one a line, or "" when its scene is built.
#pragma once

#include <string>

#include "spec/spec_loader.hpp"

namespace dem::test {

inline std::string spec_problems(const std::string& json, const std::string& base_dir = "") {
  try {
    spec::to_scene(spec::parse_json(json), base_dir);
  } catch (const spec::SpecError& e) {
    std::string all;
    for (const std::string& p : e.problems()) all += p + "\n";
    return all;
  }
  return "";
}

}  // namespace dem::test
