// How the run goes: gravity, time stepping, outputs, the domain, numerics (JobSpec.gravity, .time,
// .outputs, .domain, .numerics).
#include "spec/defaults.hpp"
#include "spec/section_loaders.hpp"

namespace dem::spec {
namespace {

double length_unit(const std::string& name, Checker& check) {
  if (name.empty() || name == "m") return defaults::kLengthUnit;
  if (name == "cm") return 1e-2;
  if (name == "mm") return 1e-3;
  check.fail("outputs.lengthUnit", "must be \"m\", \"cm\" or \"mm\" (got \"" + name + "\")");
  return 1.0;
}

}  // namespace

void load_run_settings(const api::JobSpec& spec, SpecContext& ctx) {
  Checker& check = ctx.check;
  Scene& scene = ctx.scene;
  // gravity, time, outputs, domain, numerics
  check.vector("gravity", spec.gravity(), kAcceleration);
  scene.gravity = vec(spec.gravity());
  const auto& t = spec.time();
  check.non_negative("time.dt", t.dt());
  scene.time.dt = t.dt();
  if (t.dt_fraction() != 0) {
    // at most the stable limit (10 steps per contact), which a given dt is held to as well
    check.in_range("time.dtFraction", t.dt_fraction(), 0, 0.1, true, false);
    scene.time.dt_fraction = t.dt_fraction();
  }
  if (t.duration() != 0 && t.steps() != 0) check.fail("time", "give duration or steps, not both");
  if (t.duration() == 0 && t.steps() == 0 &&
      spec.stages().empty())  // a staged run's are its stages' (stages_section.cpp)
    check.fail("time", "give the run's duration (s) or its number of steps");
  if (t.duration() != 0) check.positive("time.duration", t.duration());
  if (t.steps() < 0) check.fail("time.steps", "must be >= 0 (got " + std::to_string(t.steps()) + ")");
  scene.time.duration = t.duration();
  scene.time.steps = t.steps();
  scene.time.allow_unstable_dt = t.allow_unstable_dt();

  const auto& o = spec.outputs();
  if (o.interval() != 0 && o.every_steps() != 0) check.fail("outputs", "give interval or everySteps, not both");
  check.non_negative("outputs.interval", o.interval());
  if (o.every_steps() < 0) check.fail("outputs.everySteps", "must be >= 0");
  scene.outputs.animation = o.has_animation() ? o.animation() : true;
  scene.outputs.force_chains = o.force_chains();
  scene.outputs.vtk = o.has_vtk() ? o.vtk() : true;
  scene.outputs.csv = o.has_csv() ? o.csv() : true;
  scene.outputs.length_unit = length_unit(o.length_unit(), check);
  scene.outputs.length_unit_name = o.length_unit().empty() ? "m" : o.length_unit();
  if (!api::Outputs::NumberFormat_IsValid(o.number_format()))
    check.fail("outputs.numberFormat",
               "must be SCIENTIFIC, LEGACY_FIXED or FULL (got " + std::to_string(o.number_format()) + ")");
  scene.outputs.number_format = o.number_format() == api::Outputs::LEGACY_FIXED ? FileNumberFormat::LegacyFixed
                                : o.number_format() == api::Outputs::FULL       ? FileNumberFormat::Full
                                                                                : FileNumberFormat::Scientific;
  scene.outputs.every_steps = o.every_steps();
  scene.outputs.interval_seconds = o.interval();
  if (o.last_frames() < 0 || o.last_frames() > (std::int64_t{1} << 53))
    check.fail("outputs.lastFrames", "must be in [0, 2^53] (got " + std::to_string(o.last_frames()) + ")");
  scene.outputs.last_frames = o.last_frames();

  if (spec.has_domain()) {
    // Written into every animation frame header, where a non-finite number cannot be read back.
    check.vector("domain.min", spec.domain().min(), kLength);
    check.vector("domain.max", spec.domain().max(), kLength);
    const Vec3 lo = vec(spec.domain().min()), hi = vec(spec.domain().max());
    // a 2D run's frames write x and z only
    const bool planar = scene.plane.has_value();
    if (!(lo.x() < hi.x() && lo.z() < hi.z() && (planar || lo.y() < hi.y())))
      check.fail("domain.max",
                 planar ? "must be above domain.min in x and z" : "must be above domain.min in x, y and z");
    scene.domain = Box{lo, hi};
  }

  const auto& n = spec.numerics();
  if (n.skin() != 0) {
    check.in_range("numerics.skin", n.skin(), 0, 2, true, false);
    scene.numerics.skin_fraction = n.skin();
  }
  if (n.search_interval() < 0) check.fail("numerics.searchInterval", "must be >= 0");
  if (n.threads() < 0 || n.threads() > check.limits.max_threads)
    check.fail("numerics.threads", "must be in [0, " + std::to_string(check.limits.max_threads) +
                                       "] (0 = all cores; got " + std::to_string(n.threads()) + ")");
  if (n.check_interval() < 0) check.fail("numerics.checkInterval", "must be >= 0");
  if (n.reorder_interval() < 0) check.fail("numerics.reorderInterval", "must be >= 0");
  scene.numerics.search_interval = n.search_interval();
  scene.numerics.threads = n.threads();
  if (n.max_overlap_fraction() != 0) {
    check.in_range("numerics.maxOverlapFraction", n.max_overlap_fraction(), 0, 1, true, false);
    scene.numerics.max_overlap_fraction = n.max_overlap_fraction();
  }
  if (n.check_interval() > 0) scene.numerics.check_interval = n.check_interval();
  if (n.reorder_interval() > 0) scene.numerics.reorder_interval = n.reorder_interval();
  check.in_range("numerics.localDamping", n.local_damping(), 0, 1, false, true);
  scene.numerics.local_damping = n.local_damping();
}

}  // namespace dem::spec
