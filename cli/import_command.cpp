// dem import INPT.inp [MESH ...]: a legacy parameter file as a job spec (import/inpt_import.hpp).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/terminal_text.hpp"
#include "cli/verb_args.hpp"
#include "import/inpt_import.hpp"
#include "legacy/inpt_file.hpp"
#include "sim/simulation.hpp"
#include "spec/spec_loader.hpp"

namespace dem::cli {
namespace {

struct ImportArgs {
  std::string inpt;
  std::vector<std::string> meshes;
  std::string out;
  import::ImportOptions options;
};

}  // namespace

const Verb kImportVerb{
    "import",
    "import INPT.inp [MESH ...] [--out SPEC.json] [--unit METRES] [--program pdem-egd|ballastdem]",
    "a legacy INPT.inp as a job spec, with every line's fate (PDEM-EGD's: MESH the terrain, then the funnel)",
    "the INPT.inp file",
    {{"--out", "SPEC.json", "where the spec goes (default: standard output)"},
     {"--unit", "METRES", "metres per INPT length unit (default 1; 0.001 for mm)"},
     {"--program", "pdem-egd|ballastdem", "which program's INPT.inp it is (default: told from its lines)"}},
    1,
    SIZE_MAX,
    false,
    "exit status: 0 written, 1 the file cannot be read or its spec does not validate (nothing written), 2 bad "
    "arguments"};

int import_command(const std::vector<std::string>& args) {
  VerbArgs parsed;
  if (const auto exit = parse_verb_args(kImportVerb, args, parsed)) return *exit;
  ImportArgs a;
  a.inpt = parsed.positional[0];
  a.meshes.assign(parsed.positional.begin() + 1, parsed.positional.end());
  a.out = parsed.value("--out");
  if (parsed.has("--unit")) {
    const std::string v = parsed.value("--unit");
    try {
      std::size_t used = 0;
      a.options.length_unit = std::stod(v, &used);
      if (used != v.size()) throw std::invalid_argument(v);
    } catch (const std::exception&) {
      return usage_error(kImportVerb, "--unit must be a number of metres (got \"" + v.substr(0, 40) + "\")");
    }
  }
  if (parsed.has("--program")) {
    const std::string v = parsed.value("--program");
    if (v == "pdem-egd")
      a.options.program = import::Program::PdemEgd;
    else if (v == "ballastdem")
      a.options.program = import::Program::BallastDem;
    else
      return usage_error(kImportVerb, "--program is pdem-egd or ballastdem (got \"" + v + "\")");
  }
  namespace fs = std::filesystem;
  std::ifstream file(a.inpt, std::ios::binary);
  if (!file) {
    std::fprintf(stderr, "dem import: cannot open %s\n", a.inpt.c_str());
    return 1;
  }
  std::stringstream text;
  text << file.rdbuf();
  // the spec names its meshes relative to its own folder
  const fs::path spec_dir = a.out.empty() ? fs::current_path() : fs::absolute(a.out).parent_path();
  for (const std::string& m : a.meshes) {
    if (!fs::is_regular_file(m)) {
      std::fprintf(stderr, "dem import: cannot find the mesh file %s\n", m.c_str());
      return 1;
    }
    a.options.meshes.push_back(fs::absolute(m).lexically_relative(spec_dir).generic_string());
  }
  import::Imported imported;
  try {
    imported = import::import_inpt(text.str(), a.options);
  } catch (const legacy::InptError& e) {
    std::fprintf(stderr, "dem import: %s: %s\n", a.inpt.c_str(), printable(e.what()).c_str());
    return 1;
  }
  const std::string json = imported.spec.dump(2) + "\n";
  FILE* notes = a.out.empty() ? stderr : stdout;
  std::fprintf(notes, "%s: %s's INPT.inp, line by line:\n", a.inpt.c_str(),
               import::program_name(imported.program).c_str());
  for (const import::LineFate& line : imported.lines)
    std::fprintf(notes, "  %2d  %-28s %-22s -> %s\n", line.number, line.name.c_str(), line.text.c_str(),
                 line.fate.c_str());
  // The spec must stand on its own, checked as `dem validate` would, before it is written: a problem
  // is named by the INPT line its field came from.
  std::string summary;
  try {
    const Scene scene = spec::to_scene(spec::parse_json(json), spec_dir.string());
    Simulation sim(scene);
    char buf[600];
    std::snprintf(buf, sizeof buf, "%s: valid; %zu particles, %zu walls; %s; %lld steps\n",
                  a.out.empty() ? "the spec" : a.out.c_str(), sim.particles().size(), scene.walls.size(),
                  sim.time_step().describe().c_str(), static_cast<long long>(sim.total_steps()));
    summary = buf;
  } catch (const spec::SpecError& e) {
    std::fprintf(stderr, "dem import: %s: the spec it makes does not validate (nothing written):\n", a.inpt.c_str());
    print_problems(import::locate(imported, e.problems()));
    return 1;
  } catch (const SceneError& e) {
    std::fprintf(stderr, "dem import: %s: the spec it makes does not validate (nothing written):\n  %s\n",
                 a.inpt.c_str(), printable(e.what()).c_str());
    return 1;
  }
  if (a.out.empty()) {
    std::fputs(json.c_str(), stdout);
  } else {
    std::ofstream out(a.out, std::ios::binary);
    out << json;
    out.flush();
    if (!out) {
      std::fprintf(stderr, "dem import: cannot write %s\n", a.out.c_str());
      return 1;
    }
  }
  std::fputs(summary.c_str(), notes);
  return 0;
}

}  // namespace dem::cli
