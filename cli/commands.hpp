#pragma once

#include <string>
#include <vector>

namespace dem::cli {

int run_command(const std::vector<std::string>& args);
int validate_command(const std::vector<std::string>& args);

}  // namespace dem::cli
