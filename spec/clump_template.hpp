// Clump template files: a rigid clump's spheres, one a line, "x y z r" (blanks or commas between,
// `#` starts a comment), as LIGGGHTS' and YADE's clump templates are usually kept.
#pragma once

#include <string>
#include <vector>

#include "clumps/mass_properties.hpp"

namespace dem::spec {

// Throws std::runtime_error naming the file and the line for anything else, a radius <= 0, or an
// empty file.
std::vector<MemberSphere> read_clump_template(const std::string& path);

}  // namespace dem::spec
