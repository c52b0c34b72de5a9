// The arguments of dem's client verbs (submit, status, ..., study --server): one parser and one
// way of reporting what the server said, for every verb.
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

extern const char* kCommonUsage;  // the options every client verb takes

struct Verb {
  const char* name;
  const char* usage;  // after "usage: dem "
  const char* first;  // what the first positional argument is
  std::vector<std::string> value_options;
  std::vector<std::string> flags;
  std::size_t min_positional, max_positional;
};

struct VerbArgs {
  std::vector<std::string> positional;
  std::map<std::string, std::string> values;
  std::set<std::string> flags;
  std::string server = "http://127.0.0.1:8080", token;
  double timeout_seconds = 300;  // for the server's whole answer (a download: for its next bytes)

  bool flag(const std::string& f) const { return flags.count(f) > 0; }
  std::string value(const std::string& option) const {
    const auto it = values.find(option);
    return it == values.end() ? "" : it->second;
  }
};

// Says what is wrong and how the verb is used; returns 2.
int usage_error(const Verb& verb, const std::string& problem);

// Fills `out`, or returns the exit status: 0 after --help, 2 after saying what is wrong.
std::optional<int> parse_verb_args(const Verb& verb, const std::vector<std::string>& args, VerbArgs& out);

// Runs `body` against the server, reporting what goes wrong in one way for every verb.
int with_server(const Verb& verb, const VerbArgs& a, const std::function<int(const ServerApi&)>& body);

std::optional<std::int64_t> job_id(const std::string& text);

}  // namespace dem::cli
