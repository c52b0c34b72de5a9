// dem: run a job spec locally, check one, or drive a dem-server.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "dem/version.hpp"

namespace {

const char* kUsage =
    "usage:\n"
    "  dem run SPEC.json --out DIR [--threads N] [--quiet] [--restart FILE]\n"
    "                                   run a job spec, writing the legacy files, their CSV twins, ParaView's\n"
    "                                   files, results.json and restart.dat to DIR;\n"
    "                                   --restart FILE continues from a saved state (e.g. DIR/restart.dat),\n"
    "                                   appending to DIR's files\n"
    "  dem validate SPEC.json                                 check a job spec and report every problem\n"
    "  dem import INPT.inp [MESH ...] [--out SPEC.json] [--unit METRES] [--program pdem-egd|ballastdem]\n"
    "                                   a legacy INPT.inp (PDEM-EGD's: MESH the terrain, then the funnel) as\n"
    "                                   a job spec, with every line's fate; --unit: metres per INPT length\n"
    "                                   unit (default 1; 0.001 for mm)\n"
    "  dem study STUDY.json --out DIR [--jobs N] [--threads N] [--quiet] [--plan]\n"
    "                                   a parameter study: the base spec's runs for each value (or combination\n"
    "                                   of values) of the fields it names, one after another (--jobs N: N at\n"
    "                                   once, each with cores/N threads and its lines in its run.log) into\n"
    "                                   DIR/run-NNN, then DIR/study.csv, study.json (one row per run: its\n"
    "                                   values and its results.json) and study.svg (each result against the\n"
    "                                   first parameter); runs done before with the same spec are kept;\n"
    "                                   --plan lists the runs\n"
    "  dem study STUDY.json --out DIR --submit [--detach]      the same study on a dem-server (its jobs run\n"
    "                                   there); waits for them and downloads the table and figure into DIR\n"
    "  dem study --id ID --out DIR                            follow a study on the server to its end\n"
    "  dem plot FILE --x COLUMN --y COLUMN [--y ...] --out FIGURE.svg [--title T]\n"
    "                                   a figure of a run's columns (Force_Displacement.dat: --x 2 --y 3)\n"
    "  dem plot results.json [MORE.json ...] --rows LIST --x KEY --y KEY [--y ...] --out FIGURE.svg\n"
    "                                   a figure of a list's rows (--rows loadedWalls[0].cycles --x cycle\n"
    "                                   --y settlement); several files: a line each (NAME=FILE names it)\n"
    "  dem chains RUN_DIR --times T[,T...] --out FIGURE.svg [--view x|y|z] [--unit U] [--title T]\n"
    "                                   the force chains at the frames nearest the times T, one panel each\n"
    "  dem deposits RUN_DIR [RUN_DIR ...] --out FIGURE.svg [--time T] [--view x|y|z] [--terrain MESH]\n"
    "               [--contour STEP] [--unit U] [--title T]\n"
    "                                   the runs' particles at their last frames side by side, coloured by\n"
    "                                   piece, over the terrain's contours (NAME=RUN_DIR names a panel)\n"
    "\n"
    "  dem submit SPEC.json [--wait] [--idempotency-key K] [--quiet]\n"
    "                                   send a job spec to dem-server (mesh files go inline) and print the\n"
    "                                   job id (--quiet: only the id); --wait follows the job to its end\n"
    "  dem status ID [--json]                                 one line on a job (--json: the server's JSON)\n"
    "  dem list [--state S[,S]] [--tag T[,T]] [--name N] [--json]\n"
    "                                   the server's jobs (every page), or those in these states, with all\n"
    "                                   these tags, of this name\n"
    "  dem cancel ID                                          stop a queued or running job\n"
    "  dem resume ID                                          continue an interrupted job\n"
    "  dem watch ID                                           show a job's progress until it ends\n"
    "  dem fetch ID [NAME ...] [--out DIR]                    download a job's files to DIR (default: here);\n"
    "                                   no NAME: every file but outputs.tar (which NAME may be)\n"
    "                                   these verbs take --server URL (default: $DEM_SERVER, else\n"
    "                                   http://127.0.0.1:8080) and --token T (default: $DEM_SERVER_TOKEN);\n"
    "                                   exit 0: done (the job succeeded), 1: it failed or the server said no,\n"
    "                                   2: bad arguments\n"
    "\n"
    "  dem help                                               this text (dem VERB --help: the verb's)\n"
    "  dem --version                                          the version (also after any verb)\n";

// The usage of the verbs whose own parsers have no --help: their lines of kUsage.
const char* kRunUsage =
    "usage: dem run SPEC.json --out DIR [--threads N] [--quiet] [--restart FILE]\n"
    "  run a job spec, writing the legacy files, their CSV twins, ParaView's files, results.json and restart.dat\n"
    "  to DIR\n"
    "  --threads N     OpenMP threads (default: all cores)\n"
    "  --quiet         no progress line\n"
    "  --restart FILE  continue from a saved state (e.g. DIR/restart.dat), appending to DIR's files\n"
    "  exit 0: the run ended; 1: the spec or the run failed; 2: bad arguments\n";
const char* kValidateUsage =
    "usage: dem validate SPEC.json\n"
    "  check a job spec and report every problem (each with its field's path); exit 0 valid, 1 not, 2 bad arguments\n";
const char* kImportUsage =
    "usage: dem import INPT.inp [MESH ...] [--out SPEC.json] [--unit METRES] [--program pdem-egd|ballastdem]\n"
    "  a legacy INPT.inp (PDEM-EGD's: MESH the terrain, then the funnel) as a job spec, with every line's fate\n"
    "  --out SPEC.json  where to write it (default: standard output)\n"
    "  --unit METRES    metres per INPT length unit (default 1; 0.001 for mm)\n"
    "  --program P      which program's INPT.inp it is (default: told from its lines)\n";

// Each verb, its command, and the usage main prints for --help when the verb's own parser has none.
struct VerbEntry {
  const char* name;
  int (*command)(const std::vector<std::string>&);
  const char* usage = nullptr;
};
const VerbEntry kVerbs[] = {{"run", dem::cli::run_command, kRunUsage},
                            {"validate", dem::cli::validate_command, kValidateUsage},
                            {"import", dem::cli::import_command, kImportUsage},
                            {"study", dem::cli::study_command},
                            {"plot", dem::cli::plot_command},
                            {"chains", dem::cli::chains_command},
                            {"deposits", dem::cli::deposits_command},
                            {"submit", dem::cli::submit_command},
                            {"status", dem::cli::status_command},
                            {"list", dem::cli::list_command},
                            {"cancel", dem::cli::cancel_command},
                            {"resume", dem::cli::resume_command},
                            {"watch", dem::cli::watch_command},
                            {"fetch", dem::cli::fetch_command}};

bool asks_help(const std::vector<std::string>& args) {
  return std::find(args.begin(), args.end(), "--help") != args.end() ||
         std::find(args.begin(), args.end(), "-h") != args.end();
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "help" || args[0] == "--help" || args[0] == "-h") {
    std::fputs(kUsage, args.empty() ? stderr : stdout);
    return args.empty() ? 2 : 0;
  }
  const std::string verb = args[0];
  const VerbEntry* entry =
      std::find_if(std::begin(kVerbs), std::end(kVerbs), [&](const VerbEntry& v) { return verb == v.name; });
  const bool known = entry != std::end(kVerbs);
  if (verb == "--version" || verb == "version" ||
      (known && std::find(args.begin(), args.end(), "--version") != args.end())) {
    std::printf("dem %s\n", dem::kVersion);
    return 0;
  }
  args.erase(args.begin());
  if (known) {
    if (entry->usage != nullptr && asks_help(args)) {
      std::fputs(entry->usage, stdout);
      return 0;
    }
    return entry->command(args);
  }
  std::fprintf(stderr, "dem: unknown command \"%s\"\n%s", verb.c_str(), kUsage);
  return 2;
}
