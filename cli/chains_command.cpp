// dem chains: a figure (SVG) of a run's force chains at a few instants, from its ANIMATION_3D.dat
// (where the particles and plates are) and ForceChain_3D.dat (which pairs touch, how hard), seen
// along an axis.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include "cli/commands.hpp"
#include "cli/verb_args.hpp"
#include "cli/run_frames.hpp"
#include "legacy/legacy_formats.hpp"
#include "study/chain_figure.hpp"

namespace dem::cli {
namespace {

namespace fs = std::filesystem;

std::vector<double> parse_times(const std::string& list) {
  if (!list.empty() && list.back() == ',') throw std::invalid_argument("--times: \"\" is not a time in seconds");
  std::vector<double> times;
  std::stringstream words(list);
  for (std::string word; std::getline(words, word, ',');) {
    char* end = nullptr;
    const double t = std::strtod(word.c_str(), &end);
    if (word.empty() || *end != '\0' || !std::isfinite(t))
      throw std::invalid_argument("--times: \"" + word + "\" is not a time in seconds");
    times.push_back(t);
  }
  if (times.empty()) throw std::invalid_argument("--times: give at least one time");
  if (times.size() > 16) throw std::invalid_argument("--times: at most 16 panels");
  return times;
}

// A frame of either animation file, in the drawing plane.
struct PlaneFrame {
  double time = 0;
  std::int64_t step = 0;
  std::unordered_map<int, study::ChainDisc> discs;  // by particle id
  std::vector<study::ChainDisc> disc_list;          // in the file's order
  std::vector<std::vector<study::Point2>> outlines;
};

std::vector<PlaneFrame> frames_3d(const fs::path& file, std::pair<int, int> axes) {
  auto project = [&](const Vec3& p) { return study::Point2{p[axes.first], p[axes.second]}; };
  std::vector<PlaneFrame> out;
  for (const legacy::AnimationFrame& f :
       read_frames<legacy::AnimationFrame>(file, &legacy::read_animation, "dem chains")) {
    PlaneFrame frame{f.scalars[0], f.step, {}, {}, {}};
    for (const legacy::AnimationParticle& p : f.particles) {
      frame.discs[p.id] = {project(p.position), p.diameter / 2};
      frame.disc_list.push_back({project(p.position), p.diameter / 2});
    }
    for (const legacy::AnimationPlate& plate : f.plates) {
      std::vector<study::Point2> outline;
      for (const Vec3& c : plate.corners) outline.push_back(project(c));
      frame.outlines.push_back(std::move(outline));
    }
    out.push_back(std::move(frame));
  }
  return out;
}

std::vector<PlaneFrame> frames_2d(const fs::path& file) {
  std::vector<PlaneFrame> out;
  for (const legacy::Animation2DFrame& f :
       read_frames<legacy::Animation2DFrame>(file, &legacy::read_animation_2d, "dem chains")) {
    PlaneFrame frame{f.scalars[0], f.step, {}, {}, {}};
    for (const legacy::AnimationDisc& d : f.discs) {
      frame.discs[d.id] = {{d.position.x(), d.position.y()}, d.diameter / 2};
      frame.disc_list.push_back({{d.position.x(), d.position.y()}, d.diameter / 2});
    }
    for (const legacy::AnimationSegment& plate : f.plates)
      frame.outlines.push_back({{plate.ends[0].x(), plate.ends[0].y()}, {plate.ends[1].x(), plate.ends[1].y()}});
    out.push_back(std::move(frame));
  }
  return out;
}

}  // namespace

const Verb kChainsVerb{
    "chains",
    "chains RUN_DIR --times T[,T...] --out FIGURE.svg [--view x|y|z] [--unit U] [--title T]",
    "the force chains of the run in RUN_DIR (its ANIMATION_3D.dat and ForceChain_3D.dat: a spec with "
    "outputs.forceChains) at the frames nearest the times T (s), one panel each",
    "the run's folder",
    {{"--times", "T[,T...]", "the times (s), at most 16"},
     {"--out", "FIGURE.svg", "the figure"},
     {"--view", "x|y|z", "the axis it is seen along (default y: x to the right, z up)"},
     {"--unit", "U", "the name of the files' length unit"},
     {"--title", "T", "the figure's title"}},
    1,
    1,
    false,
    "A 2D run (ANIMATION_2D.dat) is drawn in its x-z plane. A frame both files hold is drawn, the nearest to each "
    "time (a word when it is more than half a frame interval away)"};

int chains_command(const std::vector<std::string>& args) {
  VerbArgs a;
  if (const auto exit = parse_verb_args(kChainsVerb, args, a)) return *exit;
  auto chains_usage = [](const std::string& problem) { return usage_error(kChainsVerb, problem); };
  const std::string dir = a.positional[0], out = a.value("--out"), times_text = a.value("--times"),
                    view = a.has("--view") ? a.value("--view") : "y", unit = a.value("--unit"),
                    title = a.value("--title");
  if (times_text.empty()) return chains_usage("give --times");
  if (out.empty()) return chains_usage("give --out FIGURE.svg");
  std::vector<double> times;
  std::pair<int, int> axes;
  try {
    times = parse_times(times_text);
    axes = plane_axes(view);
  } catch (const std::invalid_argument& e) {
    return chains_usage(e.what());
  }
  const fs::path animation_3d = fs::path(dir) / "ANIMATION_3D.dat", animation_2d = fs::path(dir) / "ANIMATION_2D.dat";
  std::error_code error;
  const bool planar = !fs::exists(animation_3d, error) && fs::is_regular_file(animation_2d, error);
  if (planar && view != "y") return chains_usage("a 2D run is drawn in its x-z plane: --view y (got \"" + view + "\")");
  try {
    const std::vector<PlaneFrame> frames = planar ? frames_2d(animation_2d) : frames_3d(animation_3d, axes);
    const auto chain_frames =
        read_frames<legacy::ForceChainFrame>(fs::path(dir) / "ForceChain_3D.dat", &legacy::read_force_chains,
                                             "dem chains", "a run with outputs.forceChains writes it");
    std::unordered_map<std::int64_t, const legacy::ForceChainFrame*> chains_at;
    for (const legacy::ForceChainFrame& c : chain_frames) chains_at[c.step] = &c;
    std::vector<const PlaneFrame*> both;  // the frames both files hold
    for (const PlaneFrame& f : frames)
      if (chains_at.count(f.step) > 0) both.push_back(&f);
    if (both.empty())
      throw std::runtime_error(std::string("ForceChain_3D.dat and ") +
                               (planar ? "ANIMATION_2D.dat" : "ANIMATION_3D.dat") + " have no frame (step) in common");
    // half the usual spacing of the frames: a frame farther than that from a time is worth a word
    double spacing = 0;
    if (frames.size() > 1) {
      std::vector<double> gaps;
      for (std::size_t k = 1; k < frames.size(); ++k) gaps.push_back(std::abs(frames[k].time - frames[k - 1].time));
      std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
      spacing = gaps[gaps.size() / 2];
    }
    const char* names = "xyz";
    study::ChainFigureText text{title.empty() ? "Force chains, " + folder_name(dir) : title,
                                std::string(1, names[axes.first]), std::string(1, names[axes.second]), unit};
    std::vector<study::ChainPanel> panels;
    for (double t : times) {
      const PlaneFrame* frame = both.front();
      for (const PlaneFrame* f : both)
        if (std::abs(f->time - t) < std::abs(frame->time - t)) frame = f;
      if (std::abs(frame->time - t) > 0.5 * spacing + 1e-9 * std::max(1.0, std::abs(t)))
        std::fprintf(stderr, "dem chains: t = %g s: the nearest frame both files hold is %s\n", t,
                     time_text(frame->time).c_str());
      study::ChainPanel panel;
      panel.title = time_text(frame->time) + " (step " + std::to_string(frame->step) + ")";
      panel.discs = frame->disc_list;
      panel.outlines = frame->outlines;
      std::size_t unknown = 0;
      for (const legacy::ForceChain& c : chains_at.at(frame->step)->chains) {
        const auto a = frame->discs.find(c.i), b = frame->discs.find(c.j);
        if (a == frame->discs.end() || b == frame->discs.end()) {
          ++unknown;
          continue;
        }
        panel.chains.push_back({a->second.centre, b->second.centre, c.normal_force});
      }
      if (unknown > 0)
        std::fprintf(stderr, "dem chains: step %lld: %zu contacts name a particle the frame does not have; not drawn\n",
                     static_cast<long long>(frame->step), unknown);
      panels.push_back(std::move(panel));
    }
    std::ofstream file(out, std::ios::binary);
    file << study::chain_figure_svg(text, panels);
    file.close();
    if (!file) throw std::runtime_error(out + ": cannot write it");
    std::printf("%s\n", out.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dem chains: %s\n", e.what());
    return 1;
  }
}

}  // namespace dem::cli
