// dem-server: the simulation service (REST jobs, live frames, legacy archives). See docs/api.md.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "dem/version.hpp"
#include "server/http_server.hpp"
#include "server/request_policy.hpp"

namespace {

const char* kUsage =
    "usage: dem-server --data DIR [--port PORT] [--address ADDR] [--token TOKEN] [--jobs N]\n"
    "                  [--threads-per-job N] [--max-body-mb MB] [--web DIR] [--checkpoint-seconds S]\n"
    "                  [--max-frame-rate HZ] [--max-output-mb MB] [--max-job-memory-mb MB] [--cases DIR]\n"
    "                  [--request-timeout S]\n"
    "                  [--max-connections N] [--max-connections-per-client N]\n"
    "                  [--keep-finished-days D] [--keep-finished-jobs N]\n"
    "       dem-server --version | --help\n"
    "  --data DIR              where the job table (jobs.db) and each job's folder live (made if missing)\n"
    "  --port PORT             default 8080; 0 picks a free port (printed)\n"
    "  --address ADDR          default 127.0.0.1; any other address needs a token\n"
    "  --token TOKEN           every request must carry \"Authorization: Bearer TOKEN\" (or\n"
    "                          ?access_token=TOKEN); also from DEM_SERVER_TOKEN\n"
    "  --jobs N                jobs running at once (default 1, with all cores)\n"
    "  --threads-per-job N     OpenMP threads of a job (default: the cores shared among running jobs)\n"
    "  --max-body-mb MB        largest request body (default 64)\n"
    "  --web DIR               the viewer's files (default: web/dist of the source tree)\n"
    "  --cases DIR             the bundled cases offered to the viewer (default: cases/ of the source tree)\n"
    "  --checkpoint-seconds S  a checkpoint of a running job every S seconds (default 10)\n"
    "  --max-frame-rate HZ     live frames a second per job at most (default 30; 0: every output frame)\n"
    "  --max-output-mb MB      what one job's files may hold (default 10000): a spec whose frames alone\n"
    "                          would pass it is refused, a job whose files pass it is stopped\n"
    "  --max-job-memory-mb MB  the memory one job may need, estimated from its particle count before\n"
    "                          any is made (default: half the machine's memory); past it a 400\n"
    "  --request-timeout S     a request's header must arrive within S seconds (default 10; its body\n"
    "                          gets 60 s more), else 408 and the connection closes\n"
    "  --max-connections N     connections at once (default 512), WebSockets included; past it 503\n"
    "  --max-connections-per-client N   from one address (default 128)\n"
    "  --keep-finished-days D  delete a job that succeeded, failed or was cancelled more than D days\n"
    "                          ago, with its files (fractions allowed; default: keep every job)\n"
    "  --keep-finished-jobs N  keep only the newest N finished jobs, deleting older ones with their\n"
    "                          files (default: keep every job); queued, running and interrupted jobs\n"
    "                          are never deleted by either\n";

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

}  // namespace

int main(int argc, char** argv) {
  dem::server::ServerOptions options;
  options.web = DEM_WEB_DIR;
  options.cases = DEM_CASES_DIR;
  if (const char* token = std::getenv("DEM_SERVER_TOKEN")) options.token = token;
  std::vector<std::string> args(argv + 1, argv + argc);
  for (std::size_t k = 0; k < args.size(); ++k) {
    const std::string& a = args[k];
    if (a == "-h" || a == "--help") {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (a == "--version") {
      std::printf("dem-server %s\n", dem::kVersion);
      return 0;
    }
    if (k + 1 >= args.size()) {
      std::fprintf(stderr, "dem-server: %s\n%s",
                   a.rfind("--", 0) == 0 ? (a + " needs a value").c_str() : ("unexpected " + a).c_str(), kUsage);
      return 2;
    }
    const std::string& v = args[++k];
    double x = 0;
    auto whole = [&](double lo, double hi) {
      return number(v, x) && x == static_cast<long long>(x) && x >= lo && x <= hi;
    };
    auto bad = [&](const char* what) {
      std::fprintf(stderr, "dem-server: %s must be %s (got \"%s\")\n", a.c_str(), what, v.c_str());
      return 2;
    };
    if (a == "--data")
      options.data = v;
    else if (a == "--address")
      options.address = v;
    else if (a == "--token")
      options.token = v;
    else if (a == "--web")
      options.web = v;
    else if (a == "--cases")
      options.cases = v;
    else if (a == "--port") {
      if (!whole(0, 65535)) return bad("a port number 0-65535");
      options.port = static_cast<unsigned short>(x);
    } else if (a == "--jobs") {
      if (!whole(1, 64)) return bad("a whole number 1-64");
      options.concurrency = static_cast<int>(x);
    } else if (a == "--threads-per-job") {
      if (!whole(0, 1024)) return bad("a whole number from 0 to 1024");
      options.threads_per_job = static_cast<int>(x);
    } else if (a == "--max-body-mb") {
      if (!number(v, x) || !(x > 0) || x > 4096) return bad("a size in MB, > 0 and at most 4096");
      options.max_body = static_cast<std::size_t>(x * 1024 * 1024);
    } else if (a == "--max-output-mb") {
      if (!number(v, x) || !(x > 0) || x > 1e9) return bad("a size in MB, > 0 and at most 1e9");
      options.max_output_bytes = x * 1024 * 1024;
    } else if (a == "--max-job-memory-mb") {
      if (!number(v, x) || !(x > 0) || x > 1e9) return bad("a size in MB, > 0 and at most 1e9");
      options.max_job_memory_bytes = x * 1024 * 1024;
    } else if (a == "--request-timeout") {
      if (!number(v, x) || !(x > 0) || x > 86400) return bad("a number of seconds > 0 and at most 86400");
      options.request_timeout = x;
    } else if (a == "--max-connections") {
      if (!whole(1, 1e6)) return bad("a whole number from 1 to 1e6");
      options.max_connections = static_cast<std::size_t>(x);
    } else if (a == "--max-connections-per-client") {
      if (!whole(1, 1e6)) return bad("a whole number from 1 to 1e6");
      options.max_connections_per_client = static_cast<std::size_t>(x);
    } else if (a == "--keep-finished-days") {
      if (!number(v, x) || !(x > 0) || x > 1e6) return bad("a number of days > 0 and at most 1e6");
      options.keep_finished_days = x;
    } else if (a == "--keep-finished-jobs") {
      if (!whole(1, 1e9)) return bad("a whole number from 1 to 1e9");
      options.keep_finished_jobs = static_cast<std::size_t>(x);
    } else if (a == "--max-frame-rate") {
      if (!number(v, x) || !(x >= 0)) return bad("a rate in Hz >= 0");
      options.max_frame_rate = x;
    } else if (a == "--checkpoint-seconds") {
      if (!number(v, x) || !(x >= 0)) return bad("a number of seconds >= 0");
      options.checkpoint_seconds = x;
    } else {
      std::fprintf(stderr, "dem-server: unknown option %s\n%s", a.c_str(), kUsage);
      return 2;
    }
  }
  if (options.data.empty()) {
    std::fprintf(stderr, "dem-server: --data DIR is required\n%s", kUsage);
    return 2;
  }
  // the viewer's page keeps the token in a cookie, where it must go unquoted
  if (!options.token.empty() && !dem::server::is_cookie_safe(options.token)) {
    std::fprintf(stderr,
                 "dem-server: the token must be printable ASCII without blanks, quotes, commas, semicolons or "
                 "backslashes\n");
    return 2;
  }
  try {
    return dem::server::run_server(options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dem-server: %s\n", e.what());
    return 1;
  }
}
