#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "cli/output_folder.hpp"
#include "cli/progress_bar.hpp"
#include "cli/terminal_text.hpp"
#include "cli/verb_args.hpp"
#include "core/errors.hpp"
#include "output/legacy_output.hpp"
#include "output/run_results.hpp"
#include "output/run_writers.hpp"
#include "results/results_json.hpp"
#include "sim/particle_sources.hpp"
#include "sim/state_io.hpp"
#include "spec/spec_loader.hpp"

namespace dem::cli {
namespace {

// The whole text of --threads as a count in [0, the most a spec may ask for], or -1.
int thread_count(const std::string& text) {
  try {
    std::size_t used = 0;
    const int n = std::stoi(text, &used);
    return used == text.size() && n >= 0 && n <= spec::SpecLimits{}.max_threads ? n : -1;
  } catch (const std::exception&) {
    return -1;
  }
}

// The most memory the process has held resident (VmHWM of /proc/self/status, Linux), or nothing
// where that cannot be read.
std::optional<std::size_t> peak_resident_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) {
      std::istringstream fields(line.substr(6));
      std::size_t kib = 0;
      if (fields >> kib) return kib * 1024;
    }
  return std::nullopt;
}

Scene load(const std::string& path) {
  // mesh files are found next to the spec
  return spec::to_scene(spec::read_json_file(path), std::filesystem::path(path).parent_path().string());
}

}  // namespace

const Verb kRunVerb{"run",
                    "run SPEC.json --out DIR [--threads N] [--quiet] [--profile] [--restart FILE]",
                    "run a job spec, writing the legacy files, their CSV twins, ParaView's files, results.json and "
                    "restart.dat to DIR",
                    "the spec file",
                    {{"--out", "DIR", "where the run's files go (made if missing)"},
                     {"--threads", "N", "OpenMP threads (default: the spec's, else all cores)"},
                     {"--quiet", nullptr, "no progress line"},
                     {"--profile", nullptr,
                      "at the end, where the loop's time went: seconds per phase of the step (pairs, walls, meshes, "
                      "bonds, clumps, neighbour rebuild, sort, guard, outputs...)"},
                     {"--restart", "FILE",
                      "continue from a saved state (e.g. DIR/restart.dat), appending to DIR's "
                      "files"}},
                    1,
                    1,
                    false,
                    "exit status: 0 the run ended, 1 the spec or the run failed, 2 bad arguments"};

const Verb kValidateVerb{"validate",
                         "validate SPEC.json",
                         "check a job spec and report every problem, each with its field's path",
                         "the spec file",
                         {},
                         1,
                         1,
                         false,
                         "exit status: 0 valid, 1 not, 2 bad arguments"};

int validate_command(const std::vector<std::string>& arguments) {
  VerbArgs parsed;
  if (const auto exit = parse_verb_args(kValidateVerb, arguments, parsed)) return *exit;
  const std::vector<std::string>& args = parsed.positional;
  try {
    const Scene scene = load(args[0]);
    Simulation sim(scene);  // also checks what needs the scene assembled (the time step)
    std::printf("%s: valid; %zu particles, %zu walls%s; %s; %lld steps\n", args[0].c_str(), scene.particles.size(),
                scene.walls.size(),
                scene.sources.empty() ? "" : (", " + std::to_string(scene.sources.size()) + " sources").c_str(),
                sim.time_step().describe().c_str(), static_cast<long long>(sim.total_steps()));
    return 0;
  } catch (const spec::SpecError& e) {
    std::fprintf(stderr, "%s: invalid spec:\n", args[0].c_str());
    print_problems(e.problems());
  } catch (const SceneError& e) {
    std::fprintf(stderr, "%s: invalid spec:\n  %s\n", args[0].c_str(), printable(e.what()).c_str());
  }
  return 1;
}

