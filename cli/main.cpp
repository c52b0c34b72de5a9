// dem: run a job spec locally, or check one.
#include <cstdio>
#include <string>
#include <vector>

#include "cli/commands.hpp"

namespace {

const char* kUsage =
    "usage:\n"
    "  dem run SPEC.json --out DIR [--threads N] [--quiet] [--restart FILE]\n"
    "                                   run a job spec, writing the legacy files and restart.dat to DIR;\n"
    "                                   --restart FILE continues from a saved state (e.g. DIR/restart.dat),\n"
    "                                   appending to DIR's files\n"
    "  dem validate SPEC.json                                 check a job spec and report every problem\n"
    "  dem help                                               this text\n";

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "help" || args[0] == "--help" || args[0] == "-h") {
    std::fputs(kUsage, args.empty() ? stderr : stdout);
    return args.empty() ? 2 : 0;
  }
  const std::string verb = args[0];
  args.erase(args.begin());
  if (verb == "run") return dem::cli::run_command(args);
  if (verb == "validate") return dem::cli::validate_command(args);
  std::fprintf(stderr, "dem: unknown command \"%s\"\n%s", verb.c_str(), kUsage);
  return 2;
}
