// dem import INPT.inp [MESH ...]: a legacy parameter file as a job spec (import/inpt_import.hpp).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "import/inpt_import.hpp"
#include "legacy/inpt_file.hpp"
#include "sim/simulation.hpp"
#include "spec/spec_loader.hpp"

namespace dem::cli {
namespace {

constexpr const char* kImportUsage =
    "usage: dem import INPT.inp [MESH ...] [--out SPEC.json] [--unit METRES] [--program pdem-egd|ballastdem]\n";

struct ImportArgs {
  std::string inpt;
  std::vector<std::string> meshes;
  std::string out;
  import::ImportOptions options;
};

bool parse(const std::vector<std::string>& args, ImportArgs& a) {
  for (std::size_t k = 0; k < args.size(); ++k) {
    const std::string& s = args[k];
    auto value = [&]() -> const std::string* {
      if (k + 1 >= args.size()) {
        std::fprintf(stderr, "dem import: %s needs a value\n%s", s.c_str(), kImportUsage);
        return nullptr;
      }
      return &args[++k];
    };
    if (s == "--out") {
      const std::string* v = value();
      if (!v) return false;
      a.out = *v;
    } else if (s == "--unit") {
      const std::string* v = value();
      if (!v) return false;
      try {
        std::size_t used = 0;
        a.options.length_unit = std::stod(*v, &used);
        if (used != v->size()) throw std::invalid_argument(*v);
      } catch (const std::exception&) {
        std::fprintf(stderr, "dem import: --unit must be a number of metres (got \"%.40s\")\n", v->c_str());
        return false;
      }
    } else if (s == "--program") {
      const std::string* v = value();
      if (!v) return false;
      if (*v == "pdem-egd") {
        a.options.program = import::Program::PdemEgd;
      } else if (*v == "ballastdem") {
        a.options.program = import::Program::BallastDem;
      } else {
        std::fprintf(stderr, "dem import: --program is pdem-egd or ballastdem (got \"%s\")\n", v->c_str());
        return false;
      }
    } else if (s.rfind("--", 0) == 0) {
      std::fprintf(stderr, "dem import: unknown option %s\n%s", s.c_str(), kImportUsage);
      return false;
    } else if (a.inpt.empty()) {
      a.inpt = s;
    } else {
      a.meshes.push_back(s);
    }
  }
  if (a.inpt.empty()) {
    std::fputs(kImportUsage, stderr);
    return false;
  }
  return true;
}

}  // namespace

int import_command(const std::vector<std::string>& args) {
  ImportArgs a;
  if (!parse(args, a)) return 2;
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
    std::fprintf(stderr, "dem import: %s: %s\n", a.inpt.c_str(), e.what());
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
    for (const std::string& p : import::locate(imported, e.problems())) std::fprintf(stderr, "  %s\n", p.c_str());
    return 1;
  } catch (const SceneError& e) {
    std::fprintf(stderr, "dem import: %s: the spec it makes does not validate (nothing written):\n  %s\n",
                 a.inpt.c_str(), e.what());
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
