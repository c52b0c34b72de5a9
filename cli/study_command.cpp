// dem study: a parameter study (study/study_plan.hpp) run here, one job after another (or a few at
// once, --jobs), or on a dem-server (--submit), ending with its table (study.csv, study.json) and
// figure (study.svg).
#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <mutex>
#include <optional>
#include <random>
#include <sstream>
#include <thread>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include "cli/commands.hpp"
#include "cli/output_folder.hpp"
#include "cli/terminal_text.hpp"
#include "cli/verb_args.hpp"
#include "core/errors.hpp"
#include "results/results_json.hpp"
#include "spec/json_keys.hpp"
#include "spec/referenced_files.hpp"
#include "spec/spec_loader.hpp"
#include "study/study_table.hpp"

namespace dem::cli {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

}  // namespace

const Verb kStudyVerb{
    "study",
    "study STUDY.json --out DIR [--jobs N] [--threads N] [--quiet] [--plan]\n"
    "       dem study STUDY.json --out DIR --submit [--detach] [--json]\n"
    "       dem study --id ID --out DIR [--json]",
    "a parameter study: the base spec's runs for each value (or combination of values) of the fields it names, "
    "into DIR/run-NNN, then DIR/study.csv, study.json (one row per run: its values and its results.json) and "
    "study.svg (each result against the first parameter); runs done before with the same spec are kept; with --submit "
    "the runs are jobs of a dem-server",
    "the study file",
    {{"--out", "DIR", "where the runs, the table and the figure go"},
     {"--jobs", "N", "N runs at once (1-64), each with cores/N threads and its lines in its run.log"},
     {"--threads", "N", "OpenMP threads of each run (default: the cores, shared by --jobs)"},
     {"--quiet", nullptr, "no progress bars (still a line as each run starts and ends)"},
     {"--plan", nullptr, "list the runs and check every spec, run nothing"},
     {"--submit", nullptr,
      "run the study on a dem-server (its jobs run there); wait for them and download the table "
      "and the figure into DIR"},
     {"--detach", nullptr, "with --submit: do not wait"},
     {"--idempotency-key", "K",
      "with --submit: the same key again gives the study first made, not a second one (default: a new key, "
      "printed if the server does not answer)"},
     {"--id", "ID", "follow a study already on the server to its end, then download its table and figure"}},
    0,
    1,
    true,
    "--server, --token, --timeout and --json go with --submit and --id; --json prints the study's JSON at the end "
    "(with --detach: as submitted) and its progress lines on stderr"};