int run_scene(Scene scene, const std::string& label, const std::string& out, const RunSceneOptions& options) {
  std::FILE* info = options.log != nullptr ? options.log : stdout;
  std::FILE* problems = options.log != nullptr ? options.log : stderr;
  if (options.threads >= 0) scene.numerics.threads = options.threads;
  Simulation sim(std::move(scene));
  PhaseProfile profile;
  if (options.profile) sim.set_profile(&profile);
  const bool append = !options.restart.empty();
  if (append) {
    StateIO::read_file(sim, options.restart);
    StateIO::require_within_run(sim);
  }
  const std::int64_t first_step = sim.step_count();  // a continued run starts at its saved step
  make_output_folder(out);
  std::fprintf(info, "%s: %zu particles, %zu walls, %lld steps; %s\n", label.c_str(), sim.particles().size(),
               sim.scene().walls.size(), static_cast<long long>(sim.total_steps()), sim.time_step().describe().c_str());
  std::fflush(info);

  std::vector<std::unique_ptr<Observer>> writers = make_run_writers(sim, out, append);
  writers.push_back(std::make_unique<StateWriter>((std::filesystem::path(out) / "restart.dat").string()));
  auto recorder = std::make_unique<ResultsRecorder>(
      sim, (std::filesystem::path(out) / ResultsRecorder::kTrackName).string(), append);
  std::vector<Observer*> observers;
  for (auto& w : writers) observers.push_back(w.get());
  observers.push_back(recorder.get());

  RunOptions run_options;
  if (!options.quiet) run_options.on_progress = make_progress_printer(isatty(STDERR_FILENO));
  const RunOutcome outcome = run(sim, observers, run_options);
  writers.clear();  // closes the files
  results::write_results_file(recorder->results(), out);
  for (const std::string& note : recorder->results().notes) std::fprintf(problems, "dem run: note: %s\n", note.c_str());
  // the steps this run took, which loop_seconds timed (outcome.steps is the step it ended at)
  const std::int64_t steps_run = outcome.steps - first_step;
  const std::size_t particles = sim.particles().size();
  const double rate =
      static_cast<double>(particles) * static_cast<double>(steps_run) / std::max(outcome.loop_seconds, 1e-9);
  std::string memory;
  if (options.memory) {
    if (const std::optional<std::size_t> peak = peak_resident_bytes()) {
      char text[120];
      std::snprintf(text, sizeof text, " peak_memory_mb=%.1f", static_cast<double>(*peak) / 1e6);
      memory = text;
      if (particles > 0) {  // a run that ended empty (a source's, before its first) has no share
        std::snprintf(text, sizeof text, " bytes_per_particle=%.0f",
                      static_cast<double>(*peak) / static_cast<double>(particles));
        memory += text;
      }
    }
  }
  // A stopped run says how far it went too, and where its time went: when it is most wanted.
  std::FILE* summary = outcome.ok ? info : problems;
  std::fprintf(summary,
               "%s: steps=%lld particles=%zu loop_seconds=%.3f particle_steps_per_second=%.4e neighbor_builds=%d%s\n",
               outcome.ok ? "done" : "stopped", static_cast<long long>(steps_run), particles, outcome.loop_seconds,
               rate, sim.neighbor_builds(), memory.c_str());
  if (options.profile) std::fputs(profile.table().c_str(), summary);
  if (!outcome.ok) {
    std::fprintf(problems, "dem run: %s\n(the files in %s hold every frame written before the stop)\n",
                 outcome.error.c_str(), out.c_str());
    return 1;
  }
  for (std::size_t k = 0; k < sim.scene().sources.size(); ++k) {
    const SourceProgress& progress = sim.source_progress()[k];
    const ParticleSource& source = sim.scene().sources[k];
    const std::optional<bool> reached = total_reached(sim.scene(), source, progress);
    char short_of[160] = "";
    if (reached && !*reached) {
      if (source.total_count >= 0)
        std::snprintf(short_of, sizeof short_of, "; short of its total of %lld particles",
                      static_cast<long long>(source.total_count));
      else
        std::snprintf(short_of, sizeof short_of, "; short of its total of %.6g kg", source.total_mass);
    }
    std::fprintf(info,
                 "source \"%s\": inserted %lld particles, %.6g kg; %lld batches found no room for a particle due%s\n",
                 source.name.c_str(), static_cast<long long>(progress.inserted), progress.mass,
                 static_cast<long long>(progress.crowded_batches), short_of);
  }
  std::fprintf(info, "results: %s\n", (std::filesystem::path(out) / results::kResultsName).c_str());
  return 0;
}

int run_command(const std::vector<std::string>& args) {
  VerbArgs a;
  if (const auto exit = parse_verb_args(kRunVerb, args, a)) return *exit;
  const std::string& spec = a.positional[0];
  if (!a.has("--out")) return usage_error(kRunVerb, "missing --out DIR: where the run's files go");
  int threads = -1;
  if (a.has("--threads") && (threads = thread_count(a.value("--threads"))) < 0)
    return usage_error(kRunVerb, "--threads must be a whole number in [0, " +
                                     std::to_string(spec::SpecLimits{}.max_threads) + "] (got \"" +
                                     a.value("--threads") + "\")");
  try {
    RunSceneOptions options;
    options.threads = threads;
    options.quiet = a.flag("--quiet");
    options.restart = a.value("--restart");
    options.profile = a.flag("--profile");
    options.memory = true;
    return run_scene(load(spec), spec, a.value("--out"), options);
  } catch (const spec::SpecError& e) {
    std::fprintf(stderr, "%s: invalid spec:\n", spec.c_str());
    print_problems(e.problems());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dem run: %s\n", e.what());
  }
  return 1;
}

}  // namespace dem::cli
