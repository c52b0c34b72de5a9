// Bash completion for dem, written from the verbs' own descriptions (cli/verb_args.hpp), so that
// it offers exactly the verbs and options the parser takes.
#pragma once

#include <string>
#include <vector>

#include "cli/verb_args.hpp"

namespace dem::cli {

// The script `source <(dem completion bash)` loads: verbs, their options, and for an option's value
// folders (DIR), files (a name with a dot, FILE, MESH) or the words of an "a|b|c" value.
std::string bash_completion(const std::vector<const Verb*>& verbs);

}  // namespace dem::cli
