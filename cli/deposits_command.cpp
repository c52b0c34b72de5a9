// dem deposits: a figure (SVG) of where several runs' particles lie at their last frame (or at a
// given time), side by side at one scale, coloured by the piece each belongs to, over a terrain's
// contour lines: a landslide study's deposits, as the PDEM-EGD manual's figure 4.17 shows them.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>

#include "cli/commands.hpp"
#include "cli/verb_args.hpp"
#include "cli/run_frames.hpp"
#include "legacy/legacy_formats.hpp"
#include "mesh/mesh_io.hpp"
#include "study/deposit_figure.hpp"

namespace dem::cli {
namespace {

namespace fs = std::filesystem;

constexpr int kMostContourLevels = 1000;

struct NamedRun {
  std::string name, dir;
};

// "NAME=DIR" (split at the last '=': a name such as "C = 4 MPa" may hold some; a NAME has no '/'),
// or DIR named by its folder (a folder that is there is taken whole, '=' and all).
NamedRun named_run(const std::string& text) {
  std::error_code error;
  const std::size_t eq = text.rfind('=');
  if (!fs::is_directory(text, error) && eq != std::string::npos && eq > 0 && text.find('/') > eq)
    return {text.substr(0, eq), text.substr(eq + 1)};
  return {folder_name(text), text};
}

double number_option(const std::string& name, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v))
    throw std::invalid_argument(name + ": \"" + text + "\" is not a number");
  return v;
}

}  // namespace

const Verb kDepositsVerb{
    "deposits",
    "deposits RUN_DIR [RUN_DIR ...] --out FIGURE.svg [--time T] [--view x|y|z] [--terrain MESH] [--contour STEP] "
    "[--unit U] [--title T]",
    "the particles of each run (its ANIMATION_3D.dat) at its last frame, or the frame nearest T (s), one panel each "
    "at one scale, each sphere coloured by the piece it belongs to (the eight largest pieces their own colours)",
    "the runs' folders",
    {{"--out", "FIGURE.svg", "the figure"},
     {"--time", "T", "the frame nearest this time (s) (default: each run's last)"},
     {"--view", "x|y|z", "the axis it is seen along (default z: from above, x to the right, y up)"},
     {"--terrain", "MESH", "a mesh file (the legacy format or STL) whose contour lines go under every panel"},
     {"--contour", "STEP", "the contours' step (default: a round step giving 10 to 25 levels)"},
     {"--unit", "U", "the name of the length unit"},
     {"--title", "T", "the figure's title"}},
    1,
    SIZE_MAX,
    false,
    "NAME=RUN_DIR names a panel (default: the folder's name). At most 20 runs"};