namespace {
const Verb& kVerb = kStudyVerb;

json read_json(const fs::path& path, const std::string& what) {
  std::error_code error;
  if (fs::is_directory(path, error))
    throw std::runtime_error(path.string() + ": the " + what + " is a folder, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open the " + what);
  std::stringstream text;
  text << in.rdbuf();
  json j;
  try {
    j = json::parse(text.str());
  } catch (const json::exception& e) {  // where: "parse error at line 3, column 5: ..."; a number past a double
    throw std::runtime_error(path.string() + ": the " + what +
                             " is not JSON: " + spec::number_out_of_range(text.str(), e.what()));
  }
  // a key given twice would be taken last, silently, where dem validate refuses it
  if (const std::vector<std::string> twice = spec::repeated_keys(text.str()); !twice.empty())
    throw std::runtime_error(path.string() + ": " + twice.front() + ": is given twice in its object (the " + what +
                             "'s reader would keep the last one)");
  return j;
}

void write_text(const fs::path& path, const std::string& text) {
  // into a file beside it, renamed over it once whole: the table written before stays until then
  // (one dem study at a time writes into a folder: FolderLock)
  const fs::path part = path.string() + ".part";
  bool written = false;
  {
    std::ofstream out(part, std::ios::binary);
    out << text;
    out.flush();
    written = static_cast<bool>(out);
  }
  if (!written) {
    std::error_code ignored;
    fs::remove(part, ignored);
    throw std::runtime_error("cannot write " + path.string() + " (a full disk?); the one written before is kept");
  }
  fs::rename(part, path);
}

// The study file, its base spec (read from its file when the study names one) and the folder the
// base's own files (meshes) are found from.
struct StudyInput {
  json study;
  json base;
  std::string base_dir;
  std::vector<fs::path> files;  // the study file and its base spec's file, if it has one
};

StudyInput read_study(const std::string& path) {
  StudyInput in;
  in.study = read_json(path, "study file");
  in.files.emplace_back(path);
  in.base_dir = fs::path(path).parent_path().string();
  if (in.study.is_object() && in.study.contains("base") && in.study["base"].is_string()) {
    const fs::path base = spec::resolve_file(in.study["base"].get<std::string>(), in.base_dir);
    in.base = read_json(base, "base spec");
    in.files.push_back(base);
    in.base_dir = base.parent_path().string();
  }
  return in;
}

// Whether `file`, present, is what a study writes there: a table (study.json with its rows, study.csv
// with its header) or a figure.
bool is_a_table(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string head(16, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  const std::string name = file.filename().string();
  if (name == "study.csv") return head.rfind("run,", 0) == 0;
  if (name == "study.svg") return head.rfind("<svg", 0) == 0;
  in.close();
  const json j = json::parse(std::ifstream(file, std::ios::binary), nullptr, false);
  return j.is_object() && j.contains("rows");
}

// Why DIR may not take the study's files, or "": a table's file would be written over one of the
// study's own files (--out the folder of a study file named study.json, as the bundled cases name
// theirs) or over a file that is not a study's (the user's study.json beside `dem study --id`), or
// an input lies in a run's folder, which the study writes.
std::string overwritten_input(const fs::path& out, const std::vector<fs::path>& inputs) {
  for (const char* name : {"study.json", "study.csv", "study.svg"}) {
    std::error_code error;
    for (const fs::path& file : inputs)
      if (fs::equivalent(out / name, file, error))
        return (out / name).string() + " is " + (file == inputs.front() ? "the study file" : "its base spec") +
               " itself: the study's table would be written over it; give --out another folder";
    if (fs::exists(out / name, error) && !is_a_table(out / name))
      return (out / name).string() + " is there and is not a study's table or figure (a study file?): the " +
             "study would write over it; give --out another folder";
  }
  std::error_code error;
  const fs::path folder = fs::weakly_canonical(out, error);
  for (const fs::path& file : inputs) {
    const fs::path at = fs::weakly_canonical(file, error).parent_path();
    const std::string run = at.filename().string();
    if (at.parent_path() == folder && run.size() > 4 && run.rfind("run-", 0) == 0 &&
        std::all_of(run.begin() + 4, run.end(), [](unsigned char c) { return std::isdigit(c) != 0; }))
      return file.string() + " is in " + at.string() + ", a run's folder, which the study writes: give --out " +
             "another folder, or move the file";
  }
  return "";
}

// One dem study at a time writes into a folder: two would run the same runs into the same run-NNN
// folders and write each other's tables. An flock of DIR/.dem-study.lock, held to the end (the
// kernel lets it go when the process ends, however it ends).
class FolderLock {
 public:
  explicit FolderLock(const fs::path& out) {
    make_output_folder(out);
    const fs::path file = out / ".dem-study.lock";
    fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw std::runtime_error("cannot open " + file.string() + ": " + std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd_);
      throw std::runtime_error("another dem study is writing into " + out.string() + " (it holds " + file.string() +
                               "): wait for it to end, or give another --out");
    }
  }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  ~FolderLock() { ::close(fd_); }

 private:
  int fd_ = -1;
};

void write_table(const fs::path& out, const study::StudyPlan& plan, const std::vector<study::StudyRow>& rows) {
  write_text(out / "study.json", study::table_json(plan, rows).dump(2) + "\n");
  write_text(out / "study.csv", study::table_csv(plan, rows));
  write_text(out / "study.svg", study::figure_svg(plan, rows));
}

std::string row_line(const study::StudyPlan& plan, const study::StudyRow& row) {
  std::string line = study::run_label(plan, row.index, row.values) + ": " + row.state;
  if (!row.error.empty()) line += ": " + row.error;
  for (const std::string& key : study::plot_keys(plan, {row}))
    if (const std::optional<json> value = study::result_at(row, key)) line += "; " + key + " = " + value->dump();
  return line;
}

// Every run's spec checked as `dem validate` checks it, before any runs: a typo in the tenth value
// is found now, not after nine runs. Each run's spec as its folder keeps it: standing alone, the
// files it names (meshes) inline, so that the folder runs again as it is and a changed mesh is a
// changed spec.
// (The scenes are made again to run: a study of many large scenes would not fit in memory at once.)
std::vector<json> check_runs(const study::StudyPlan& plan, const std::string& base_dir) {
  std::vector<std::string> problems;
  std::vector<json> specs;
  for (const study::StudyRun& run : plan.runs) {
    const std::string where = study::run_label(plan, run.index, run.values) + ": ";
    try {
      api::JobSpec spec = spec::parse_json(run.spec.dump());
      (void)spec::to_scene(spec, base_dir);
      if (spec::file_references(spec).empty()) {
        specs.push_back(run.spec);
      } else {
        spec::inline_files(spec, base_dir);
        specs.push_back(json::parse(spec::to_json_text(spec)));
      }
    } catch (const spec::SpecError& e) {
      for (const std::string& p : e.problems()) problems.push_back(where + p);
    } catch (const SceneError& e) {
      problems.push_back(where + e.what());
    }
  }
  if (!problems.empty()) throw study::StudyError(problems);
  return specs;
}

// A spec without its name: a run's name is the study's with its values, which a renamed study or
// a new way of labelling changes without changing what is run.
json without_name(json spec) {
  if (spec.is_object()) spec.erase("name");
  return spec;
}

// The results of a run done before with this very spec (but for its name), or null (none, another
// spec, not completed, or a file that cannot be read: the run is done again).
json done_before(const fs::path& folder, const json& spec) {
  const fs::path results = folder / results::kResultsName, spec_file = folder / "spec.json";
  std::error_code error;
  if (!fs::is_regular_file(results, error) || !fs::is_regular_file(spec_file, error)) return nullptr;
  const json kept_spec = json::parse(std::ifstream(spec_file), nullptr, false);
  const json done = json::parse(std::ifstream(results), nullptr, false);
  if (kept_spec.is_discarded() || done.is_discarded() || without_name(kept_spec) != without_name(spec) ||
      !done.is_object() || done.value("status", json()) != "completed")
    return nullptr;
  return done;
}

// Runs the study's runs here, `jobs` at a time (each with `threads` threads; with several at once,
// each run's own lines go to its folder's run.log), keeping those done before with the same spec.
int run_here(const study::StudyPlan& plan, const StudyInput& in, const fs::path& out, int threads, bool quiet,
             int jobs) {
  const std::vector<json> specs = check_runs(plan, in.base_dir);
  const FolderLock lock(out);  // here, after the checks: a bad study makes no folder
  std::vector<study::StudyRow> rows;
  for (const study::StudyRun& run : plan.runs) rows.push_back(study::row_of(run));
  write_table(out, plan, rows);
  int failed = 0;
  std::mutex shared;  // guards rows, failed, the table's files and the lines printed
  auto run_one = [&](std::size_t k) {
    const study::StudyRun& run = plan.runs[k];
    char name[32];
    std::snprintf(name, sizeof name, "run-%03d", run.index);
    const fs::path folder = out / name;
    // a run done before with this very spec is kept: a study stopped half-way goes on where it stopped
    const fs::path results = folder / results::kResultsName, spec_file = folder / "spec.json";
    if (const json done = done_before(folder, specs[k]); !done.is_null()) {
      const std::lock_guard<std::mutex> lock(shared);
      rows[k].state = "succeeded";
      rows[k].results = done;
      std::printf("%s (done before, kept)\n", printable(row_line(plan, rows[k])).c_str());
      write_table(out, plan, rows);  // a study of kept runs only still ends with their table
      return;
    }
    make_output_folder(folder, "the run's folder");
    fs::remove(results);
    write_text(spec_file, specs[k].dump(2) + "\n");
    const fs::path log_file = folder / "run.log";
    {
      std::string where = folder.string();
      if (jobs > 1) (where += ", its lines in ") += log_file.string();
      const std::lock_guard<std::mutex> lock(shared);
      std::printf("run %d of %zu (%s) into %s\n", run.index, plan.runs.size(),
                  printable(study::describe_values(plan.parameters, run.values)).c_str(), where.c_str());
      std::fflush(stdout);
    }
    std::FILE* log = nullptr;
    if (jobs > 1 && (log = std::fopen(log_file.c_str(), "w")) == nullptr)
      throw std::runtime_error("cannot write " + log_file.string());
    int status = 1;
    std::string error;
    try {
      RunSceneOptions options;
      options.threads = threads;
      options.quiet = quiet || jobs > 1;
      options.log = log;
      status = run_scene(spec::to_scene(spec::parse_json(specs[k].dump()), in.base_dir), spec_file.string(),
                         folder.string(), options);
    } catch (const std::exception& e) {
      error = e.what();
      if (log != nullptr) std::fprintf(log, "dem study: %s\n", printable(e.what()).c_str());
    }
    if (log != nullptr) std::fclose(log);
    json found;
    if (fs::exists(results)) found = json::parse(std::ifstream(results), nullptr, false);
    const std::lock_guard<std::mutex> lock(shared);
    study::StudyRow& row = rows[k];
    row.error = error;
    row.results = found.is_discarded() ? json() : found;
    row.state = status == 0 ? "succeeded" : "failed";
    if (status != 0 && row.error.empty() && row.results.is_object()) row.error = row.results.value("error", "");
    failed += status != 0;
    std::printf("%s\n", printable(row_line(plan, row)).c_str());
    std::fflush(stdout);
    write_table(out, plan, rows);
  };
  if (jobs <= 1) {
    for (std::size_t k = 0; k < plan.runs.size(); ++k) run_one(k);
  } else {
    // each worker takes the next run not yet begun; the first error that is not a run's own (a
    // folder or table that cannot be written) stops the workers and is thrown once they have ended
    std::atomic<std::size_t> next{0};
    std::atomic<bool> stop{false};
    std::exception_ptr first_error;
    std::vector<std::thread> workers;
    for (int w = 0; w < std::min<int>(jobs, static_cast<int>(plan.runs.size())); ++w)
      workers.emplace_back([&] {
        for (std::size_t k; !stop && (k = next++) < plan.runs.size();) {
          try {
            run_one(k);
          } catch (...) {
            const std::lock_guard<std::mutex> lock(shared);
            if (!first_error) first_error = std::current_exception();
            stop = true;
          }
        }
      });
    for (std::thread& w : workers) w.join();
    if (first_error) std::rethrow_exception(first_error);
  }
  for (const std::string& key : plan.plot) {
    const bool any = std::any_of(rows.begin(), rows.end(),
                                 [&](const study::StudyRow& row) { return study::number_at(row, key).has_value(); });
    if (!any)
      std::printf("plot: no run has a number \"%s\" (results.json's dotted names: see study.csv's columns)\n",
                  printable(key).c_str());
  }
  std::printf("study \"%s\": %zu runs, %d failed; table %s, figure %s\n", printable(plan.name).c_str(),
              plan.runs.size(), failed, (out / "study.csv").c_str(), (out / "study.svg").c_str());
  return failed == 0 ? 0 : 1;
}

// Follows a server's study until every job has ended, then downloads its table and figure (the
// caller holds DIR's FolderLock from before the study is made or followed).
int follow(const ServerApi& api, std::int64_t id, const fs::path& out, bool as_json) {
  std::FILE* lines = as_json ? stderr : stdout;  // --json: stdout has the study's JSON only
  const std::string target = "/api/v1/studies/" + std::to_string(id);
  std::string last;
  json study;
  for (;;) {
    study = api.call("GET", target);
    const std::string line = "study " + std::to_string(id) + ": " + study.value("summary", std::string());
    if (line != last) {
      std::fprintf(lines, "%s\n", line.c_str());
      std::fflush(lines);
      last = line;
    }
    if (study.value("finished", false)) break;
    std::this_thread::sleep_for(std::chrono::seconds(1));
  }
  make_output_folder(out);
  write_text(out / "study.json", api.send("GET", target + "/results.json").body);
  write_text(out / "study.csv", api.send("GET", target + "/results.csv").body);
  write_text(out / "study.svg", api.send("GET", target + "/figure.svg").body);
  int failed = 0;
  for (const json& job : study.value("jobs", json::array())) failed += job.value("state", "") != "succeeded";
  std::fprintf(lines, "study %lld: table %s, figure %s\n", static_cast<long long>(id), (out / "study.csv").c_str(),
               (out / "study.svg").c_str());
  if (as_json) print_json_line(study);
  return failed == 0 ? 0 : 1;
}

// A key no other submission has: 128 random bits.
std::string new_idempotency_key() {
  std::random_device random;
  char key[48];
  std::snprintf(key, sizeof key, "dem-study-%08x%08x%08x%08x", random(), random(), random(), random());
  return key;
}

// The study as the server takes it: its base inline, and the base's files (meshes) inline in it.
json for_server(const StudyInput& in) {
  json study = in.study;
  study["base"] = json::parse(spec::to_json_text([&] {
    api::JobSpec base = spec::parse_json((in.base.is_object() ? in.base : in.study["base"]).dump());
    spec::inline_files(base, in.base_dir);
    return base;
  }()));
  return study;
}

}  // namespace

