// A 2D run (JobSpec.dimension = 2, .discThickness): discs in the x-z plane, at y = 0. load_plane comes before the
// particles are made (lattices, packings and sources place theirs in the plane); check_plane, after every other
// section, refuses what would move or turn a disc out of the plane, naming the field.
#include <algorithm>
#include <cmath>
#include <utility>

#include "spec/defaults.hpp"
#include "spec/section_loaders.hpp"

namespace dem::spec {
namespace {

// A motion that keeps a wall's trace in the plane: moving in it and turning about y only.
void check_motion_in_plane(const PrescribedMotion& m, const std::string& path, Checker& check) {
  if (m.angular_velocity.x() != 0 || m.angular_velocity.z() != 0)
    check.fail(path + ".angularVelocity", "a 2D run's walls turn about y only: its x and z must be 0");
  for (const auto& [field, v] : {std::pair{".velocity", m.velocity}, std::pair{".amplitude", m.amplitude}})
    if (v.y() != 0)
      check.fail(path + field, "a 2D run's walls move in the x-z plane: its y must be 0 (got " + num(v.y()) + ")");
}

void check_load_in_plane(const LoadControl& load, const std::string& path, Checker& check) {
  if (load.direction.y() != 0)
    check.fail(path + ".direction", "a 2D run's loaded walls push in the x-z plane: its y must be 0");
}

// A plate meets the discs as their section's line only when it stands across the plane (its normal in it) and
// reaches both sides of y = 0; otherwise a disc would touch it where the files draw nothing, or off its line.
void check_plate_across_plane(const PlateShape& plate, const std::string& path, Checker& check) {
  const auto& c = plate.corners;
  const Vec3 normal = (c[1] - c[0]).cross(c[3] - c[0]);
  double low = c[0].y(), high = c[0].y();
  for (const Vec3& x : c) {
    low = std::min(low, x.y());
    high = std::max(high, x.y());
  }
  if (std::abs(normal.y()) > 1e-9 * normal.norm())
    check.fail(path + ".plate",
               "a 2D run's plates stand across the x-z plane: the plate's normal must have no y "
               "part (a tilted plate would meet the discs as spheres, off the line drawn)");
  else if (!(low < 0 && high > 0))
    check.fail(path + ".plate", "a 2D run's plates reach across the plane y = 0 (this one spans y from " + num(low) +
                                    " to " + num(high) + ")");
}

}  // namespace

void load_plane(const api::JobSpec& spec, SpecContext& ctx) {
  Checker& check = ctx.check;
  const int dimension = spec.has_dimension() ? spec.dimension() : 3;
  if (dimension != 2 && dimension != 3) {
    check.fail("dimension", "must be 2 (discs in the x-z plane) or 3 (got " + std::to_string(spec.dimension()) + ")");
    return;
  }
  if (dimension == 3) {
    if (spec.has_disc_thickness())
      check.fail("discThickness", "is for a 2D run's discs: give dimension 2, or leave it out");
    return;
  }
  const double thickness = spec.has_disc_thickness() ? spec.disc_thickness() : defaults::kDiscThickness;
  check.positive("discThickness", thickness, kLength);
  ctx.scene.plane = Scene::Plane{thickness};
}

void check_plane(const api::JobSpec& spec, SpecContext& ctx) {
  Checker& check = ctx.check;
  const Scene& scene = ctx.scene;
  if (!scene.plane) return;
  auto in_plane = [&](const std::string& path, const api::Vec3& v) {
    if (v.y() != 0) check.fail(path, "a 2D run lies in the x-z plane: its y must be 0 (got " + num(v.y()) + ")");
  };
  auto about_y = [&](const std::string& path, const api::Vec3& w) {
    if (w.x() != 0 || w.z() != 0) check.fail(path, "a 2D run's discs turn about y only: its x and z must be 0");
  };
  in_plane("gravity", spec.gravity());
  for (int k = 0; k < spec.stages_size(); ++k) in_plane(at("stages", k) + ".gravity", spec.stages(k).gravity());
  for (int k = 0; k < spec.particles_size(); ++k) {
    const auto& p = spec.particles(k);
    const std::string path = at("particles", k);
    in_plane(path + ".position", p.position());
    in_plane(path + ".velocity", p.velocity());
    in_plane(path + ".force", p.force());
    about_y(path + ".angularVelocity", p.angular_velocity());
  }
  for (int k = 0; k < spec.lattices_size(); ++k) in_plane(at("lattices", k) + ".velocity", spec.lattices(k).velocity());
  for (int k = 0; k < spec.packings_size(); ++k) in_plane(at("packings", k) + ".velocity", spec.packings(k).velocity());
  if (spec.clumps_size() > 0) check.fail("clumps", "rigid clumps are 3D bodies: a 2D run has discs only");
  if (spec.ballast_stones_size() > 0)
    check.fail("ballastStones", "ballast stones are 3D clusters of spheres: a 2D run has discs only");
  for (int k = 0; k < spec.sources_size(); ++k) {
    const auto& s = spec.sources(k);
    in_plane(at("sources", k) + ".velocity", s.velocity());
    if (!s.face().empty())
      check.fail(at("sources", k) + ".face", "a 2D run's sources are boxes (min, max): a face source is 3D only");
  }
  for (std::size_t k = 0; k < scene.walls.size(); ++k) {
    const WallInit& w = scene.walls[k];
    const std::string path = w.where(k);
    if (const auto* plane = std::get_if<PlaneShape>(&w.shape); plane && std::abs(plane->normal.y()) > 1e-12)
      check.fail(path + ".plane.normal",
                 "a 2D run's plane walls stand across the x-z plane: the normal's y must be 0 (a tilted plane would "
                 "meet the discs as spheres)");
    if (const auto* plate = std::get_if<PlateShape>(&w.shape)) check_plate_across_plane(*plate, path, check);
    if (w.motion) check_motion_in_plane(*w.motion, path + ".motion", check);
    if (w.load) check_load_in_plane(*w.load, path + ".load", check);
  }
  for (std::size_t s = 0; s < scene.stages.size(); ++s)
    for (std::size_t c = 0; c < scene.stages[s].wall_changes.size(); ++c) {
      const WallChange& change = scene.stages[s].wall_changes[c];
      const std::string path = at(at("stages", static_cast<int>(s)) + ".wallChanges", static_cast<int>(c));
      if (change.motion) check_motion_in_plane(*change.motion, path + ".motion", check);
      if (change.load) check_load_in_plane(*change.load, path + ".load", check);
    }
}

}  // namespace dem::spec
