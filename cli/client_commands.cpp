// The client verbs of dem: scripts drive a dem-server with them (submit, status, list, cancel,
// resume, watch, fetch). Exit status: 0 done, 1 the server or the job said no (or cannot be
// reached), 2 bad arguments.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/job_watch.hpp"
#include "cli/output_folder.hpp"
#include "cli/verb_args.hpp"
#include "cli/server_api.hpp"
#include "cli/terminal_text.hpp"
#include "spec/referenced_files.hpp"
#include "spec/spec_loader.hpp"

namespace dem::cli {
namespace {

namespace fs = std::filesystem;

const char* kArchive = "outputs.tar";  // every other artifact in one file; fetched only by name

// The verbs that name one job: parses the arguments and the id, then runs `body`.
int job_verb(const Verb& verb, const std::vector<std::string>& args,
             const std::function<int(const ServerApi&, const VerbArgs&, std::int64_t)>& body) {
  VerbArgs a;
  if (const auto exit = parse_verb_args(verb, args, a)) return *exit;
  const std::optional<std::int64_t> id = job_id(a.positional[0]);
  if (!id) return usage_error(verb, "a job id is a whole number (got \"" + a.positional[0] + "\")");
  return with_server(verb, a, [&](const ServerApi& api) { return body(api, a, *id); });
}

// A job the server answered with: its JSON (--json) or its summary line.
void print_job(const nlohmann::json& job, const VerbArgs& a) {
  if (a.json)
    print_json_line(job);
  else
    std::printf("%s\n", job_summary(job).c_str());
}

// An artifact is a plain file name of letters, digits, '.', '_' and '-', not starting with '.': the
// server's own rule, kept here because the list comes from a server, which might not be ours (a
// name with ESC, a line break or a right-to-left mark made files of those names).
bool is_artifact_name(const std::string& name) {
  if (name.empty() || name.size() > 100 || name[0] == '.') return false;
  return std::all_of(name.begin(), name.end(),
                     [](unsigned char c) { return std::isalnum(c) || c == '.' || c == '_' || c == '-'; });
}

}  // namespace

const Verb kSubmitVerb{"submit",
                       "submit SPEC.json [--wait] [--idempotency-key K] [--quiet] [--json]",
                       "send a job spec to dem-server (mesh files go inline) and print the job id",
                       "the spec file",
                       {{"--wait", nullptr, "follow the job to its end (exit 1 if it does not succeed)"},
                        {"--idempotency-key", "K", "the same key again gives the job first made, not a second one"},
                        {"--quiet", nullptr, "only the job id (and nothing while waiting)"}},
                       1,
                       1,
                       true};

int submit_command(const std::vector<std::string>& args) {
  static const Verb& verb = kSubmitVerb;
  VerbArgs a;
  if (const auto exit = parse_verb_args(verb, args, a)) return *exit;
  const std::string& path = a.positional[0];
  const bool quiet = a.flag("--quiet");
  if (quiet && a.json) return usage_error(verb, "--quiet and --json: give one (--json prints the job, --quiet its id)");
  api::JobSpec spec;
  try {
    spec = spec::read_json_file(path);
    spec::inline_files(spec, fs::path(path).parent_path().string());  // the server reads no files of ours
  } catch (const spec::SpecError& e) {
    std::fprintf(stderr, "%s: invalid spec:\n", path.c_str());
    print_problems(e.problems());
    return 1;
  }
  return with_server(verb, a, [&](const ServerApi& api) {
    client::Headers headers;
    const std::string key = a.value("--idempotency-key");
    if (!key.empty()) headers.emplace_back("Idempotency-Key", key);
    client::Response response;
    try {
      response = api.send("POST", "/api/v1/jobs", spec.SerializeAsString(), "application/x-protobuf", headers);
    } catch (const ApiError& e) {
      if (e.status() != 400 || e.problems().empty()) throw;
      std::fprintf(stderr, "%s: invalid spec (the server answered %s):\n", path.c_str(), describe(e).c_str());
      print_problems(e.problems());
      return 1;
    }
    const nlohmann::json job = checked_job(api.json_of(response, "/api/v1/jobs"));
    const std::int64_t id = job.at("id").get<std::int64_t>();
    if (a.json)
      print_json_line(job);
    else if (quiet)
      std::printf("%lld\n", static_cast<long long>(id));
    else if (response.header("idempotent-replayed") == "true")
      std::printf("already submitted with idempotency key %s: %s\n", key.c_str(), job_summary(job).c_str());
    else
      std::printf("submitted %s\n", job_summary(job).c_str());
    std::fflush(stdout);  // a script reading our output learns the id before the wait
    if (!a.flag("--wait")) return 0;
    return watch_job(api, id, verb.name, quiet ? WatchOutput::quiet : a.json ? WatchOutput::json : WatchOutput::lines);
  });
}

const Verb kStatusVerb{"status", "status ID [--json]", "one line on a job", "the job id", {}, 1, 1, true};

int status_command(const std::vector<std::string>& args) {
  static const Verb& verb = kStatusVerb;
  return job_verb(verb, args, [](const ServerApi& api, const VerbArgs& a, std::int64_t id) {
    // --json too: what is printed is a job (a proxy's page answered 200 is not success)
    print_job(checked_job(api.json_of(api.send("GET", job_target(id)), job_target(id))), a);
    return 0;
  });
}

// `text` as a query value (RFC 3986 2.3: anything but letters, digits and - _ . ~ escaped).
std::string query_value(const std::string& text) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out;
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~' || c == ',') {
      out += ch;
    } else {
      out += '%';
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  return out;
}

