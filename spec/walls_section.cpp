// Walls: planes, plates and triangle meshes, with their prescribed motions and loads (JobSpec.walls,
// and the walls a stage adds).
#include <numbers>

#include "mesh/mesh_io.hpp"
#include "spec/defaults.hpp"
#include "spec/referenced_files.hpp"
#include "spec/section_loaders.hpp"

namespace dem::spec {
namespace {

void check_plate(const std::array<Vec3, 4>& c, const std::string& path, Checker& check) {
  const double size = std::max((c[2] - c[0]).norm(), (c[3] - c[1]).norm());
  Vec3 normal = Vec3::Zero();
  // Relative to c1: over absolute coordinates the sum cancels catastrophically far from the origin.
  for (int k = 0; k < 4; ++k) normal += (c[k] - c[0]).cross(c[(k + 1) % 4] - c[0]);
  if (!(size > 0) || normal.norm() < 1e-12 * size * size) {
    check.fail(path, "the four corners do not span an area (degenerate plate)");
    return;
  }
  normal.normalize();
  for (int k = 0; k < 4; ++k) {
    if (std::abs((c[k] - c[0]).dot(normal)) > 1e-6 * size) {
      check.fail(path + ".c" + std::to_string(k + 1), "the plate's corners are not in one plane");
      return;
    }
    if ((c[(k + 1) % 4] - c[k]).cross(c[(k + 2) % 4] - c[(k + 1) % 4]).dot(normal) <= 0) {
      check.fail(path, "the corners must go once around a convex quadrilateral, in order");
      return;
    }
  }
}

// The models the spec's contact block names (contact/models.hpp), with their parameters: each

}  // namespace

Eigen::Matrix3d rotation(const api::Vec3& axis, double degrees, const std::string& path, Checker& check) {
  const Vec3 a = vec(axis);
  if (degrees == 0) return Eigen::Matrix3d::Identity();
  if (!std::isfinite(degrees)) check.fail(path + ".rotationDegrees", "must be finite");
  if (!(a.norm() > 0) || !a.allFinite()) {
    check.fail(path + ".rotationAxis", "must be a non-zero vector when rotationDegrees is given");
    return Eigen::Matrix3d::Identity();
  }
  return Eigen::AngleAxisd(degrees * std::numbers::pi / 180, a.normalized()).toRotationMatrix();
}

std::optional<MeshShape> load_mesh(const api::Mesh& in, const std::string& path, SpecContext& ctx) {
  Checker& check = ctx.check;
  TriangleMesh mesh;
  std::string source = "inline";
  const bool inline_mesh = in.vertices_size() > 0 || in.triangles_size() > 0;
  if (inline_mesh && !in.file().empty()) {
    check.fail(path, "has both a file and inline vertices/triangles: give one");
    return std::nullopt;
  }
  if (!api::Mesh::Format_IsValid(in.format())) {
    check.fail(path + ".format", "must be AUTO, LEGACY or STL (got " + std::to_string(in.format()) + ")");
    return std::nullopt;
  }
  try {
    if (!in.file().empty()) {
      source = resolve_file(in.file(), ctx.base_dir).string();
      if (in.format() == api::Mesh::STL)
        mesh = read_stl(source);
      else if (in.format() == api::Mesh::LEGACY)
        mesh = read_legacy_mesh(source);
      else
        mesh = read_mesh(source);
    } else if (inline_mesh) {
      for (const auto& v : in.vertices()) mesh.vertices.push_back(vec(v));
      for (const auto& t : in.triangles()) mesh.triangles.push_back({t.i() - 1, t.j() - 1, t.k() - 1});
      check_mesh(mesh, [&](std::size_t t) { return path + ".triangles[" + std::to_string(t) + "]"; });
    } else {
      check.fail(path, "needs a file or inline vertices and triangles");
      return std::nullopt;
    }
  } catch (const MeshError& e) {
    check.fail(path + (inline_mesh ? "" : ".file"), e.what());
    return std::nullopt;
  }
  const double scale = in.scale() == 0 ? defaults::kMeshScale : in.scale();
  if (!(scale > 0) || !std::isfinite(scale))
    check.fail(path + ".scale", "must be a positive number (got " + num(scale) + ")");
  check.vector(path + ".translation", in.translation(), kLength);
  mesh.transform(scale, rotation(in.rotation_axis(), in.rotation_degrees(), path, check), vec(in.translation()));
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    if (!mesh.vertices[v].allFinite() || mesh.vertices[v].cwiseAbs().maxCoeff() > kLength.max) {
      check.fail(path, "vertex " + std::to_string(v + 1) + " lies at " + num(mesh.vertices[v].cwiseAbs().maxCoeff()) +
                           " m once placed: " + Checker::beyond(mesh.vertices[v].cwiseAbs().maxCoeff(), kLength));
      break;
    }
  return MeshShape{std::move(mesh.vertices), std::move(mesh.triangles), source};
}

PrescribedMotion load_motion(const api::Motion& in, const std::string& path, Checker& check) {
  check.vector(path + ".velocity", in.velocity(), kSpeed);
  check.vector(path + ".amplitude", in.amplitude(), kSpeed);
  check.vector(path + ".angularVelocity", in.angular_velocity(), kAngularSpeed);
  check.non_negative(path + ".frequency", in.frequency(), kFrequency);
  if (!std::isfinite(in.phase_degrees())) check.fail(path + ".phaseDegrees", "must be finite");
  PrescribedMotion m;
  m.velocity = vec(in.velocity());
  m.amplitude = vec(in.amplitude());
  m.frequency = in.frequency();
  m.phase = in.phase_degrees() * std::numbers::pi / 180;
  m.angular_velocity = vec(in.angular_velocity());
  if (in.has_center()) {
    check.vector(path + ".center", in.center(), kLength);
    m.center = vec(in.center());
  }
  if (!m.amplitude.isZero(0) && !(m.frequency > 0))
    check.fail(path + ".frequency", "must be > 0 when an amplitude is given");
  return m;
}

LoadControl load_control(const api::Load& in, const std::string& path, Checker& check) {
  LoadControl l;
  if (in.has_direction()) {
    check.vector(path + ".direction", in.direction(), kDirection);
    const Vec3 d = vec(in.direction());
    if (!(d.stableNorm() > 0))
      check.fail(path + ".direction", "must not be zero");
    else
      l.direction = unit(d);
  }
  if (in.has_cyclic()) {
    const auto& c = in.cyclic();
    l.kind = LoadControl::Kind::Cyclic;
    check.positive(path + ".mass", in.mass(), kMass);
    check.non_negative(path + ".cyclic.fMin", c.f_min(), kForce);
    check.non_negative(path + ".cyclic.fMax", c.f_max(), kForce);
    if (c.f_max() < c.f_min())
      check.fail(path + ".cyclic.fMax", "must be >= fMin (got " + num(c.f_max()) + " < " + num(c.f_min()) + ")");
    check.positive(path + ".cyclic.frequency", c.frequency(), kFrequency);
    if (c.cycles() < 1) check.fail(path + ".cyclic.cycles", "must be >= 1 (got " + std::to_string(c.cycles()) + ")");
    l.mass = in.mass();
    l.f_min = c.f_min();
    l.f_max = c.f_max();
    l.frequency = c.frequency();
    l.cycles = c.cycles();
  } else if (in.has_servo()) {
    const auto& sv = in.servo();
    l.kind = LoadControl::Kind::Servo;
    check.non_negative(path + ".servo.target", sv.target(), kForce);
    check.positive(path + ".servo.gain", sv.gain(), kGain);
    check.positive(path + ".servo.maxSpeed", sv.max_speed(), kSpeed);
    // a servo sets its speed: a mass would be read and never used (its weight did not act either)
    if (in.mass() != 0)
      check.fail(path + ".mass",
                 "a servo moves at the speed it sets, so it has no mass: give `mass` with `cyclic` only");
    l.target = sv.target();
    l.gain = sv.gain();
    l.max_speed = sv.max_speed();
  } else {
    check.fail(path, "needs a control: cyclic or servo");
  }
  return l;
}

WallInit load_wall(const api::Wall& in, const std::string& path, const std::string& default_name, SpecContext& ctx) {
  Checker& check = ctx.check;
  WallInit w;
  w.path = path;
  w.name = in.name().empty() ? default_name : in.name();
  w.material = ctx.material(in.material(), path + ".material");
  if (w.material >= 0) ctx.wall_materials.insert(w.material);
  if (in.has_plane()) {
    check.vector(path + ".plane.point", in.plane().point(), kLength);
    check.vector(path + ".plane.normal", in.plane().normal(), kDirection);
    const Vec3 n = vec(in.plane().normal());
    if (!(n.stableNorm() > 0)) check.fail(path + ".plane.normal", "must not be zero");
    w.shape = PlaneShape{vec(in.plane().point()), n.stableNorm() > 0 ? unit(n) : Vec3::UnitZ()};
  } else if (in.has_plate()) {
    const auto& pl = in.plate();
    PlateShape plate{{vec(pl.c1()), vec(pl.c2()), vec(pl.c3()), vec(pl.c4())}};
    const std::size_t before = check.count();
    check.vector(path + ".plate.c1", pl.c1(), kLength);
    check.vector(path + ".plate.c2", pl.c2(), kLength);
    check.vector(path + ".plate.c3", pl.c3(), kLength);
    check.vector(path + ".plate.c4", pl.c4(), kLength);
    // The shape checks mean nothing (NaN compares false) unless every corner is finite.
    if (check.count() == before) check_plate(plate.corners, path + ".plate", check);
    w.shape = plate;
  } else if (in.has_mesh()) {
    if (std::optional<MeshShape> mesh = load_mesh(in.mesh(), path + ".mesh", ctx)) w.shape = std::move(*mesh);
  } else {
    check.fail(path, "needs a shape: plane, plate or mesh");
  }
  if (in.has_motion() && in.has_load()) check.fail(path, "has both a motion and a load: give one");
  if (in.has_motion()) w.motion = load_motion(in.motion(), path + ".motion", check);
  if (in.has_load()) w.load = load_control(in.load(), path + ".load", check);
  return w;
}

void load_walls(const api::JobSpec& spec, SpecContext& ctx) {
  // refused at once past the limit (300,000 planes in a 24 MB spec took 744 MB and 12 s to check,
  // and every step tests every particle against every plane)
  if (spec.walls_size() > ctx.check.limits.max_walls)
    throw SpecError({"walls: at most " + std::to_string(ctx.check.limits.max_walls) + " walls (got " +
                     std::to_string(spec.walls_size()) + "); a terrain is one mesh wall of many triangles"});
  for (int k = 0; k < spec.walls_size(); ++k)
    ctx.scene.walls.push_back(load_wall(spec.walls(k), at("walls", k), "wall" + std::to_string(k + 1), ctx));
}

}  // namespace dem::spec
