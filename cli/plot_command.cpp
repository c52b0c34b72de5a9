// dem plot: a figure (SVG) of a run's columns (Force_Displacement.dat, Energy.dat, ...) or of the
// rows of a list in a JSON file (a results.json's load cycles), one panel per y.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/verb_args.hpp"
#include "study/study_plan.hpp"
#include "study/svg_chart.hpp"

namespace dem::cli {
namespace {

using json = nlohmann::json;

// An axis given as "3:force (N)" or "travel:travel (m)": the column or key before the first colon,
// and the label after it (none: `unlabelled` and the column or key, "column 3" or "travel").
struct Axis {
  std::string name, label;
};

Axis axis_of(const std::string& text, const std::string& unlabelled) {
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos) return {text, unlabelled + text};
  return {text.substr(0, colon), text.substr(colon + 1)};
}

// The rows of numbers of a text file: every line whose words are all numbers, with at least `need` of them.
// A file to read: a regular file (not a folder, nor /dev/zero), opened.
std::ifstream open_file(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw std::runtime_error(path + ": a folder, not a file");
  if (std::filesystem::exists(path, error) && !std::filesystem::is_regular_file(path, error))
    throw std::runtime_error(path + ": not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open it");
  return in;
}

// The next line of `in`, at most 1 MB (a file of one endless line is refused, not read whole).
bool next_line(std::istream& in, std::string& line, const std::string& path) {
  line.clear();
  for (int c; (c = in.get()) != EOF;) {
    if (c == '\n') return true;
    if (line.size() >= (1U << 20)) throw std::runtime_error(path + ": a line longer than 1 MB");
    line.push_back(static_cast<char>(c));
  }
  return !line.empty();
}

std::vector<std::vector<double>> numeric_rows(const std::string& path, std::size_t need) {
  std::ifstream in = open_file(path);
  std::vector<std::vector<double>> rows;
  std::string line;
  while (next_line(in, line, path)) {
    std::istringstream words(line);
    std::vector<double> row;
    std::string word;
    bool numbers = true;
    while (words >> word) {
      char* end = nullptr;
      const double v = std::strtod(word.c_str(), &end);
      if (end == word.c_str() || *end != '\0') {
        numbers = false;
        break;
      }
      row.push_back(v);
    }
    if (numbers && row.size() >= need) rows.push_back(std::move(row));
  }
  return rows;
}

// One JSON file of an overlay: "NAME=PATH" names its line NAME (a NAME has no '/'); else its folder does.
struct NamedFile {
  std::string name, path;
  bool given = false;  // NAME=PATH, not the folder's name
};

NamedFile named_file(const std::string& text) {
  const std::size_t eq = text.find('=');
  if (eq != std::string::npos && eq > 0 && text.find('/') > eq) return {text.substr(0, eq), text.substr(eq + 1), true};
  const std::filesystem::path folder = std::filesystem::path(text).parent_path();
  return {folder.empty() ? text : folder.filename().string(), text, false};
}

// The series of `ky` against `kx` over the rows at `rows_path` of the JSON file `file`.
study::Series json_rows_series(const std::string& file, const std::string& rows_path, const std::string& kx,
                               const std::string& ky) {
  std::ifstream in = open_file(file);
  const json doc = json::parse(in, nullptr, false);
  if (doc.is_discarded()) throw std::runtime_error(file + ": not JSON");
  const json::json_pointer pointer(study::to_pointer(rows_path));
  bool list = false;
  try {
    list = doc.contains(pointer) && doc.at(pointer).is_array();
  } catch (const json::exception&) {  // an index past what a number holds
  }
  if (!list) throw std::runtime_error(file + ": " + rows_path + " is not a list in it");
  study::Series series{{}, true, true, ""};
  for (const json& row : doc.at(pointer)) {
    if (!row.is_object() || !row.contains(kx) || !row.contains(ky) || !row[kx].is_number() || !row[ky].is_number())
      throw std::runtime_error(file + ": a row of " + rows_path + " has no number " +
                               (row.is_object() && row.contains(kx) && row[kx].is_number() ? ky : kx));
    series.points.emplace_back(row[kx].get<double>(), row[ky].get<double>());
  }
  if (series.points.empty()) std::fprintf(stderr, "dem plot: %s: %s is empty\n", file.c_str(), rows_path.c_str());
  return series;
}

}  // namespace

