// dem-server: the simulation service (REST jobs, live frames, legacy archives). See docs/api.md.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <initializer_list>
#include <string>
#include <tuple>
#include <vector>

#include "dem/version.hpp"
#include "server/http_server.hpp"
#include "server/install_paths.hpp"
#include "server/request_policy.hpp"

namespace {

const char* kUsage =
    "usage: dem-server --data DIR [--port PORT] [--address ADDR] [--token TOKEN] [--jobs N] [OPTIONS]\n"
    "       dem-server --version | --help\n"
    "  the simulation service: REST jobs, live frames to the viewer, every output archived (docs/api.md)\n";

// A decimal number (std::stod alone also takes hexadecimal, "inf" and "nan").
bool number(const std::string& text, double& out) {
  if (text.empty() || text.find_first_not_of("0123456789.eE+-") != std::string::npos) return false;
  try {
    std::size_t used = 0;
    out = std::stod(text, &used);
    return used == text.size();
  } catch (...) {
    return false;
  }
}

// A check of an option's text: a decimal number in [lo, hi] (above lo when `above`), whole when
// `whole`; CLI11 reports what it returns as "--option: must be ...".
CLI::Validator number_in(double lo, double hi, bool whole, bool above, const std::string& what) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double x = 0;
        const bool ok = number(text, x) && (above ? x > lo : x >= lo) && x <= hi &&
                        (!whole || x == static_cast<double>(static_cast<long long>(x)));
        return ok ? "" : "must be " + what + " (got \"" + text + "\")";
      },
      "", "");
}

// dem-server --help begins with kUsage, not CLI11's "Usage:" line.
class HelpWithoutUsageLine : public CLI::Formatter {
 public:
  std::string make_usage(const CLI::App*, std::string) const override { return ""; }
};

// The options, bound to `options` (numbers through doubles, whose text the checks above have read).
struct NumberOptions {
  double port = 8080, jobs = 1, threads_per_job = 0, max_body_mb = 64, max_output_mb = 10000, max_job_memory_mb = 0,
         request_timeout = 10, max_connections = 512, max_connections_per_client = 128, keep_finished_days = 0,
         keep_finished_jobs = 0, max_frame_rate = 30, checkpoint_seconds = 10;
};

void define_options(CLI::App& app, dem::server::ServerOptions& o, NumberOptions& n, std::string& web,
                    std::string& cases) {
  const CLI::Validator not_empty([](std::string& text) { return text.empty() ? std::string("is empty") : ""; }, "", "");
  app.add_option("--data", o.data, "where the job table (jobs.db) and each job's folder live (made if missing)")
      ->required()
      ->check(not_empty)
      ->type_name("DIR");
  app.add_option("--port", n.port, "default 8080; 0 picks a free port (printed)")
      ->check(number_in(0, 65535, true, false, "a port number 0-65535"))
      ->type_name("PORT");
  app.add_option("--address", o.address, "default 127.0.0.1; any other address needs a token")->type_name("ADDR");
  app.add_option("--token", o.token,
                 "every request must carry \"Authorization: Bearer TOKEN\" (or ?access_token=TOKEN); also from "
                 "DEM_SERVER_TOKEN")
      ->type_name("TOKEN");
  app.add_option("--jobs", n.jobs, "jobs running at once (default 1, with all cores)")
      ->check(number_in(1, 64, true, false, "a whole number 1-64"))
      ->type_name("N");
  app.add_option("--threads-per-job", n.threads_per_job,
                 "OpenMP threads of a job (default: the cores shared among running jobs)")
      ->check(number_in(0, 1024, true, false, "a whole number from 0 to 1024"))
      ->type_name("N");
  app.add_option("--max-body-mb", n.max_body_mb, "largest request body (default 64)")
      ->check(number_in(0, 4096, false, true, "a size in MB, > 0 and at most 4096"))
      ->type_name("MB");
  app.add_option("--web", web, "the viewer's files (default: ../share/dem/web beside the executable, else ../web/dist)")
      ->type_name("DIR");
  app.add_option("--cases", cases,
                 "the bundled cases offered to the viewer (default: ../share/dem/cases beside the executable, else "
                 "../cases)")
      ->type_name("DIR");
  app.add_option("--checkpoint-seconds", n.checkpoint_seconds,
                 "a checkpoint of a running job every S seconds (default 10)")
      ->check(number_in(0, 1e9, false, false, "a number of seconds >= 0"))
      ->type_name("S");
  app.add_option("--max-frame-rate", n.max_frame_rate,
                 "live frames a second per job at most (default 30; 0: every output frame)")
      ->check(number_in(0, 1e9, false, false, "a rate in Hz >= 0"))
      ->type_name("HZ");
  app.add_option("--max-output-mb", n.max_output_mb,
                 "what one job's files may hold (default 10000): a spec whose frames alone would pass it is refused, "
                 "a job whose files pass it is stopped")
      ->check(number_in(0, 1e9, false, true, "a size in MB, > 0 and at most 1e9"))
      ->type_name("MB");
  app.add_option("--max-job-memory-mb", n.max_job_memory_mb,
                 "the memory one job may need, estimated from its particle count before any is made (default: half "
                 "the machine's memory); past it a 400")
      ->check(number_in(0, 1e9, false, true, "a size in MB, > 0 and at most 1e9"))
      ->type_name("MB");
  app.add_option("--request-timeout", n.request_timeout,
                 "a request's header must arrive within S seconds (default 10; its body gets 60 s more), else 408 "
                 "and the connection closes")
      ->check(number_in(0, 86400, false, true, "a number of seconds > 0 and at most 86400"))
      ->type_name("S");
  app.add_option("--max-connections", n.max_connections,
                 "connections at once (default 512), WebSockets included; past it 503")
      ->check(number_in(1, 1e6, true, false, "a whole number from 1 to 1e6"))
      ->type_name("N");
  app.add_option("--max-connections-per-client", n.max_connections_per_client, "from one address (default 128)")
      ->check(number_in(1, 1e6, true, false, "a whole number from 1 to 1e6"))
      ->type_name("N");
  app.add_option("--keep-finished-days", n.keep_finished_days,
                 "delete a job that succeeded, failed or was cancelled more than D days ago, with its files "
                 "(fractions allowed; default: keep every job)")
      ->check(number_in(0, 1e6, false, true, "a number of days > 0 and at most 1e6"))
      ->type_name("D");
  app.add_option("--keep-finished-jobs", n.keep_finished_jobs,
                 "keep only the newest N finished jobs, deleting older ones with their files (default: keep every "
                 "job); queued, running and interrupted jobs are never deleted by either")
      ->check(number_in(1, 1e9, true, false, "a whole number from 1 to 1e9"))
      ->type_name("N");
  app.set_version_flag("--version", std::string("dem-server ") + dem::kVersion, "the version");
}

