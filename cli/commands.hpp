#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "cli/verb_args.hpp"
#include "core/scene.hpp"

namespace dem::cli {

// Each verb's command line (cli/verb_args.hpp), defined beside its command.
extern const Verb kRunVerb, kValidateVerb, kImportVerb, kStudyVerb, kPlotVerb, kChainsVerb, kDepositsVerb;
extern const Verb kSubmitVerb, kStatusVerb, kListVerb, kCancelVerb, kResumeVerb, kWatchVerb, kFetchVerb;

int run_command(const std::vector<std::string>& args);
int validate_command(const std::vector<std::string>& args);
int import_command(const std::vector<std::string>& args);    // cli/import_command.cpp
int study_command(const std::vector<std::string>& args);     // cli/study_command.cpp
int plot_command(const std::vector<std::string>& args);      // cli/plot_command.cpp
int chains_command(const std::vector<std::string>& args);    // cli/chains_command.cpp
int deposits_command(const std::vector<std::string>& args);  // cli/deposits_command.cpp

struct RunSceneOptions {
  int threads = -1;          // OpenMP threads; < 0: the spec's
  bool quiet = false;        // no progress line
  std::string restart;       // a saved state to continue from, "" for none
  std::FILE* log = nullptr;  // where its lines go; stdout and stderr when null
  bool profile = false;      // print the loop's time phase by phase (PhaseProfile)
  bool memory = false;       // add the process's peak resident memory to the summary (one run per process)
};

// Runs a checked scene into `out` as `dem run` does: the legacy files, restart.dat and results.json.
// Returns the exit status (0, or 1 when the run stopped); throws for a state or file that cannot be
// read or written.
int run_scene(Scene scene, const std::string& label, const std::string& out, const RunSceneOptions& options);

// Client verbs of a dem-server (cli/client_commands.cpp)
int submit_command(const std::vector<std::string>& args);
int status_command(const std::vector<std::string>& args);
int list_command(const std::vector<std::string>& args);
int cancel_command(const std::vector<std::string>& args);
int resume_command(const std::vector<std::string>& args);
int watch_command(const std::vector<std::string>& args);
int fetch_command(const std::vector<std::string>& args);

}  // namespace dem::cli
