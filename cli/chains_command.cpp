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
#include "legacy/legacy_formats.hpp"
#include "study/chain_figure.hpp"

namespace dem::cli {
namespace {

namespace fs = std::filesystem;

const char* kChainsUsage =
    "usage: dem chains RUN_DIR --times T[,T...] --out FIGURE.svg [--view x|y|z] [--unit U] [--title T]\n"
    "         the force chains of the run in RUN_DIR (its ANIMATION_3D.dat and ForceChain_3D.dat: a spec with\n"
    "         outputs.forceChains) at the frames nearest the times T (s), one panel each, seen along the\n"
    "         axis --view (default y: x to the right, z up); --unit names the files' length unit\n";

int chains_usage(const std::string& problem) {
  std::fprintf(stderr, "dem chains: %s\n%s", problem.c_str(), kChainsUsage);
  return 2;
}

std::vector<double> parse_times(const std::string& list) {
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

template <class Frame>
std::vector<Frame> read_frames(const fs::path& path, legacy::ReadResult<Frame> (*reader)(std::istream&),
                               const char* need) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) throw std::runtime_error(path.string() + ": not there (" + need + ")");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open it");
  legacy::ReadResult<Frame> read = reader(in);
  if (!read.problem.empty()) std::fprintf(stderr, "dem chains: %s: %s\n", path.string().c_str(), read.problem.c_str());
  if (read.frames.empty()) throw std::runtime_error(path.string() + ": no complete frame in it");
  return std::move(read.frames);
}

// The two axes of the drawing plane for a view along `axis` (right-handed: y is seen from -y).
std::pair<int, int> plane_axes(const std::string& view) {
  if (view == "x") return {1, 2};
  if (view == "y") return {0, 2};
  if (view == "z") return {0, 1};
  throw std::invalid_argument("--view: x, y or z (got \"" + view + "\")");
}

std::string time_text(double t) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "t = %.3f s", t);
  return buf;
}

}  // namespace

int chains_command(const std::vector<std::string>& args) {
  std::string dir, out, times_text, view = "y", unit, title;
  for (std::size_t k = 0; k < args.size(); ++k) {
    const std::string& a = args[k];
    if (a == "-h" || a == "--help") {
      std::fputs(kChainsUsage, stdout);
      return 0;
    }
    if (a == "--times" || a == "--out" || a == "--view" || a == "--unit" || a == "--title") {
      if (k + 1 >= args.size()) return chains_usage(a + " needs a value");
      const std::string& v = args[++k];
      (a == "--times" ? times_text : a == "--out" ? out : a == "--view" ? view : a == "--unit" ? unit : title) = v;
    } else if (!a.empty() && a[0] == '-') {
      return chains_usage("unknown option " + a);
    } else if (dir.empty()) {
      dir = a;
    } else {
      return chains_usage("one run folder only (got \"" + dir + "\" and \"" + a + "\")");
    }
  }
  if (dir.empty()) return chains_usage("give the run's folder");
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
  try {
    const auto frames = read_frames<legacy::AnimationFrame>(fs::path(dir) / "ANIMATION_3D.dat", &legacy::read_animation,
                                                            "the particles' frames");
    const auto chain_frames = read_frames<legacy::ForceChainFrame>(
        fs::path(dir) / "ForceChain_3D.dat", &legacy::read_force_chains, "a run with outputs.forceChains writes it");
    const char* names = "xyz";
    study::ChainFigureText text{title.empty() ? "Force chains, " + dir : title, std::string(1, names[axes.first]),
                                std::string(1, names[axes.second]), unit};
    auto project = [&](const Vec3& p) { return study::Point2{p[axes.first], p[axes.second]}; };
    std::vector<study::ChainPanel> panels;
    for (double t : times) {
      const legacy::AnimationFrame* frame = &frames.front();
      for (const legacy::AnimationFrame& f : frames)
        if (std::abs(f.scalars[0] - t) < std::abs(frame->scalars[0] - t)) frame = &f;
      const legacy::ForceChainFrame* chains = nullptr;
      for (const legacy::ForceChainFrame& c : chain_frames)
        if (c.step == frame->step) chains = &c;
      if (chains == nullptr)
        throw std::runtime_error("ForceChain_3D.dat has no frame at step " + std::to_string(frame->step) + " (" +
                                 time_text(frame->scalars[0]) + "), which ANIMATION_3D.dat has");
      study::ChainPanel panel;
      panel.title = time_text(frame->scalars[0]) + " (step " + std::to_string(frame->step) + ")";
      std::unordered_map<int, std::size_t> index;
      for (const legacy::AnimationParticle& p : frame->particles) {
        index[p.id] = panel.discs.size();
        panel.discs.push_back({project(p.position), p.diameter / 2});
      }
      for (const legacy::AnimationPlate& plate : frame->plates) {
        std::vector<study::Point2> outline;
        for (const Vec3& c : plate.corners) outline.push_back(project(c));
        panel.outlines.push_back(std::move(outline));
      }
      std::size_t unknown = 0;
      for (const legacy::ForceChain& c : chains->chains) {
        const auto a = index.find(c.i), b = index.find(c.j);
        if (a == index.end() || b == index.end()) {
          ++unknown;
          continue;
        }
        panel.chains.push_back({panel.discs[a->second].centre, panel.discs[b->second].centre, c.normal_force});
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
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dem chains: %s\n", e.what());
    return 1;
  }
}

}  // namespace dem::cli