const Verb kListVerb{
    "list",
    "list [--state S[,S]] [--tag T[,T]] [--name N] [--json]",
    "the server's jobs (every page), or those in these states, with all these tags, of this name",
    "",
    {{"--state", "S[,S]", "queued, running, succeeded, failed, cancelled or interrupted; several: any of them"},
     {"--tag", "T[,T]", "jobs with every one of these tags"},
     {"--name", "N", "jobs of this name"}},
    0,
    0,
    true};

int list_command(const std::vector<std::string>& args) {
  static const Verb& verb = kListVerb;
  VerbArgs a;
  if (const auto exit = parse_verb_args(verb, args, a)) return *exit;
  static const std::set<std::string> kStates = {"queued", "running", "succeeded", "failed", "cancelled", "interrupted"};
  const std::string states = a.value("--state");
  for (std::size_t at = 0; a.has("--state") && at <= states.size();) {
    const std::size_t comma = std::min(states.find(',', at), states.size());
    const std::string state = states.substr(at, comma - at);
    if (!kStates.count(state))
      return usage_error(verb,
                         "--state is one or more of queued, running, succeeded, failed, cancelled, interrupted, "
                         "separated by commas (got \"" +
                             state + "\")");
    at = comma + 1;
  }
  // pages of 200 (the server's list of thousands of jobs, each with its results, is megabytes)
  std::string query = "?limit=200";
  for (const char* option : {"--state", "--tag", "--name"})
    if (a.has(option)) query += "&" + std::string(option + 2) + "=" + query_value(a.value(option));
  return with_server(verb, a, [&](const ServerApi& api) {
    nlohmann::json jobs = nlohmann::json::array();
    std::set<std::string> read;  // a server's next link back to a page read would list for ever
    for (std::string target = "/api/v1/jobs" + query; !target.empty();) {
      if (!read.insert(target).second) {
        std::fprintf(stderr, "dem list: the server's next page is a page already read: %s\n",
                     printable(target).c_str());
        return 1;
      }
      const nlohmann::json page = api.json_of(api.send("GET", target), target);
      for (const nlohmann::json& job : page.value("jobs", nlohmann::json::array())) jobs.push_back(job);
      const std::string next = page.value("next", "");
      if (!next.empty() && next.rfind("/api/", 0) != 0) {  // a link elsewhere: not this server's
        std::fprintf(stderr, "dem list: the server's next page is not under /api/: %s\n", printable(next).c_str());
        return 1;
      }
      target = next;
    }
    if (a.json) {
      print_json_line(nlohmann::json{{"jobs", jobs}});
      return 0;
    }
    if (jobs.empty()) {
      const bool filtered = a.has("--state") || a.has("--tag") || a.has("--name");
      std::fprintf(stderr, "no jobs%s\n", filtered ? " of these filters" : "");
      return 0;
    }
    std::printf("%8s  %-11s  %8s  %-21s  %s\n", "ID", "STATE", "PROGRESS", "STEP", "NAME");
    for (const nlohmann::json& job : jobs) {
      const std::string step =
          std::to_string(job.value("step", 0LL)) + "/" + std::to_string(job.value("totalSteps", 0LL));
      std::printf("%8lld  %-11s  %7.1f%%  %-21s  %s\n", job.value("id", 0LL), printable(job.value("state", "")).c_str(),
                  100 * job.value("progress", 0.0), step.c_str(), printable(job.value("name", "")).c_str());
    }
    return 0;
  });
}

const Verb kCancelVerb{"cancel", "cancel ID [--json]", "stop a queued or running job", "the job id", {}, 1, 1, true};

