// A JSON key as protobuf's JSON parser matches it to a field: case and underscores do not count, so
// "normal_stiffness", "normalStiffness" and "normalstiffness" name one field. Header-only: the study
// planner (study/, which has no protobuf descriptors) finds a base spec's field by the same rule.
#pragma once

#include <cctype>
#include <string>

namespace dem::spec {

inline std::string json_field_key(const std::string& key) {
  std::string out;
  for (const char c : key)
    if (c != '_') out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace dem::spec