const Verb kPlotVerb{
    "plot",
    "plot FILE --x COLUMN --y COLUMN [--y COLUMN ...] --out FIGURE.svg [--title T]\n"
    "       dem plot FILE.json [FILE.json ...] --rows LIST --x KEY --y KEY [--y KEY ...] --out FIGURE.svg [--title T]",
    "a figure of a run's columns (Force_Displacement.dat: --x 2 --y 3), or of a list's rows in JSON files "
    "(--rows loadedWalls[0].cycles --x cycle --y settlement)",
    "the file to plot",
    {{"--x", "COLUMN", "the x axis: a column 1, 2, ... (or KEY with --rows), or COLUMN:NAME to name the axis"},
     {"--y", "COLUMN", "a y axis, as --x; each --y a line", true},
     {"--out", "FIGURE.svg", "the figure"},
     {"--title", "T", "its title (default: the file's name)"},
     {"--rows", "LIST", "the path of a list of objects in the JSON files (loadedWalls[0].cycles)"}},
    1,
    SIZE_MAX,
    false,
    "FILE: columns of numbers (lines that are not are skipped). With --rows, several files: a line each, named in "
    "the legend by its folder, or NAME=FILE.json (one file given as NAME=FILE.json: its line so named)"};

int plot_command(const std::vector<std::string>& args) {
  VerbArgs a;
  if (const auto exit = parse_verb_args(kPlotVerb, args, a)) return *exit;
  auto usage = [](const std::string& problem) { return usage_error(kPlotVerb, problem); };
  const std::vector<std::string>& files = a.positional;
  const std::vector<std::string> ys = a.all("--y");
  const std::string out = a.value("--out"), rows_path = a.value("--rows"), x = a.value("--x");
  std::string title = a.value("--title");
  if (files.empty()) return usage("missing the file to plot");
  if (files.size() > 1 && rows_path.empty())
    return usage("one file only without --rows (got \"" + files[0] + "\" and \"" + files[1] + "\")");
  const std::string& file = files[0];
  if (x.empty() || ys.empty()) return usage("--x and at least one --y");
  if (out.empty()) return usage("--out FIGURE.svg");
  if (title.empty()) title = std::filesystem::path(file).filename().string();
  try {
    std::vector<study::Panel> panels(ys.size());
    if (!rows_path.empty()) {
      std::vector<NamedFile> named;  // one file without NAME=: no name (no legend)
      for (const std::string& text : files) {
        NamedFile f = named_file(text);
        if (files.size() == 1 && !f.given) f.name.clear();  // one file, not named: no legend
        named.push_back(f);
      }
      std::vector<bool> shared(named.size());  // a folder's name two lines would have: each named by its path
      for (std::size_t a = 0; a < named.size(); ++a)
        for (std::size_t b = 0; b < named.size(); ++b)
          shared[a] = shared[a] || (a != b && named[a].name == named[b].name);
      for (std::size_t a = 0; a < named.size(); ++a)
        if (shared[a] && !named[a].given) named[a].name = named[a].path;
      const Axis ax = axis_of(x, "");
      for (std::size_t k = 0; k < ys.size(); ++k) {
        const Axis ay = axis_of(ys[k], "");
        panels[k] = {ay.label, ax.label, "", {}, {}};
        for (const NamedFile& f : named) {
          panels[k].series.push_back(json_rows_series(f.path, rows_path, ax.name, ay.name));
          panels[k].series.back().name = f.name;
        }
      }
    } else {
      auto column = [&](const std::string& text) {
        std::size_t used = 0;
        int c = 0;
        try {
          c = std::stoi(text, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used != text.size() || c < 1) throw std::invalid_argument("a column is 1, 2, ... (got \"" + text + "\")");
        return static_cast<std::size_t>(c);
      };
      const std::size_t cx = column(axis_of(x, "column ").name);
      std::size_t need = cx;
      std::vector<std::size_t> cy;
      for (const std::string& y : ys) {
        cy.push_back(column(axis_of(y, "column ").name));
        need = std::max(need, cy.back());
      }
      const std::vector<std::vector<double>> rows = numeric_rows(file, need);
      if (rows.empty()) throw std::runtime_error(file + ": no line of at least " + std::to_string(need) + " numbers");
      for (std::size_t k = 0; k < cy.size(); ++k) {
        study::Series series{{}, true, false, ""};
        for (const std::vector<double>& row : rows) series.points.emplace_back(row[cx - 1], row[cy[k] - 1]);
        panels[k] = {axis_of(ys[k], "column ").label, axis_of(x, "column ").label, "", {series}, {}};
      }
    }
    std::ofstream o(out, std::ios::binary);
    o << study::chart_svg(title, panels);
    o.flush();
    if (!o) throw std::runtime_error("cannot write " + out);
    std::printf("%s\n", out.c_str());
    return 0;
  } catch (const std::invalid_argument& e) {
    return usage(e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dem plot: %s\n", e.what());
    return 1;
  }
}

}  // namespace dem::cli
