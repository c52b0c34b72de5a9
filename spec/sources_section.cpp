// Particles entering during the run (JobSpec.sources): the BallastDEM manual's wind-blown sand. Each
// source is checked against the walls, stages and materials it names; its particles' count over the
// run, where the run's length is known in seconds, against the spec's particle limit.
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "sim/particle_sources.hpp"
#include "spec/input_range.hpp"
#include "spec/section_loaders.hpp"

namespace dem::spec {
namespace {

constexpr int kMaxSources = 1000;
// The diameters a source's checks draw: its sizes must be drawable, and its mean mass estimated.
constexpr int kTrialDraws = 200;
// A region at most this many largest diameters across (its cells are counted in 21 bits an axis).
constexpr double kMaxCellsAcross = 1e6;
constexpr double kMaxCountRate = 1e9;  // particles/s
constexpr std::int64_t kMaxTotalCount =
    1'000'000'000'000;  // particles: far beyond any limit, a bound for the arithmetic

// The seconds the source's window may last at most: its stage's or the run's length where given in
// seconds (0: unknown, a length in steps; the run's settings are loaded after the sources).
double window_length(const ParticleSource& s, const Scene& scene, const api::TimeStepping& time) {
  if (s.stage >= 0) return scene.stages[s.stage].steps > 0 ? 0 : scene.stages[s.stage].duration;
  if (scene.stages.empty()) return time.steps() > 0 ? 0 : time.duration();
  double length = 0;
  for (const Stage& stage : scene.stages) {
    if (stage.steps > 0) return 0;
    length += stage.duration;
  }
  return length;
}

// The seconds it inserts for at most: from its start to its end or its window's, the sooner (0:
// unknown). An end past the run's end does not count (1e9 s on a 0.3 s run was refused as 1e11
// particles: an independent tester).
double active_length(const ParticleSource& s, const Scene& scene, const api::TimeStepping& time) {
  const double window = window_length(s, scene, time);
  const double until = std::isfinite(s.end) ? (window > 0 ? std::min(s.end, window) : s.end) : window;
  return std::isfinite(until) ? std::max(0.0, until - s.start) : 0.0;  // (a bad length is reported by its section)
}

void load_source(const api::Source& in, const std::string& path, int index, SpecContext& ctx,
                 const api::TimeStepping& time, double& inserted) {
  Checker& check = ctx.check;
  Scene& scene = ctx.scene;
  const std::size_t before = check.count();
  ParticleSource s;
  s.name = in.name().empty() ? "source " + std::to_string(index + 1) : in.name();
  check.printable_name(path + ".name", in.name());
  s.path = path;
  s.material = ctx.particle_material(in.material(), path + ".material");
  s.sizes = load_sizes(in.sizes(), path + ".sizes", check);
  const double d_max = largest_diameter(s.sizes);

  const bool box = in.has_min() || in.has_max();
  if (box == !in.face().empty()) {
    check.fail(path, "give its region: a box (min and max) or the faces of a wall (face), one of them");
    return;
  }
  Vec3 lo, hi;  // the region's extent
  if (box) {
    check.vector(path + ".min", in.min(), kLength);
    check.vector(path + ".max", in.max(), kLength);
    s.box = Box{vec(in.min()), vec(in.max())};
    Vec3 width = s.box.max - s.box.min;
    const bool planar = ctx.scene.plane.has_value();  // a 2D run's discs enter at y = 0: the box's y is not used
    if (planar) width.y() = d_max;
    if (!width.allFinite() || !(width.array() >= d_max).all())
      check.fail(path + ".max", "the box must be at least the largest diameter (" + num(d_max) + " m) wide in " +
                                    (planar ? "x and z" : "x, y and z") + ", above min");
    lo = s.box.min;
    hi = s.box.max;
  } else {
    s.region = ParticleSource::Region::Face;
    for (std::size_t k = 0; k < scene.walls.size(); ++k)
      if (scene.walls[k].name == in.face()) {
        if (s.face_wall >= 0) {
          check.fail(path + ".face", "more than one wall is named \"" + in.face() + "\": give them names of their own");
          return;
        }
        s.face_wall = static_cast<int>(k);
      }
    if (s.face_wall < 0) {
      check.fail(path + ".face", "no wall is named \"" + in.face() + "\"");
      return;
    }
    const WallInit& wall = scene.walls[s.face_wall];
    if (std::holds_alternative<PlaneShape>(wall.shape)) {
      check.fail(path + ".face", "wall \"" + in.face() + "\" is an infinite plane: give a plate or a mesh");
      return;
    }
    // particles due while the wall is away would all enter at once when it comes back
    const int stages = std::max<int>(1, static_cast<int>(scene.stages.size()));
    for (int k = 0; k < stages; ++k) {
      if (!in.stage().empty() && (scene.stages.empty() || scene.stages[k].name != in.stage())) continue;
      if (wall.present_at(k)) continue;
      check.fail(path + ".face", "wall \"" + in.face() + "\" is not there at stage " + std::to_string(k + 1) + " (\"" +
                                     scene.stages[k].name +
                                     "\"), where the source is active: give the source the "
                                     "stage it inserts in (stage)");
      break;
    }
    s.depth = in.depth() == 0 ? d_max : in.depth();  // 0 or omitted: a largest diameter
    check.positive(path + ".depth", s.depth, kLength);
    lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    hi = -lo;
    auto include = [&](const Vec3& x) {
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    };
    if (const auto* plate = std::get_if<PlateShape>(&wall.shape))
      for (const Vec3& c : plate->corners) include(c);
    if (const auto* mesh = std::get_if<MeshShape>(&wall.shape))
      for (const Vec3& v : mesh->vertices) include(v);
    lo -= Vec3::Constant(s.depth);
    hi += Vec3::Constant(s.depth);
  }
  if (d_max > 0 && ((hi - lo).array() / d_max > kMaxCellsAcross).any())
    check.fail(path, "its region is more than " + num(kMaxCellsAcross) + " largest diameters across: make it smaller");

  if (in.mass_rate() < 0 || in.count_rate() < 0) {
    if (in.mass_rate() < 0) check.positive(path + ".massRate", in.mass_rate());
    if (in.count_rate() < 0) check.positive(path + ".countRate", in.count_rate());
  } else if ((in.mass_rate() > 0) == (in.count_rate() > 0)) {
    check.fail(path, "give massRate (kg/s) or countRate (particles/s), one of them, positive");
  } else if (in.mass_rate() > 0) {
    s.mass_rate = in.mass_rate();
    check.positive(path + ".massRate", s.mass_rate, kMass);
  } else {
    s.count_rate = in.count_rate();
    check.in_range(path + ".countRate", s.count_rate, 0, kMaxCountRate, true, false);
  }
  if (in.has_mass() && in.has_count()) {
    check.fail(path, "give mass (kg) or count (particles), one of them: the most it inserts in all");
  } else if (in.has_mass()) {
    s.total_mass = in.mass();
    if (!(s.total_mass >= 0) || s.total_mass > kMass.max)
      check.fail(path + ".mass", "must be in [0, " + num(kMass.max) + "] kg (got " + num(s.total_mass) + ")");
  } else if (in.has_count()) {
    s.total_count = in.count();
    if (s.total_count < 0 || s.total_count > kMaxTotalCount)
      check.fail(path + ".count", "must be in [0, 1e12] particles (got " + std::to_string(in.count()) + ")");
  }
  if (!std::isfinite(in.mass_rate())) check.fail(path + ".massRate", "must be finite");
  if (!std::isfinite(in.count_rate())) check.fail(path + ".countRate", "must be finite");
  check.vector(path + ".velocity", in.velocity(), kSpeed);
  s.velocity = vec(in.velocity());
  s.start = in.start();
  if (!(s.start >= 0) || s.start > kDuration.max)
    check.fail(path + ".start", "must be in [0, " + num(kDuration.max) + "] s (got " + num(s.start) + ")");
  if (in.has_end()) {
    s.end = in.end();
    if (!(s.end > s.start) || s.end > kDuration.max)
      check.fail(path + ".end",
                 "must be after start and at most " + num(kDuration.max) + " s (got " + num(s.end) + ")");
  }
  if (!in.stage().empty()) {
    for (std::size_t k = 0; k < scene.stages.size(); ++k)
      if (scene.stages[k].name == in.stage()) s.stage = static_cast<int>(k);
    if (s.stage < 0) check.fail(path + ".stage", "no stage is named \"" + in.stage() + "\"");
  }
  if (const double window = window_length(s, scene, time);
      check.count() == before && window > 0 && std::isfinite(window) && s.start >= window)
    check.fail(path + ".start", "the source starts at " + num(s.start) + " s, when its " +
                                    (s.stage >= 0 ? "stage" : "run") + " of " + num(window) +
                                    " s is over: it would never insert");
  s.seed = in.seed() == 0 ? 1 : in.seed();
  if (in.every_steps() < 0 || in.every_steps() > (std::int64_t{1} << 53))
    check.fail(path + ".everySteps", "must be in [0, 2^53] (got " + std::to_string(in.every_steps()) + ")");
  s.every_steps = in.every_steps();
  if (check.count() != before || s.material < 0) return;

  // Its sizes must be drawable (a spread that hardly ever falls between the bounds is not), and its
  // particles over the run must fit the spec's limits.
  double mean_mass = 0;
  try {
    for (int k = 0; k < kTrialDraws; ++k) {
      const double r = source_radius(s, k);
      mean_mass += sphere_mass(scene.materials[s.material].density, r) / kTrialDraws;
    }
  } catch (const std::runtime_error& e) {
    check.fail(path + ".sizes", e.what());
    return;
  }
  const double length = active_length(s, scene, time);
  const double by_rate = s.count_rate > 0 ? s.count_rate * length : s.mass_rate * length / mean_mass;
  // a total caps it, and gives the count where the window is not known in seconds
  const double by_total = s.total_count >= 0 ? static_cast<double>(s.total_count) : s.total_mass / mean_mass;
  const double count = length > 0 ? std::min(by_rate, by_total) : by_total;
  if (std::isfinite(count) &&
      !check.room(path, scene.particles.size() + static_cast<std::size_t>(inserted), std::ceil(count)))
    return;
  if (std::isfinite(count)) inserted += std::ceil(count);
  scene.sources.push_back(s);
}

}  // namespace

void load_sources(const api::JobSpec& spec, SpecContext& ctx) {
  if (spec.sources_size() > kMaxSources) {
    ctx.check.fail("sources", "at most " + std::to_string(kMaxSources) + " sources (got " +
                                  std::to_string(spec.sources_size()) + ")");
    return;
  }
  double inserted = 0;  // the particles the sources before insert over the run (where known)
  for (int k = 0; k < spec.sources_size(); ++k)
    load_source(spec.sources(k), "sources[" + std::to_string(k) + "]", k, ctx, spec.time(), inserted);
}

}  // namespace dem::spec
