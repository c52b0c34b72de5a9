#pragma once

#include <string>
#include <vector>

namespace dem::cli {

int run_command(const std::vector<std::string>& args);
int validate_command(const std::vector<std::string>& args);
int import_command(const std::vector<std::string>& args);  // cli/import_command.cpp

// Client verbs of a dem-server (cli/client_commands.cpp)
int submit_command(const std::vector<std::string>& args);
int status_command(const std::vector<std::string>& args);
int list_command(const std::vector<std::string>& args);
int cancel_command(const std::vector<std::string>& args);
int resume_command(const std::vector<std::string>& args);
int watch_command(const std::vector<std::string>& args);
int fetch_command(const std::vector<std::string>& args);

}  // namespace dem::cli