int deposits_command(const std::vector<std::string>& args) {
  VerbArgs a;
  if (const auto exit = parse_verb_args(kDepositsVerb, args, a)) return *exit;
  auto deposits_usage = [](const std::string& problem) { return usage_error(kDepositsVerb, problem); };
  const std::string out = a.value("--out"), view = a.has("--view") ? a.value("--view") : "z",
                    terrain = a.value("--terrain"), unit = a.value("--unit"), title = a.value("--title"),
                    time_text_given = a.value("--time"), contour_text = a.value("--contour");
  std::vector<NamedRun> runs;
  for (const std::string& text : a.positional) runs.push_back(named_run(text));
  if (runs.empty()) return deposits_usage("give at least one run's folder");
  if (runs.size() > 20) return deposits_usage("at most 20 runs (got " + std::to_string(runs.size()) + ")");
  if (out.empty()) return deposits_usage("give --out FIGURE.svg");
  std::pair<int, int> axes;
  double at_time = NAN, contour_step = 0;
  try {
    axes = plane_axes(view);
    if (!time_text_given.empty()) at_time = number_option("--time", time_text_given);
    if (!contour_text.empty()) {
      contour_step = number_option("--contour", contour_text);
      if (!(contour_step > 0)) throw std::invalid_argument("--contour: must be above 0 (got " + contour_text + ")");
      if (terrain.empty()) throw std::invalid_argument("--contour: needs --terrain MESH");
    }
  } catch (const std::invalid_argument& e) {
    return deposits_usage(e.what());
  }
  const int depth = 3 - axes.first - axes.second;
  try {
    // the terrain first: a step it refuses is told before any run's frames are read
    std::vector<study::ContourSegment> contours;
    std::string contour_words;
    if (!terrain.empty()) {
      const TriangleMesh mesh = read_mesh(terrain);
      std::vector<study::MeshTriangle> triangles;
      double lo = INFINITY, hi = -INFINITY;
      for (const auto& t : mesh.triangles) {
        study::MeshTriangle m{};
        for (int c = 0; c < 3; ++c)
          for (int d = 0; d < 3; ++d) m.corners[c][d] = mesh.vertices[t[c]][d];
        triangles.push_back(m);
      }
      for (const Vec3& v : mesh.vertices) lo = std::min(lo, v[depth]), hi = std::max(hi, v[depth]);
      if (contour_step == 0) contour_step = study::contour_interval(hi - lo);
      // a line per level and triangle: a step far below the relief would draw millions
      const double levels = (hi - lo) / contour_step;
      if (levels > kMostContourLevels) {
        char words[200];
        std::snprintf(words, sizeof words, "--contour %s gives %.3g levels over the terrain's relief of %g: at most %d",
                      contour_text.c_str(), levels, hi - lo, kMostContourLevels);
        return deposits_usage(words);
      }
      contours = study::contour_segments(triangles, axes.first, axes.second, depth, contour_step);
      char words[96];
      std::snprintf(words, sizeof words, "contours every %g %s", contour_step,
                    unit.empty() ? "length units" : unit.c_str());
      contour_words = words;
    }
    std::vector<study::DepositPanel> panels;
    for (const NamedRun& run : runs) {
      std::error_code error;
      if (!fs::exists(fs::path(run.dir) / "ANIMATION_3D.dat", error) &&
          fs::is_regular_file(fs::path(run.dir) / "ANIMATION_2D.dat", error))
        throw std::runtime_error(run.dir +
                                 " is a 2D run (ANIMATION_2D.dat): dem deposits draws 3D runs' deposits; "
                                 "dem chains draws a 2D run's discs");
      const auto frames = read_frames<legacy::AnimationFrame>(
          fs::path(run.dir) / "ANIMATION_3D.dat", &legacy::read_animation, "dem deposits", "a 3D run writes it");
      const legacy::AnimationFrame* frame = &frames.back();
      if (std::isfinite(at_time)) {
        for (const legacy::AnimationFrame& f : frames)
          if (std::abs(f.scalars[0] - at_time) < std::abs(frame->scalars[0] - at_time)) frame = &f;
        // a frame farther from the time than the frames are apart is worth a word
        const double spacing = frames.size() > 1 ? std::abs(frames.back().scalars[0] - frames.front().scalars[0]) /
                                                       static_cast<double>(frames.size() - 1)
                                                 : 0;
        if (std::abs(frame->scalars[0] - at_time) > spacing + 1e-9 * std::max(1.0, std::abs(at_time)))
          std::fprintf(stderr, "dem deposits: %s: --time %g s: the nearest frame is %s\n", run.name.c_str(), at_time,
                       time_text(frame->scalars[0], 3).c_str());
      }
      study::DepositPanel panel;
      panel.title = run.name;
      std::set<int> pieces;
      for (const legacy::AnimationParticle& p : frame->particles) {
        // part 0: the run has no bonds or clumps, and every sphere is a piece of its own
        const int piece = p.part > 0 ? p.part : -p.id;
        panel.discs.push_back({{p.position[axes.first], p.position[axes.second]}, p.diameter / 2, piece});
        pieces.insert(piece);
      }
      panel.subtitle = time_text(frame->scalars[0], 3) + ", " + std::to_string(pieces.size()) +
                       (pieces.size() == 1 ? " piece" : " pieces");
      panels.push_back(std::move(panel));
    }
    const char* names = "xyz";
    const study::DepositFigureText text{title.empty() ? std::string("Deposits") : title,
                                        std::string(1, names[axes.first]), std::string(1, names[axes.second]), unit,
                                        contour_words};
    std::ofstream file(out, std::ios::binary);
    file << study::deposit_figure_svg(text, panels, contours);
    file.close();
    if (!file) throw std::runtime_error(out + ": cannot write it");
    std::printf("%s\n", out.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dem deposits: %s\n", e.what());
    return 1;
  }
}

}  // namespace dem::cli
