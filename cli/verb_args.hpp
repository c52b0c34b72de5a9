// The command lines of dem's verbs: each verb is described once (its options, their values and
// help), CLI11 reads the arguments by that description, and the same description gives the verb's
// --help, dem's overview and the bash completion (cli/completion.cpp).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "cli/server_api.hpp"

namespace dem::cli {

struct VerbOption {
  const char* name;   // "--out"
  const char* value;  // what its value is ("DIR"); nullptr for a flag
  const char* help;
  bool repeated = false;  // may be given more than once (each value kept)
};

struct Verb {
  const char* name;
  const char* usage;    // after "usage: dem "
  const char* summary;  // what the verb does, in a line or two
  const char* first;    // what its positional arguments are ("SPEC.json"); "" for none
  std::vector<VerbOption> options;
  std::size_t min_positional = 0, max_positional = 0;
  bool client = false;            // talks to a dem-server: takes --server, --token, --timeout and --json
  const char* details = nullptr;  // more of its help, after the options
};

struct VerbArgs {
  std::vector<std::string> positional;
  std::map<std::string, std::vector<std::string>> values;  // each value option given, its values in order
  std::set<std::string> flags;
  std::string server = "http://127.0.0.1:8080", token;
  double timeout_seconds = 300;  // for the server's whole answer (a download: for its next bytes)
  bool json = false;             // a client verb's --json: the server's JSON on standard output

  bool flag(const std::string& f) const { return flags.count(f) > 0; }
  bool has(const std::string& option) const { return values.count(option) > 0; }
  // The option's value ("" when not given); a repeated option's last.
  std::string value(const std::string& option) const {
    const auto it = values.find(option);
    return it == values.end() ? "" : it->second.back();
  }
  std::vector<std::string> all(const std::string& option) const {
    const auto it = values.find(option);
    return it == values.end() ? std::vector<std::string>{} : it->second;
  }
};

// The options every client verb takes, after its own.
const std::vector<VerbOption>& client_options();

// Says what is wrong and how the verb is used; returns 2.
int usage_error(const Verb& verb, const std::string& problem);

// Fills `out`, or returns the exit status: 0 after --help (on standard output), 2 after saying
// what is wrong (an unknown option, a missing value, an option given twice, too few or too many
// positional arguments).
std::optional<int> parse_verb_args(const Verb& verb, const std::vector<std::string>& args, VerbArgs& out);

// `text` broken into lines of at most `width` characters, each after `indent` spaces but the first.
std::string wrap_words(const std::string& text, std::size_t indent, std::size_t width);

// The verb's --help.
std::string verb_help(const Verb& verb);

// Runs `body` against the server, reporting what goes wrong in one way for every verb.
int with_server(const Verb& verb, const VerbArgs& a, const std::function<int(const ServerApi&)>& body);

std::optional<std::int64_t> job_id(const std::string& text);

}  // namespace dem::cli
