#include "import/inpt_import.hpp"

#include <cctype>
#include <cmath>

#include "import/line_fates.hpp"
#include "import/program_imports.hpp"
#include "legacy/inpt_file.hpp"

namespace dem::import {
namespace {

// PDEM-EGD's third line is BOND_MODEL (P or C), BallastDEM's nstep (a number).
Program detect(const std::vector<legacy::InptLine>& lines) {
  if (lines.size() < 3)
    throw legacy::InptError("INPT.inp has " + std::to_string(lines.size()) +
                            " lines: too few for PDEM-EGD's (32) or BallastDEM's (36)");
  const std::string& third = lines[2].values[0];
  if (third.size() == 1 && std::isalpha(static_cast<unsigned char>(third[0]))) return Program::PdemEgd;
  if (std::isdigit(static_cast<unsigned char>(third[0])) || third[0] == '+') return Program::BallastDem;
  throw legacy::InptError("INPT.inp line 3: \"" + third +
                          "\" is neither PDEM-EGD's BOND_MODEL (P or C) nor BallastDEM's nstep (a number)");
}

}  // namespace

std::string program_name(Program p) {
  switch (p) {
    case Program::PdemEgd:
      return "PDEM-EGD";
    case Program::BallastDem:
      return "BallastDEM";
    case Program::Auto:
      break;
  }
  return "either program";
}

std::vector<std::string> locate(const Imported& imported, const std::vector<std::string>& problems) {
  std::vector<std::string> out;
  for (const std::string& problem : problems) {
    int line = 0;
    std::size_t longest = 0;
    for (const auto& [path, number] : imported.fields) {
      // the field itself, or one under it ("interactions[0]" covers "interactions[0].friction")
      if (path.size() <= longest || problem.compare(0, path.size(), path) != 0) continue;
      const char next = problem.size() > path.size() ? problem[path.size()] : ':';
      if (next != ':' && next != '.' && next != '[') continue;
      line = number;
      longest = path.size();
    }
    if (line == 0) {
      out.push_back(problem);
      continue;
    }
    out.push_back("INPT.inp line " + std::to_string(line) + " (" + imported.lines[line - 1].name + "): " + problem);
  }
  return out;
}

Imported import_inpt(std::string_view text, const ImportOptions& options) {
  const std::vector<legacy::InptLine> lines = legacy::read_inpt(text);
  Imported out;
  out.program = options.program == Program::Auto ? detect(lines) : options.program;
  if (!(options.length_unit > 0) || options.length_unit > 1e3)
    throw legacy::InptError("the length unit must be a positive number of metres, at most 1000 (got " +
                            show(options.length_unit) + ")");
  if (out.program == Program::PdemEgd)
    import_pdem_egd(lines, options, out);
  else
    import_ballastdem(lines, options, out);
  // A value made from the lines (k_n from D and E, a count from a box and a mass) may overflow where
  // each line was a number: named, as a spec cannot hold it.
  std::string bad;
  auto find_non_finite = [&](auto& self, const nlohmann::ordered_json& j, const std::string& path) -> void {
    if (!bad.empty()) return;
    if (j.is_number_float() && !std::isfinite(j.get<double>())) bad = path;
    if (j.is_object())
      for (auto it = j.begin(); it != j.end(); ++it)
        self(self, it.value(), path.empty() ? it.key() : path + "." + it.key());
    if (j.is_array())
      for (std::size_t k = 0; k < j.size(); ++k) self(self, j[k], path + "[" + std::to_string(k) + "]");
  };
  find_non_finite(find_non_finite, out.spec, "");
  if (!bad.empty())
    throw legacy::InptError(
        locate(out, {bad + ": is not a finite number: the values it is made from are too large"})[0]);
  // the files in the INPT file's unit, as the legacy programs wrote them
  if (options.length_unit == 1e-3) out.spec["outputs"]["lengthUnit"] = "mm";
  if (options.length_unit == 1e-2) out.spec["outputs"]["lengthUnit"] = "cm";
  return out;
}

}  // namespace dem::import