int study_command(const std::vector<std::string>& args) {
  VerbArgs a;
  if (const auto exit = parse_verb_args(kVerb, args, a)) return *exit;
  const std::string out = a.value("--out");
  const bool plan_only = a.flag("--plan");
  // an option of the other mode is refused, not ignored (a forgotten --submit ran a study here)
  auto given = [&](std::initializer_list<const char*> options) -> std::string {
    for (const char* o : options)
      if (a.has(o) || a.flag(o)) return o;
    return "";
  };
  if (a.has("--id")) {
    if (const std::string o =
            given({"--jobs", "--threads", "--plan", "--quiet", "--detach", "--submit", "--idempotency-key"});
        !o.empty())
      return usage_error(kVerb, o + " does not go with --id (which follows a study on the server)");
    const std::optional<std::int64_t> id = job_id(a.value("--id"));
    if (!id) return usage_error(kVerb, "a study id is a whole number (got \"" + a.value("--id") + "\")");
    if (!a.positional.empty()) return usage_error(kVerb, "--id follows a study on the server: give no study file");
    if (out.empty()) return usage_error(kVerb, "--out DIR: where the table and the figure go");
    if (const std::string why = overwritten_input(out, {}); !why.empty()) return usage_error(kVerb, "--out " + why);
    return with_server(kVerb, a, [&](const ServerApi& api) {
      const FolderLock lock(out);
      return follow(api, *id, out, a.json);
    });
  }
  if (a.positional.empty()) return usage_error(kVerb, "missing the study file");
  if (!a.flag("--submit")) {
    if (a.flag("--detach")) return usage_error(kVerb, "--detach goes with --submit (a study on the server)");
    if (a.json) return usage_error(kVerb, "--json goes with --submit or --id (a study on the server)");
    if (const std::string o = given({"--server", "--token", "--timeout", "--idempotency-key"}); !o.empty())
      return usage_error(kVerb, o + " goes with --submit or --id (this study runs here: add --submit to run it on "
                                    "the server)");
  }
  if (out.empty() && !plan_only && !a.flag("--detach"))
    return usage_error(kVerb, "--out DIR: where the runs, the table and the figure go");
  int threads = -1;
  if (a.has("--threads")) {
    try {
      std::size_t used = 0;
      threads = std::stoi(a.value("--threads"), &used);
      if (used != a.value("--threads").size()) threads = -1;
    } catch (const std::exception&) {
      threads = -1;
    }
    if (threads < 0)
      return usage_error(kVerb, "--threads is a whole number >= 0 (got \"" + a.value("--threads") + "\")");
  }
  int jobs = 1;
  if (a.has("--jobs")) {
    const std::string& text = a.value("--jobs");
    const bool digits = !text.empty() && text.size() <= 2 &&
                        std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
    jobs = digits ? std::stoi(text) : 0;
    if (jobs < 1 || jobs > 64)
      return usage_error(kVerb, "--jobs is a whole number from 1 to 64 (got \"" + text + "\")");
    // several runs at once share the cores, unless --threads says otherwise
    if (threads < 0 && jobs > 1) threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()) / jobs);
  }
  const std::string& path = a.positional[0];
  try {
    const StudyInput in = read_study(path);
    if (!out.empty() && !plan_only && !a.flag("--detach"))  // those write nothing into DIR
      if (const std::string why = overwritten_input(out, in.files); !why.empty())
        return usage_error(kVerb, "--out " + why);
    const study::StudyPlan plan = study::plan_study(in.study, in.base);
    if (plan_only) {
      check_runs(plan, in.base_dir);
      std::printf("study \"%s\": %zu runs (%s), every spec valid\n", printable(plan.name).c_str(), plan.runs.size(),
                  plan.grid ? "grid" : "zip");
      for (const study::StudyRun& run : plan.runs)
        std::printf("run %d: %s\n", run.index, printable(study::describe_values(plan.parameters, run.values)).c_str());
      return 0;
    }
    if (!a.flag("--submit")) return run_here(plan, in, out, threads, a.flag("--quiet"), jobs);
    const json study = for_server(in);
    // A study of many runs takes the server a while to check (each run's scene is built): a client
    // that stops waiting must be able to ask again for the study the server goes on to make, not
    // make a second one. So every submission has a key, the user's or a new one.
    const std::string key = a.has("--idempotency-key") ? a.value("--idempotency-key") : new_idempotency_key();
    return with_server(kVerb, a, [&](const ServerApi& api) {
      // DIR is this command's from before the study is made: another dem study writing into it
      // while this one waits would mix its runs with this study's table
      std::optional<FolderLock> lock;
      if (!a.flag("--detach")) lock.emplace(out);
      client::Response response;
      try {
        response = api.send("POST", "/api/v1/studies", study.dump(), "application/json", {{"Idempotency-Key", key}});
      } catch (const client::ClientError& e) {
        const std::string what = e.what();
        if (what.find("did not answer in time") == std::string::npos) throw;  // not sent: nothing to get back
        throw std::runtime_error(what +
                                 "; the server may still make the study: the same command with "
                                 "--idempotency-key " +
                                 key + " gives that study, not a second one");
      }
      const json created = api.json_of(response, "/api/v1/studies");
      const std::int64_t id = created.value("id", std::int64_t{-1});
      std::fprintf(a.json ? stderr : stdout, "%s study %lld: %zu jobs\n",
                   response.header("idempotent-replayed") == "true"
                       ? ("already submitted with idempotency key " + key + ":").c_str()
                       : "submitted",
                   static_cast<long long>(id), created.value("jobs", json::array()).size());
      std::fflush(stdout);
      if (a.flag("--detach")) {
        if (a.json) print_json_line(created);
        return 0;
      }
      return follow(api, id, out, a.json);
    });
  } catch (const study::StudyError& e) {
    std::fprintf(stderr, "%s: invalid study:\n", path.c_str());
    print_problems(e.problems());
  } catch (const spec::SpecError& e) {
    std::fprintf(stderr, "%s: invalid base spec:\n", path.c_str());
    print_problems(e.problems());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dem study: %s\n", printable(e.what()).c_str());
  }
  return 1;
}

}  // namespace dem::cli