void apply(const NumberOptions& n, dem::server::ServerOptions& o) {
  o.port = static_cast<unsigned short>(n.port);
  o.concurrency = static_cast<int>(n.jobs);
  o.threads_per_job = static_cast<int>(n.threads_per_job);
  o.max_body = static_cast<std::size_t>(n.max_body_mb * 1024 * 1024);
  o.max_output_bytes = n.max_output_mb * 1024 * 1024;
  o.max_job_memory_bytes = n.max_job_memory_mb * 1024 * 1024;
  o.request_timeout = n.request_timeout;
  o.max_connections = static_cast<std::size_t>(n.max_connections);
  o.max_connections_per_client = static_cast<std::size_t>(n.max_connections_per_client);
  o.keep_finished_days = n.keep_finished_days;
  o.keep_finished_jobs = static_cast<std::size_t>(n.keep_finished_jobs);
  o.max_frame_rate = n.max_frame_rate;
  o.checkpoint_seconds = n.checkpoint_seconds;
}

int serve(int argc, char** argv) {
  dem::server::ServerOptions options;
  if (const char* token = std::getenv("DEM_SERVER_TOKEN")) options.token = token;
  NumberOptions numbers;
  std::string web, cases;
  CLI::App app{"", "dem-server"};
  app.formatter(std::make_shared<HelpWithoutUsageLine>());
  define_options(app, options, numbers, web, cases);
  app.footer("Queued, running and interrupted jobs are never deleted by --keep-finished-days or --keep-finished-jobs.");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(kUsage, stdout);
    std::fputs(app.help("", CLI::AppFormatMode::Normal).c_str(), stdout);
    return 0;
  } catch (const CLI::CallForVersion& e) {
    std::printf("%s\n", e.what());
    return 0;
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "dem-server: %s\n%s(dem-server --help: every option)\n", e.what(), kUsage);
    return 2;
  }
  apply(numbers, options);
  options.web = web.empty() ? dem::server::default_web_dir() : std::filesystem::path(web);
  options.cases = cases.empty() ? dem::server::default_cases_dir() : std::filesystem::path(cases);
  // a folder given that is not one is refused; one not found by default is said, with where it was looked for
  const std::tuple<const char*, const std::filesystem::path&, bool, const char*, const char*> folders[] = {
      {"--web", options.web, !web.empty(), "the viewer (built by scripts/build) is not at", "/ shows a short page"},
      {"--cases", options.cases, !cases.empty(), "the bundled cases are not at", "/api/v1/cases is empty"}};
  for (const auto& [option, folder, given, what, so] : folders) {
    std::error_code error;
    if (std::filesystem::is_directory(folder, error)) continue;
    if (given) {
      std::fprintf(stderr, "dem-server: %s: %s is not a folder\n", option, folder.c_str());
      return 2;
    }
    std::fprintf(stderr, "dem-server: %s %s: %s (give %s DIR)\n", what, folder.c_str(), so, option);
  }
  // the viewer's page keeps the token in a cookie, where it must go unquoted
  if (!options.token.empty() && !dem::server::is_cookie_safe(options.token)) {
    std::fprintf(stderr,
                 "dem-server: the token must be printable ASCII without blanks, quotes, commas, semicolons or "
                 "backslashes\n");
    return 2;
  }
  return dem::server::run_server(options);
}

}  // namespace

// What the command line, the folders' checks or the server throw is told, never an abort.
int main(int argc, char** argv) {
  try {
    return serve(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dem-server: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "dem-server: an unknown error\n");
  }
  return 1;
}