int cancel_command(const std::vector<std::string>& args) {
  static const Verb& verb = kCancelVerb;
  return job_verb(verb, args, [](const ServerApi& api, const VerbArgs& a, std::int64_t id) {
    print_job(checked_job(api.call("POST", job_target(id) + "/cancel")), a);
    return 0;
  });
}

const Verb kResumeVerb{
    "resume", "resume ID [--json]", "continue an interrupted job from its last checkpoint", "the job id", {}, 1, 1,
    true};

int resume_command(const std::vector<std::string>& args) {
  static const Verb& verb = kResumeVerb;
  return job_verb(verb, args, [](const ServerApi& api, const VerbArgs& a, std::int64_t id) {
    print_job(checked_job(api.call("POST", job_target(id) + "/resume")), a);
    return 0;
  });
}

const Verb kWatchVerb{"watch",
                      "watch ID [--json]",
                      "show a job's progress until it ends (--json: then the job's JSON)",
                      "the job id",
                      {},
                      1,
                      1,
                      true};

int watch_command(const std::vector<std::string>& args) {
  static const Verb& verb = kWatchVerb;
  return job_verb(verb, args, [](const ServerApi& api, const VerbArgs& a, std::int64_t id) {
    return watch_job(api, id, verb.name, a.json ? WatchOutput::json : WatchOutput::lines);
  });
}

const Verb kFetchVerb{"fetch",
                      "fetch ID [NAME ...] [--out DIR] [--json]",
                      "download a job's files to DIR (no NAME: every file but outputs.tar, which NAME may be)",
                      "the job id",
                      {{"--out", "DIR", "where the files go (default: here; made if missing)"}},
                      1,
                      SIZE_MAX,
                      true,
                      "--json: a list of the files fetched ({name, path, bytes}) and of those that were not "
                      "({name, error})"};

int fetch_command(const std::vector<std::string>& args) {
  static const Verb& verb = kFetchVerb;
  return job_verb(verb, args, [](const ServerApi& api, const VerbArgs& a, std::int64_t id) {
    std::vector<std::string> names(a.positional.begin() + 1, a.positional.end());
    for (const std::string& name : names)
      if (!is_artifact_name(name))
        return usage_error(verb, "\"" + name + "\" is not an artifact name (a file name, no folders)");
    const fs::path out = a.has("--out") ? fs::path(a.value("--out")) : fs::path(".");
    const std::string artifacts = job_target(id) + "/artifacts";
    int failed = 0;
    nlohmann::json fetched = nlohmann::json::array(), not_fetched = nlohmann::json::array();
    if (names.empty()) {
      const nlohmann::json listed = api.call("GET", artifacts).value("artifacts", nlohmann::json::array());
      for (const nlohmann::json& file : listed) {
        const std::string name = file.value("name", "");
        if (name == kArchive) continue;
        if (is_artifact_name(name)) {
          names.push_back(name);
          continue;
        }
        // the list is the server's: a name that leads out of --out is never written
        std::fprintf(stderr, "dem fetch: the server listed \"%s\", which is not a plain file name: not fetched\n",
                     printable(name).c_str());
        not_fetched.push_back({{"name", name}, {"error", "not a plain file name"}});
        ++failed;
      }
      if (names.empty() && failed == 0) {
        std::fprintf(stderr, "dem fetch: job %lld has no artifacts yet\n", static_cast<long long>(id));
        return 1;
      }
    }
    make_output_folder(out);
    for (const std::string& name : names) {
      const fs::path path = out / name;
      client::Response response;
      try {
        response = api.http().download(artifacts + "/" + name, path.string());
      } catch (const std::exception& e) {  // this file could not be written (or read): the others still are
        std::fprintf(stderr, "dem fetch: %s: %s\n", printable(name).c_str(), e.what());
        not_fetched.push_back({{"name", name}, {"error", e.what()}});
        ++failed;
        continue;
      }
      if (response.status != 200) {
        const std::string why = describe(api_error(response));
        std::fprintf(stderr, "dem fetch: %s: %s\n", printable(name).c_str(), why.c_str());
        not_fetched.push_back({{"name", name}, {"error", why}});
        ++failed;
        continue;
      }
      if (a.json) {
        std::error_code error;
        const auto bytes = fs::file_size(path, error);
        fetched.push_back({{"name", name}, {"path", path.string()}, {"bytes", error ? std::uintmax_t{0} : bytes}});
      } else {
        std::printf("%s\n", printable(path.string()).c_str());
      }
    }
    if (a.json) print_json_line({{"fetched", fetched}, {"notFetched", not_fetched}});
    return failed > 0 ? 1 : 0;
  });
}

}  // namespace dem::cli
