// `dem import`: a legacy INPT.inp (PDEM-EGD's or BallastDEM's, docs/formats.md section 2) and its
// mesh files turned into an equivalent job spec (JSON), with the fate of every INPT line: the spec
// field it became, or why it was dropped (docs/spec.md, "Legacy INPT.inp parameters").
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace dem::import {

enum class Program { Auto, PdemEgd, BallastDem };

struct ImportOptions {
  Program program = Program::Auto;  // Auto: told apart by the third line (BOND_MODEL or nstep)
  // PDEM-EGD's meshes in order: the terrain, then the funnel that holds the key block until its
  // release (either may be left out). As the spec is to name them: relative to its folder.
  std::vector<std::string> meshes;
  double length_unit = 1;  // metres per length unit of the INPT file and its meshes (0.001: mm)
};

// One INPT line and what became of it.
struct LineFate {
  int number = 0;
  std::string name;  // the manual's name for the line ("nstep", "NFILL, NGROWTH")
  std::string text;  // its values as written
  std::string fate;  // "time.steps = 200000", or "dropped: ..."
};

struct Imported {
  Program program = Program::Auto;
  nlohmann::ordered_json spec;
  std::vector<LineFate> lines;
  std::vector<std::pair<std::string, int>> fields;  // spec field path -> the INPT line it came from
};

// Throws legacy::InptError naming the line for a file that is not one of the two programs' INPT.inp
// (too few or too many lines, a value that is not what its line holds).
Imported import_inpt(std::string_view text, const ImportOptions& options);

std::string program_name(Program p);

// The spec loader's problems with the imported spec ("materials[0].density: must be ..."), each led by
// the INPT line its field came from ("INPT.inp line 15 (dens): materials[0].density: ...") where known.
std::vector<std::string> locate(const Imported& imported, const std::vector<std::string>& problems);

}  // namespace dem::import
