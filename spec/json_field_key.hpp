// A JSON key as protobuf's JSON parser matches it to a field: by the field's .proto name
// ("normal_stiffness") or its JSON name ("normalStiffness"), and by nothing else ("normalstiffness",
// "NormalStiffness" and "DENSITY" are unknown fields). Both accepted spellings give one key here, the
// snake_case one, and any other spelling a key of its own. Header-only: the study planner (study/,
// which has no protobuf descriptors) finds a base spec's field by the same rule.
#pragma once

#include <cctype>
#include <string>

namespace dem::spec {

inline std::string json_field_key(const std::string& key) {
  std::string out;
  for (const char c : key)
    if (std::isupper(static_cast<unsigned char>(c)))
      (out += '_') += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    else
      out += c;
  return out;
}

}  // namespace dem::spec
