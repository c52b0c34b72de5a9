// Keys a JSON spec gives twice in one object. The protobuf parser keeps the last one silently; a
// spec given twice a value (or once as "normalStiffness" and once as "normal_stiffness", the two
// spellings it accepts) is a mistake to name, not to guess.
#pragma once

#include <string>
#include <vector>

namespace dem::spec {

// The paths ("interactions[0].restitution") of the keys repeated in their object, in the order met.
// The text must be well-formed JSON (parse it for syntax first).
std::vector<std::string> repeated_keys(const std::string& json);

}  // namespace dem::spec
