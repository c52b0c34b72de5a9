#include "cli/verb_args.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "cli/terminal_text.hpp"

namespace dem::cli {

const char* kCommonUsage = " [--server URL] [--token T] [--timeout S]";

int usage_error(const Verb& verb, const std::string& problem) {
  std::fprintf(stderr, "dem %s: %s\nusage: dem %s%s\n", verb.name, problem.c_str(), verb.usage, kCommonUsage);
  return 2;
}

// Fills `out`, or returns the exit status: 0 after --help, 2 after saying what is wrong.
std::optional<int> parse_verb_args(const Verb& verb, const std::vector<std::string>& args, VerbArgs& out) {
  if (const char* server = std::getenv("DEM_SERVER"); server && *server) out.server = server;
  if (const char* token = std::getenv("DEM_SERVER_TOKEN")) out.token = token;
  auto listed = [](const std::vector<std::string>& list, const std::string& a) {
    return std::find(list.begin(), list.end(), a) != list.end();
  };
  for (std::size_t k = 0; k < args.size(); ++k) {
    const std::string& a = args[k];
    if (a == "-h" || a == "--help") {
      std::printf("usage: dem %s%s\n", verb.usage, kCommonUsage);
      return 0;
    }
    const bool takes_value = a == "--server" || a == "--token" || a == "--timeout" || listed(verb.value_options, a);
    if (takes_value) {
      if (k + 1 >= args.size()) return usage_error(verb, a + " needs a value");
      const std::string& v = args[++k];
      if (a == "--server")
        out.server = v;
      else if (a == "--token")
        out.token = v;
      else if (a == "--timeout") {
        char* end = nullptr;
        out.timeout_seconds = std::strtod(v.c_str(), &end);
        if (end == v.c_str() || *end != '\0' || !(out.timeout_seconds > 0) || out.timeout_seconds > 1e6)
          return usage_error(verb, "--timeout is a number of seconds in (0, 1e6] (got \"" + v + "\")");
      } else
        out.values[a] = v;
    } else if (listed(verb.flags, a)) {
      out.flags.insert(a);
    } else if (a.size() > 1 && a[0] == '-') {
      return usage_error(verb, "unknown option " + a);
    } else {
      out.positional.push_back(a);
    }
  }
  if (out.positional.size() < verb.min_positional) return usage_error(verb, std::string("missing ") + verb.first);
  if (out.positional.size() > verb.max_positional)
    return usage_error(verb, "unexpected \"" + out.positional.back() + "\"");
  return std::nullopt;
}

std::optional<std::int64_t> job_id(const std::string& text) {
  if (text.empty() || text.size() > 18 ||
      !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return std::nullopt;
  return std::stoll(text);
}

// Runs `body` against the server, reporting what goes wrong in one way for every verb.
int with_server(const Verb& verb, const VerbArgs& a, const std::function<int(const ServerApi&)>& body) {
  std::optional<ServerApi> api;
  try {
    client::HttpClient http(a.server, a.token);
    http.set_answer_timeout(std::chrono::milliseconds(static_cast<long long>(a.timeout_seconds * 1000)));
    api.emplace(std::move(http));
  } catch (const client::ClientError& e) {
    return usage_error(verb, e.what());
  }
  try {
    return body(*api);
  } catch (const ApiError& e) {
    std::fprintf(stderr, "dem %s: %s\n", verb.name, describe(e).c_str());
    for (const std::string& p : e.problems()) std::fprintf(stderr, "  %s\n", p.c_str());
  } catch (const nlohmann::json::exception& e) {  // a field of the wrong type: not dem-server's answer
    std::fprintf(stderr, "dem %s: the server's answer is not of dem-server's form (%s)\n", verb.name,
                 printable(e.what()).c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dem %s: %s\n", verb.name, e.what());
  }
  return 1;
}

}  // namespace dem::cli
