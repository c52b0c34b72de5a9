// dem: run a job spec locally, check one, or drive a dem-server.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/completion.hpp"
#include "dem/version.hpp"

namespace {

using dem::cli::Verb;

// Each verb, its command line and its command: the dispatch, dem's overview, the check of a known
// verb for --version and the bash completion all come from this one table.
struct VerbEntry {
  const Verb* verb;
  int (*command)(const std::vector<std::string>&);
};
const VerbEntry kVerbs[] = {
    {&dem::cli::kRunVerb, dem::cli::run_command},           {&dem::cli::kValidateVerb, dem::cli::validate_command},
    {&dem::cli::kImportVerb, dem::cli::import_command},     {&dem::cli::kStudyVerb, dem::cli::study_command},
    {&dem::cli::kPlotVerb, dem::cli::plot_command},         {&dem::cli::kChainsVerb, dem::cli::chains_command},
    {&dem::cli::kDepositsVerb, dem::cli::deposits_command}, {&dem::cli::kSubmitVerb, dem::cli::submit_command},
    {&dem::cli::kStatusVerb, dem::cli::status_command},     {&dem::cli::kListVerb, dem::cli::list_command},
    {&dem::cli::kCancelVerb, dem::cli::cancel_command},     {&dem::cli::kResumeVerb, dem::cli::resume_command},
    {&dem::cli::kWatchVerb, dem::cli::watch_command},       {&dem::cli::kFetchVerb, dem::cli::fetch_command}};

std::vector<const Verb*> every_verb() {
  std::vector<const Verb*> verbs;
  for (const VerbEntry& entry : kVerbs) verbs.push_back(entry.verb);
  return verbs;
}

std::string overview() {
  std::string text = "usage: dem VERB [ARGUMENTS] (dem VERB --help: the verb's options)\n";
  bool clients = false;
  for (const VerbEntry& entry : kVerbs) {
    const Verb& verb = *entry.verb;
    if (verb.client && !clients && std::string(verb.name) != "study") {  // study also runs here
      clients = true;
      text +=
          "\ndem-server's clients (--server URL, default $DEM_SERVER, else http://127.0.0.1:8080; --token T, default "
          "$DEM_SERVER_TOKEN; --json: the server's JSON):\n";
    }
    const std::string usage = verb.usage;
    text +=
        "  dem " + usage.substr(0, usage.find('\n')) + "\n      " + dem::cli::wrap_words(verb.summary, 6, 94) + "\n";
  }
  return text +
         "\n  dem completion bash      the bash completion of these verbs (source <(dem completion bash))\n"
         "  dem help [VERB]          this text, or the verb's\n"
         "  dem --version            the version (also after any verb)\n";
}

int completion_command(const std::vector<std::string>& args) {
  if (args.size() == 1 && (args[0] == "--help" || args[0] == "-h")) {
    std::fputs("usage: dem completion bash\n  the bash completion of dem's verbs and options\n", stdout);
    return 0;
  }
  if (args.size() != 1 || args[0] != "bash") {
    std::fputs("dem completion: only bash is written\nusage: dem completion bash\n", stderr);
    return 2;
  }
  std::fputs(dem::cli::bash_completion(every_verb()).c_str(), stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.size() == 2 && args[0] == "help") {  // dem help VERB: the verb's own help
    const auto named =
        std::find_if(std::begin(kVerbs), std::end(kVerbs), [&](const VerbEntry& v) { return args[1] == v.verb->name; });
    if (named != std::end(kVerbs)) return named->command({"--help"});
    if (args[1] == "completion") return completion_command({"--help"});
    std::fprintf(stderr, "dem help: unknown command \"%s\"\n%s", args[1].c_str(), overview().c_str());
    return 2;
  }
  if (args.empty() || args[0] == "help" || args[0] == "--help" || args[0] == "-h") {
    std::fputs(overview().c_str(), args.empty() ? stderr : stdout);
    return args.empty() ? 2 : 0;
  }
  const std::string verb = args[0];
  const VerbEntry* entry =
      std::find_if(std::begin(kVerbs), std::end(kVerbs), [&](const VerbEntry& v) { return verb == v.verb->name; });
  const bool known = entry != std::end(kVerbs) || verb == "completion";
  if (verb == "--version" || verb == "version" ||
      (known && std::find(args.begin(), args.end(), "--version") != args.end())) {
    std::printf("dem %s\n", dem::kVersion);
    return 0;
  }
  args.erase(args.begin());
  if (verb == "completion") return completion_command(args);
  if (entry != std::end(kVerbs)) return entry->command(args);
  std::fprintf(stderr, "dem: unknown command \"%s\"\n%s", verb.c_str(), overview().c_str());
  return 2;
}
