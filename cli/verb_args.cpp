#include "cli/verb_args.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "cli/terminal_text.hpp"

namespace dem::cli {

const std::vector<VerbOption>& client_options() {
  static const std::vector<VerbOption> options = {
      {"--server", "URL", "the dem-server (default: $DEM_SERVER, else http://127.0.0.1:8080)"},
      {"--token", "T", "its token (default: $DEM_SERVER_TOKEN)"},
      {"--timeout", "S", "seconds to wait for the server's answer (a download: for its next bytes; default 300)"},
      {"--json", nullptr, "the server's JSON on standard output instead of lines of text"},
  };
  return options;
}

namespace {

std::vector<VerbOption> every_option(const Verb& verb) {
  std::vector<VerbOption> options = verb.options;
  if (verb.client) options.insert(options.end(), client_options().begin(), client_options().end());
  return options;
}

}  // namespace

// `text` broken into lines of at most `width` characters, each after `indent` spaces but the first.
std::string wrap_words(const std::string& text, std::size_t indent, std::size_t width) {
  std::istringstream words(text);
  std::string out, line, word;
  while (words >> word) {
    if (!line.empty() && line.size() + 1 + word.size() > width) {
      out += line + "\n" + std::string(indent, ' ');
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  return out + line;
}

std::string verb_help(const Verb& verb) {
  constexpr std::size_t kColumn = 22, kWidth = 78;
  std::string help = std::string("usage: dem ") + verb.usage + "\n  " + wrap_words(verb.summary, 2, kWidth) + "\n";
  auto line = [&](const std::string& left, const std::string& text) {
    std::string row = "  " + left;
    row += row.size() < kColumn ? std::string(kColumn - row.size(), ' ') : "\n" + std::string(kColumn, ' ');
    help += row + wrap_words(text, kColumn, kWidth - kColumn) + "\n";
  };
  help += "options:\n";
  for (const VerbOption& o : every_option(verb))
    line(std::string(o.name) + (o.value ? std::string(" ") + o.value : "") + (o.repeated ? " ..." : ""), o.help);
  line("-h, --help", "this help");
  line("--version", "dem's version");
  if (verb.details != nullptr) help += "\n  " + wrap_words(verb.details, 2, kWidth) + "\n";
  if (verb.client)
    help += "exit status: 0 done (a followed job succeeded), 1 the job failed or the server said no, 2 bad arguments\n";
  else if (verb.details == nullptr || std::string(verb.details).find("exit status") == std::string::npos)
    help += "exit status: 0 done, 1 failed, 2 bad arguments\n";
  return help;
}

int usage_error(const Verb& verb, const std::string& problem) {
  std::fprintf(stderr, "dem %s: %s\nusage: dem %s\n(dem %s --help: every option)\n", verb.name, problem.c_str(),
               verb.usage, verb.name);
  return 2;
}

std::optional<int> parse_verb_args(const Verb& verb, const std::vector<std::string>& args, VerbArgs& out) {
  if (const char* server = std::getenv("DEM_SERVER"); server && *server) out.server = server;
  if (const char* token = std::getenv("DEM_SERVER_TOKEN")) out.token = token;
  CLI::App app{verb.summary, std::string("dem ") + verb.name};
  app.allow_extras();  // an unknown option is told below in dem's words, naming it
  std::vector<std::string> positional;
  app.add_option("positional", positional);
  const std::vector<VerbOption> options = every_option(verb);
  std::map<std::string, std::vector<std::string>> given;
  for (const VerbOption& o : options) {
    if (o.value == nullptr)
      app.add_flag(o.name);
    else  // one value per occurrence, never the next positional argument
      app.add_option(o.name, given[o.name])->expected(1)->allow_extra_args(false)->take_all();
  }
  // a flag takes no value: CLI11 reads --wait=false as false and --wait=0 as a count; and an option
  // given "=" and nothing: CLI11 took the next argument as its value (--out= --plan ran the study
  // into a folder named --plan)
  for (const std::string& arg : args) {
    if (arg == "--") break;
    for (const VerbOption& o : options) {
      if (o.value == nullptr && arg.rfind(std::string(o.name) + "=", 0) == 0)
        return usage_error(verb, std::string(o.name) + " takes no value (got \"" + arg + "\")");
      if (o.value != nullptr && arg == std::string(o.name) + "=")
        return usage_error(verb, std::string(o.name) + " is given an empty value");
    }
  }
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 reads the arguments from the back
  try {
    app.parse(reversed);
  } catch (const CLI::CallForHelp&) {
    std::fputs(verb_help(verb).c_str(), stdout);
    return 0;
  } catch (const CLI::ArgumentMismatch& e) {  // CLI11's "--out: 1 required TEXT missing"
    const std::string what = e.what();
    return usage_error(verb, what.substr(0, what.find(':')) + " needs a value");
  } catch (const CLI::ParseError& e) {
    return usage_error(verb, e.what());
  }
  for (const std::string& extra : app.remaining())
    if (extra != "--") return usage_error(verb, "unknown option " + extra);
  for (const VerbOption& o : options) {
    std::vector<std::string>& values = given[o.name];
    const std::size_t times = o.value == nullptr ? app.count(o.name) : values.size();
    if (times > 1 && !o.repeated)
      return usage_error(verb, std::string(o.name) + " is given " + std::to_string(times) + " times (once at most)");
    if (o.value == nullptr && times > 0) out.flags.insert(o.name);
    if (values.empty()) continue;
    for (const std::string& v : values)
      if (v.empty()) return usage_error(verb, std::string(o.name) + " is given an empty value");
    out.values[o.name] = values;
  }
  out.positional = positional;
  if (out.positional.size() < verb.min_positional) return usage_error(verb, std::string("missing ") + verb.first);
  if (out.positional.size() > verb.max_positional)
    return usage_error(verb, "unexpected \"" + out.positional[verb.max_positional] + "\"");
  if (verb.client) {
    if (out.has("--server")) out.server = out.value("--server");
    if (out.has("--token")) out.token = out.value("--token");
    out.json = out.flag("--json");
    if (out.has("--timeout")) {
      const std::string v = out.value("--timeout");
      char* end = nullptr;
      out.timeout_seconds = std::strtod(v.c_str(), &end);
      const bool decimal = v.find_first_not_of("0123456789.eE+-") == std::string::npos;  // strtod takes 0x10, inf
      if (!decimal || end == v.c_str() || *end != '\0' || !(out.timeout_seconds > 0) || out.timeout_seconds > 1e6)
        return usage_error(verb, "--timeout is a number of seconds in (0, 1e6] (got \"" + v + "\")");
    }
    // a line break in a header's value would add headers of its own to the request
    const std::pair<const char*, std::string> header_values[] = {{"--token", out.token},
                                                                 {"--idempotency-key", out.value("--idempotency-key")}};
    for (const auto& [option, v] : header_values)
      if (std::any_of(v.begin(), v.end(), [](unsigned char c) { return c < 0x20 || c == 0x7f; }))
        return usage_error(
            verb,
            std::string(option) + " holds a control character (a line break?)" +
                (std::string(option) == "--token" && !out.has("--token") ? " (it came from $DEM_SERVER_TOKEN)" : ""));
  }
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
    print_problems(e.problems());
  } catch (const nlohmann::json::exception& e) {  // a field of the wrong type: not dem-server's answer
    std::fprintf(stderr, "dem %s: the server's answer is not of dem-server's form (%s)\n", verb.name,
                 printable(e.what()).c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dem %s: %s\n", verb.name, e.what());
  }
  return 1;
}

}  // namespace dem::cli
