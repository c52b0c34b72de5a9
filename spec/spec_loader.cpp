#include "spec/spec_loader.hpp"

#include <google/protobuf/util/json_util.h>

#include <nlohmann/json.hpp>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <regex>
#include <set>
#include <sstream>

#include "clumps/mass_properties.hpp"
#include "contact/model_catalog.hpp"
#include "contact/models.hpp"
#include "mesh/mesh_io.hpp"
#include "spec/lattice.hpp"
#include "spec/ballast_stones.hpp"
#include "spec/clump_template.hpp"
#include "spec/input_range.hpp"
#include "spec/json_keys.hpp"
#include "spec/inside_mesh.hpp"
#include "spec/packing.hpp"
#include "spec/referenced_files.hpp"

namespace dem::spec {
namespace {

std::string join(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += (s.empty() ? "" : "\n") + l;
  return s;
}

// The shortest text that reads back as v: "0.10000001" stays itself ("(got 0.1)" hid why it was refused).
std::string num(double v) {
  char buf[32];
  const auto end = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general).ptr;
  return std::string(buf, end);
}

std::string at(const std::string& path, int index) { return path + "[" + std::to_string(index) + "]"; }

Vec3 vec(const api::Vec3& v) { return {v.x(), v.y(), v.z()}; }

// A direction of any length (1e-300 too, whose square underflows): scaled by its largest component first.
Vec3 unit(const Vec3& d) {
  const Vec3 scaled = d / d.cwiseAbs().maxCoeff();
  return scaled.normalized();
}

// Collects problems, each "path: what is wrong (got value; allowed range)"; past the limits' count
// they are only counted (a spec of 20,000 bad particles once got a 121 MB list).
class Checker {
 public:
  explicit Checker(const SpecLimits& l = {}, double particle_bytes = kEstimatedBytesPerParticle)
      : limits(l), bytes_per_particle(particle_bytes) {}

  void fail(const std::string& path, const std::string& what) {
    ++found;
    if (problems.size() < limits.max_problems) problems.push_back(path + ": " + what);
  }
  // The problems as reported: the first ones, then how many more there were.
  std::vector<std::string> listed() const {
    std::vector<std::string> out = problems;
    if (found > problems.size())
      out.push_back("(" + std::to_string(found - problems.size()) + " more problems not listed)");
    return out;
  }
  bool failed() const { return found > 0; }
  std::size_t count() const { return found; }

  // Whether `more` particles fit beside the `already` made, within the spec's limit; a problem at
  // `path` when not.
  bool room(const std::string& path, std::size_t already, double more) {
    const double total = static_cast<double>(already) + more;
    if (total > static_cast<double>(limits.max_particles)) {
      fail(path, "would make " + num(std::round(total)) + " particles in all, more than the limit of " +
                     std::to_string(limits.max_particles));
      return false;
    }
    const double bytes = total * bytes_per_particle;
    if (limits.max_memory_bytes > 0 && bytes > limits.max_memory_bytes) {
      char buf[400];
      std::snprintf(buf, sizeof buf,
                    "would make %.0f particles in all, which would need about %.1f GB of memory to run (%.0f bytes "
                    "a particle), more than %s allows (%.1f GB)",
                    std::round(total), bytes / 1e9, bytes_per_particle, limits.memory_limit_name.c_str(),
                    limits.max_memory_bytes / 1e9);
      fail(path, buf);
      return false;
    }
    return true;
  }

  void positive(const std::string& path, double v) {
    if (!(v > 0) || !std::isfinite(v)) fail(path, "must be a positive number (got " + num(v) + ")");
  }
  void non_negative(const std::string& path, double v) {
    if (!(v >= 0) || !std::isfinite(v)) fail(path, "must be >= 0 (got " + num(v) + ")");
  }
  void in_range(const std::string& path, double v, double lo, double hi, bool lo_open, bool hi_open) {
    const bool ok = (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
    if (!ok)
      fail(path, "must be in " + std::string(lo_open ? "(" : "[") + num(lo) + ", " + num(hi) + (hi_open ? ")" : "]") +
                     " (got " + num(v) + ")");
  }
  // A vector quantity: finite, each component within the quantity's range (spec/input_range.hpp).
  void vector(const std::string& path, const api::Vec3& v, const Quantity& q) {
    const double largest = std::max({std::abs(v.x()), std::abs(v.y()), std::abs(v.z())});
    if (!std::isfinite(v.x()) || !std::isfinite(v.y()) || !std::isfinite(v.z()))
      fail(path, "must be finite (got (" + num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()) + "))");
    else if (largest > q.max)
      fail(path, beyond(largest, q));
  }
  // A quantity >= 0 within its range's largest value (0 switches a feature off).
  void non_negative(const std::string& path, double v, const Quantity& q) {
    if (!(v >= 0) || !std::isfinite(v))
      fail(path, "must be >= 0 (got " + num(v) + ")");
    else if (v > q.max)
      fail(path, beyond(v, q));
  }
  // A positive quantity within its range.
  void positive(const std::string& path, double v, const Quantity& q) {
    if (!(v > 0) || !std::isfinite(v))
      fail(path, "must be a positive number (got " + num(v) + ")");
    else if (v > q.max)
      fail(path, beyond(v, q));
    else if (v < q.min)
      fail(path, "must be at least " + num(q.min) + (q.unit[0] ? " " : "") + q.unit + " (got " + num(v) +
                     "): far below any scene; check the units");
  }
  static std::string beyond(double v, const Quantity& q) {
    return "must be at most " + num(q.max) + (q.unit[0] ? " " : "") + q.unit + " in size (got " + num(v) +
           "): far beyond any scene; check the units";
  }

  std::vector<std::string> problems;
  SpecLimits limits;
  double bytes_per_particle;  // the memory estimate of one particle of this spec

 private:
  std::size_t found = 0;
};

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

void load_mesh(const api::Mesh& in, const std::string& path, const std::string& base_dir, Checker& check, WallInit& w) {
  TriangleMesh mesh;
  std::string source = "inline";
  const bool inline_mesh = in.vertices_size() > 0 || in.triangles_size() > 0;
  if (inline_mesh && !in.file().empty()) {
    check.fail(path, "has both a file and inline vertices/triangles: give one");
    return;
  }
  try {
    if (!in.file().empty()) {
      source = resolve_file(in.file(), base_dir).string();
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
      return;
    }
  } catch (const MeshError& e) {
    check.fail(path + (inline_mesh ? "" : ".file"), e.what());
    return;
  }
  const double scale = in.scale() == 0 ? 1.0 : in.scale();
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
  w.shape = MeshShape{std::move(mesh.vertices), std::move(mesh.triangles), source};
}

PrescribedMotion motion(const api::Motion& in, const std::string& path, Checker& check) {
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

LoadControl load(const api::Load& in, const std::string& path, Checker& check) {
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

void add_packing(const api::Packing& in, const std::string& path, const std::string& base_dir, Checker& check,
                 Scene& scene, int material) {
  const std::size_t before = check.count();
  check.vector(path + ".min", in.min(), kLength);
  check.vector(path + ".max", in.max(), kLength);
  check.vector(path + ".velocity", in.velocity(), kSpeed);
  std::optional<ClosedMesh> region;
  double region_volume = 0;
  if (in.has_inside()) {
    WallInit holder;
    load_mesh(in.inside(), path + ".inside", base_dir, check, holder);
    if (check.count() != before) return;
    const MeshShape& shape = std::get<MeshShape>(holder.shape);
    region.emplace(shape);
    double six_v = 0;  // the enclosed volume by the divergence theorem: signed tetrahedra from the origin
    for (const auto& t : shape.triangles)
      six_v += shape.vertices[t[0]].dot(shape.vertices[t[1]].cross(shape.vertices[t[2]]));
    region_volume = std::abs(six_v) / 6;
  }
  const bool box_given = in.has_min() || in.has_max();
  const Vec3 lo = region && !box_given ? region->min() : vec(in.min());
  const Vec3 hi = region && !box_given ? region->max() : vec(in.max());
  if (!(lo.array() < hi.array()).all()) check.fail(path + ".max", "must be above min in x, y and z");
  const auto& sz = in.sizes();
  SizeDistribution d;
  d.kind = static_cast<SizeKind>(sz.kind());
  d.mean = sz.mean();
  d.spread = sz.spread();
  d.d_min = sz.d_min();
  d.d_max = sz.d_max();
  d.small_fraction = sz.small_fraction() == 0 ? 0.5 : sz.small_fraction();
  const std::string sp = path + ".sizes";
  if (d.kind == SizeKind::One || d.kind == SizeKind::Normal || d.kind == SizeKind::Lognormal)
    check.positive(sp + ".mean", d.mean, kRadius);
  if (d.kind == SizeKind::Normal || d.kind == SizeKind::Lognormal) check.positive(sp + ".spread", d.spread);
  if (d.kind != SizeKind::One) {
    check.positive(sp + ".dMin", d.d_min, kRadius);
    if (d.d_max > kRadius.max) check.fail(sp + ".dMax", Checker::beyond(d.d_max, kRadius));
    if (!(d.d_max >= d.d_min)) check.fail(sp + ".dMax", "must be >= dMin (got " + num(d.d_max) + ")");
  }
  if ((d.kind == SizeKind::Normal || d.kind == SizeKind::Lognormal) && !(d.mean >= d.d_min && d.mean <= d.d_max))
    check.fail(sp + ".mean", "must lie in [dMin, dMax] (got " + num(d.mean) + ")");
  check.in_range(sp + ".smallFraction", d.small_fraction, 0, 1, false, false);
  if ((in.count() > 0) == (in.solid_fraction() > 0)) check.fail(path, "give count or solidFraction (one of them)");
  check.in_range(path + ".solidFraction", in.solid_fraction(), 0, 0.74, false, false);
  if (in.count() < 0 || in.count() > 10000000)
    check.fail(path + ".count", "must be in [1, 10000000] (got " + std::to_string(in.count()) + ")");
  if (check.count() != before) return;
  std::mt19937_64 rng(in.seed() == 0 ? 1u : in.seed());
  std::vector<double> diameters;
  try {
    if (in.count() > 0) {
      diameters = sample_diameters(d, in.count(), rng);
    } else {  // draw until the spheres' volume makes the solid fraction
      const double target = in.solid_fraction() * (region ? region_volume : (hi - lo).prod());
      double volume = 0;
      SizeDraws draws;  // one budget for the whole packing, not one per diameter
      while (volume < target && diameters.size() < 10000000) {
        const double dia = sample_diameters(d, 1, rng, &draws)[0];
        diameters.push_back(dia);
        volume += std::numbers::pi / 6 * dia * dia * dia;
      }
    }
  } catch (const std::runtime_error& e) {
    check.fail(sp, e.what());
    return;
  }
  if (!check.room(path, scene.particles.size(), static_cast<double>(diameters.size()))) return;
  try {
    std::function<bool(const Vec3&, double)> accept;
    if (region) accept = [&](const Vec3& x, double r) { return region->holds(x, r); };
    // around the particles listed, lattices and packings before it
    std::vector<Sphere> there;
    for (const ParticleInit& p : scene.particles) there.push_back({p.position, p.radius});
    const std::vector<Vec3> sites = random_packing(lo, hi, diameters, rng, accept, there);
    for (std::size_t k = 0; k < sites.size(); ++k) {
      ParticleInit p;
      p.position = sites[k];
      p.radius = diameters[k] / 2;
      p.velocity = vec(in.velocity());
      p.material = material;
      scene.particles.push_back(p);
    }
  } catch (const std::runtime_error& e) {
    check.fail(path, e.what());
  }
}

// A clump shape ready to place: its spheres (scaled) and its body, found by subdivision or given.
struct ClumpBody {
  std::vector<MemberSphere> spheres;
  bool usable = false;
  double given_mass = 0;  // kg; 0: density x volume
  double volume = 0;      // m^3 (subdivision)
  Vec3 centroid = Vec3::Zero();
  Vec3 principal_moments = Vec3::Zero();  // per unit density (subdivision) or in kg m^2 (given)
  Eigen::Matrix3d principal_axes = Eigen::Matrix3d::Identity();
};

// A user's inertia tensor: symmetric positive definite with each principal moment at most the
// sum of the other two (true of every real body); its principal moments and axes.
void given_body(const api::GivenMassProperties& in, const std::string& path, Checker& check, ClumpBody& body) {
  check.positive(path + ".mass", in.mass(), kMass);
  check.vector(path + ".centroid", in.centroid(), kLength);
  const api::Inertia& t = in.inertia();
  Eigen::Matrix3d inertia;
  inertia << t.xx(), t.xy(), t.xz(), t.xy(), t.yy(), t.yz(), t.xz(), t.yz(), t.zz();
  if (!inertia.allFinite()) {
    check.fail(path + ".inertia", "must be finite");
    return;
  }
  if (inertia.cwiseAbs().maxCoeff() > kInertia.max) {
    check.fail(path + ".inertia", Checker::beyond(inertia.cwiseAbs().maxCoeff(), kInertia));
    return;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(inertia);
  const Vec3& moments = solver.eigenvalues();  // ascending
  if (!(moments[0] > 0)) {
    check.fail(path + ".inertia", "is not positive definite (principal moments " + num(moments[0]) + ", " +
                                      num(moments[1]) + ", " + num(moments[2]) + ")");
    return;
  }
  if (moments[2] > (moments[0] + moments[1]) * (1 + 1e-9)) {
    check.fail(path + ".inertia", "is not a body's: the largest principal moment " + num(moments[2]) +
                                      " exceeds the sum of the other two");
    return;
  }
  body.given_mass = in.mass();
  body.centroid = vec(in.centroid());
  body.principal_moments = moments;
  body.principal_axes = solver.eigenvectors();
  if (body.principal_axes.determinant() < 0) body.principal_axes.col(2) *= -1;  // right-handed
}

// One clump shape: spheres inline or from a template file, scaled; the body by subdivision to the
// shape's accuracy, or as given.
ClumpBody clump_body(const api::ClumpShape& in, const std::string& path, const std::string& base_dir, Checker& check) {
  ClumpBody body;
  if (!in.file().empty() && in.spheres_size() > 0) check.fail(path, "give spheres or a template file, not both");
  std::vector<MemberSphere> spheres;
  if (!in.file().empty()) {
    try {
      spheres = read_clump_template(resolve_file(in.file(), base_dir).string());
    } catch (const std::runtime_error& e) {
      check.fail(path + ".file", e.what());
    }
  }
  for (int s = 0; s < in.spheres_size(); ++s) {
    const std::string sp = path + ".spheres[" + std::to_string(s) + "]";
    check.vector(sp + ".center", in.spheres(s).center(), kLength);
    check.positive(sp + ".radius", in.spheres(s).radius(), kRadius);
    spheres.push_back({vec(in.spheres(s).center()), in.spheres(s).radius()});
  }
  if (spheres.empty() && in.file().empty()) check.fail(path + ".spheres", "a clump shape needs at least one sphere");
  const double scale = in.scale() == 0 ? 1.0 : in.scale();
  check.positive(path + ".scale", scale);
  const double accuracy = in.accuracy() == 0 ? 1e-4 : in.accuracy();
  constexpr double kFinest = 1e-5, kCoarsest = 0.1;  // finer is past the subdivision's 2^11 cells
  const bool accuracy_ok = accuracy >= kFinest && accuracy <= kCoarsest;
  check.in_range(path + ".accuracy", accuracy, kFinest, kCoarsest, false, false);
  for (MemberSphere& m : spheres) {
    m.centre *= scale;
    m.radius *= scale;
  }
  body.spheres = spheres;
  body.usable = !spheres.empty() && scale > 0 && std::all_of(spheres.begin(), spheres.end(), [](const MemberSphere& m) {
    return m.radius > 0 && std::isfinite(m.radius) && m.centre.allFinite();
  });
  if (!body.usable) return body;
  if (in.has_given()) {
    given_body(in.given(), path + ".given", check, body);
    body.usable = body.given_mass > 0;
    return body;
  }
  if (!accuracy_ok) return body;
  const MassProperties mp = union_mass_properties(spheres, accuracy);
  body.volume = mp.volume;
  body.centroid = mp.centroid;
  body.principal_moments = mp.principal_moments;
  body.principal_axes = mp.principal_axes;
  body.usable = mp.volume > 0;
  return body;
}

// Rigid clumps: each clump's members become particles of the scene (after the others), with the
// clump's body (its mass properties, principal axes) in Scene::clumps.
template <class MaterialOf>
void add_clumps(const api::JobSpec& spec, const std::string& base_dir, Checker& check, Scene& scene,
                MaterialOf&& material_of) {
  std::map<std::string, int> shape_index;
  std::vector<ClumpBody> bodies;
  for (int k = 0; k < spec.clump_shapes_size(); ++k) {
    const api::ClumpShape& in = spec.clump_shapes(k);
    const std::string path = "clumpShapes[" + std::to_string(k) + "]";
    if (in.name().empty())
      check.fail(path + ".name", "a clump shape needs a name");
    else if (!shape_index.emplace(in.name(), k).second)
      check.fail(path + ".name", "\"" + in.name() + "\" is given twice");
    bodies.push_back(clump_body(in, path, base_dir, check));
  }
  for (int k = 0; k < spec.clumps_size(); ++k) {
    const api::Clump& in = spec.clumps(k);
    const std::string path = "clumps[" + std::to_string(k) + "]";
    const auto shape = shape_index.find(in.shape());
    if (shape == shape_index.end()) {
      check.fail(path + ".shape", "unknown clump shape \"" + in.shape() + "\"");
      continue;
    }
    const int material = material_of(in.material(), path + ".material");
    check.vector(path + ".position", in.position(), kLength);
    check.vector(path + ".velocity", in.velocity(), kSpeed);
    check.vector(path + ".angularVelocity", in.angular_velocity(), kAngularSpeed);
    const ClumpBody& body = bodies[shape->second];
    if (material < 0 || !body.usable) continue;
    const double density = scene.materials[material].density;
    const Eigen::Matrix3d turn = rotation(in.rotation_axis(), in.rotation_degrees(), path, check);
    ClumpInit c;
    c.first = static_cast<int>(scene.particles.size());
    c.mass = body.given_mass > 0 ? body.given_mass : density * body.volume;
    c.moments = body.given_mass > 0 ? body.principal_moments : Vec3(density * body.principal_moments);
    c.position = vec(in.position());
    c.orientation = Eigen::Quaterniond(turn * body.principal_axes).normalized();  // body (principal) -> space
    c.velocity = vec(in.velocity());
    c.angular_velocity = vec(in.angular_velocity());
    for (const MemberSphere& sphere : body.spheres) {
      ParticleInit p;
      const Vec3 arm = turn * (sphere.centre - body.centroid);
      p.position = c.position + arm;
      p.velocity = c.velocity + c.angular_velocity.cross(arm);
      p.angular_velocity = c.angular_velocity;
      p.radius = sphere.radius;
      p.material = material;
      p.clump = static_cast<int>(scene.clumps.size());
      scene.particles.push_back(p);
    }
    c.count = static_cast<int>(body.spheres.size());
    scene.clumps.push_back(c);
  }
}

// BallastDEM's stones (spec/ballast_stones.hpp): rigid clumps, or breakable bonded agglomerates
// (which need the spec's bonds). Generated only when the spec has no problems so far.
void add_stones(const api::BallastStones& in, const std::string& path, bool has_bonds, Checker& check, Scene& scene,
                int material) {
  StoneRequest r;
  r.count = in.count();
  r.log_mean = in.mass_log_mean();
  r.log_sigma = in.mass_log_sigma();
  r.mass_min = in.mass_min();
  r.mass_max = in.mass_max();
  r.min_spheres = in.min_spheres() == 0 ? 3 : in.min_spheres();
  r.max_spheres = in.max_spheres() == 0 ? std::max(12, r.min_spheres) : in.max_spheres();
  r.shapes = in.shapes() == 0 ? 32 : in.shapes();
  r.lo = vec(in.min());
  r.hi = vec(in.max());
  r.seed = in.seed() == 0 ? 1 : in.seed();
  check.in_range(path + ".count", r.count, 1, 1e6, false, false);
  if (!std::isfinite(r.log_mean)) check.fail(path + ".massLogMean", "must be a finite number");
  check.non_negative(path + ".massLogSigma", r.log_sigma);
  check.positive(path + ".massMin", r.mass_min);
  if (!(r.mass_max > r.mass_min)) check.fail(path + ".massMax", "must be above massMin (got " + num(r.mass_max) + ")");
  check.in_range(path + ".minSpheres", r.min_spheres, 1, 20, false, false);
  check.in_range(path + ".maxSpheres", r.max_spheres, r.min_spheres, 20, false, false);
  check.in_range(path + ".shapes", r.shapes, 1, 1000, false, false);
  if (!((r.hi - r.lo).minCoeff() > 0)) check.fail(path + ".max", "must be above min in x, y and z");
  // the bounded distribution must not be (nearly) empty: the sampler redraws until it hits it
  const auto cdf = [&](double m) {
    return 0.5 * std::erfc(-(std::log(m) - r.log_mean) / (r.log_sigma * std::sqrt(2.0)));
  };
  if (r.mass_min > 0 && r.mass_max > r.mass_min && r.log_sigma > 0 && cdf(r.mass_max) - cdf(r.mass_min) < 1e-3)
    check.fail(path + ".massMin", "and massMax hold less than 0.1% of the lognormal distribution: check massLogMean");
  const double only_mass = std::exp(r.log_mean);  // massLogSigma 0: every stone has this mass
  if (r.log_sigma == 0 && std::isfinite(r.log_mean) && (only_mass < r.mass_min || only_mass > r.mass_max))
    check.fail(path + ".massLogMean", "with massLogSigma 0 every stone weighs exp(massLogMean) = " + num(only_mass) +
                                          " kg, outside [massMin, massMax]");
  if (in.has_bonded()) {
    r.bonded_sphere_radius = in.bonded().sphere_radius();
    check.positive(path + ".bonded.sphereRadius", r.bonded_sphere_radius, kRadius);
    if (!has_bonds)
      check.fail(path + ".bonded",
                 "breakable stones need the spec's \"bonds\" block (the bonds' stiffness and strength)");
  }
  r.material = material;
  if (check.failed() || r.material < 0) return;  // generation needs a sound spec
  r.density = scene.materials[r.material].density;
  if (r.bonded_sphere_radius > 0) {
    const double sphere_mass = r.density * 4.0 / 3.0 * std::numbers::pi * std::pow(r.bonded_sphere_radius, 3);
    const double largest = r.mass_max / sphere_mass;  // spheres in the heaviest stone allowed
    if (largest > 1e6) {
      check.fail(path + ".bonded.sphereRadius", num(r.bonded_sphere_radius) + " m would put up to " + num(largest) +
                                                    " spheres in one stone (at most 1 million): make it larger");
      return;
    }
    if (largest * r.count > 5e7) {  // as the lattices' limit
      check.fail(path + ".bonded.sphereRadius", num(r.bonded_sphere_radius) + " m would put up to " +
                                                    num(largest * r.count) + " spheres in " + std::to_string(r.count) +
                                                    " stones of up to massMax (at most 50 million): make it larger");
      return;
    }
  }
  try {
    add_ballast_stones(r, scene);
  } catch (const std::runtime_error& e) {
    check.fail(path, e.what());
  }
}

double length_unit(const std::string& name, Checker& check) {
  if (name.empty() || name == "m") return 1.0;
  if (name == "cm") return 1e-2;
  if (name == "mm") return 1e-3;
  check.fail("outputs.lengthUnit", "must be \"m\", \"cm\" or \"mm\" (got \"" + name + "\")");
  return 1.0;
}

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
// parameter field given must belong to one of the chosen models and lie in its range.
struct ContactChoice {
  ContactSettings settings;
  const ModelInfo* normal = nullptr;  // nullptr: an unknown name (already reported)
};

ContactChoice contact_models_of(const api::ContactModel& in, Checker& check) {
  const ModelCatalog& catalog = contact_models();
  ContactChoice out;
  // An unset enum (its *_UNSPECIFIED value) is the default model.
  const std::string normal = in.normal() == api::ContactModel::NORMAL_UNSPECIFIED
                                 ? std::string(LinearNormal::kName)
                                 : api::ContactModel::Normal_Name(in.normal());
  const std::string rolling = in.rolling() == api::ContactModel::ROLLING_UNSPECIFIED
                                  ? std::string(NoRolling::kName)
                                  : api::ContactModel::Rolling_Name(in.rolling());
  out.normal = ModelCatalog::find(catalog.normal, normal);
  const ModelInfo* rolling_model = ModelCatalog::find(catalog.rolling, rolling);
  if (!out.normal) check.fail("contact.normal", "no normal model \"" + normal + "\" in this build");
  if (!rolling_model) check.fail("contact.rolling", "no rolling model \"" + rolling + "\" in this build");
  out.settings.normal = normal;
  out.settings.rolling = rolling;
  out.settings.no_tensile_force = in.has_no_tensile_force() ? in.no_tensile_force() : true;

  std::vector<const ModelInfo*> chosen{out.normal, rolling_model};
  for (const ModelInfo& m : catalog.tangential) chosen.push_back(&m);
  const google::protobuf::Descriptor* descriptor = in.GetDescriptor();
  const google::protobuf::Reflection* reflection = in.GetReflection();
  for (int f = 0; f < descriptor->field_count(); ++f) {
    const google::protobuf::FieldDescriptor* field = descriptor->field(f);
    if (field->type() != google::protobuf::FieldDescriptor::TYPE_DOUBLE || !reflection->HasField(in, field)) continue;
    const std::string path = "contact." + field->json_name();
    const double value = reflection->GetDouble(in, field);
    const ModelParameter* parameter = nullptr;
    for (const ModelInfo* m : chosen)
      for (const ModelParameter& p : m ? m->parameters : std::span<const ModelParameter>{})
        if (p.field == field->name()) parameter = &p;
    if (!parameter) {
      std::string owners;
      for (const auto* kind : {&catalog.normal, &catalog.rolling})
        for (const ModelInfo& m : *kind)
          for (const ModelParameter& p : m.parameters)
            if (p.field == field->name()) owners += (owners.empty() ? "" : " or ") + std::string(m.name);
      check.fail(path, "is not used by the chosen models (normal " + normal + ", rolling " + rolling + ")" +
                           (owners.empty() ? std::string() : "; it is a parameter of " + owners));
      continue;
    }
    if (!std::isfinite(value) || value < parameter->min || value > parameter->max) {
      // an unbounded range is open at infinity: "[0, inf)", which an infinite value is not in
      const std::string upper = std::isfinite(parameter->max) ? num(parameter->max) + "]" : std::string("inf)");
      check.fail(path, "must be in [" + num(parameter->min) + ", " + upper + " (got " + num(value) +
                           "): " + std::string(parameter->meaning));
      continue;
    }
    out.settings.parameters.set(parameter->field, value);
  }
  return out;
}

void check_required_properties(const ModelInfo& model, const Material& m, const std::string& path, Checker& check) {
  for (MaterialProperty property : model.required) {
    const std::string field = path + "." + std::string(material_property_name(property));
    switch (property) {
      case MaterialProperty::Density:
        break;  // checked for every particle material
      case MaterialProperty::YoungsModulus:
        check.positive(field, m.youngs_modulus, kModulus);
        break;
      case MaterialProperty::PoissonRatio:
        break;  // checked for every material
      case MaterialProperty::NormalStiffness:
        check.positive(field, m.normal_stiffness, kStiffness);
        break;
    }
  }
}

}  // namespace

SpecError::SpecError(std::vector<std::string> problems)
    : std::runtime_error(join(problems)), problems_(std::move(problems)) {}

// Protobuf's JSON errors name the field as "(parent) name: ..." or "(path): ..."; say them the way
// the checks do: "path: what is wrong".
std::string reword_protobuf_error(const std::string& message) {
  static const std::regex unknown(R"(^\(([^)]*)\) ?([A-Za-z0-9_]+): Cannot find field\.?$)");
  static const std::regex unknown_top(R"(^([A-Za-z0-9_]+): Cannot find field\.?$)");
  static const std::regex bad_value(R"(^\(([^)]*)\): invalid value (.*) for type TYPE_([A-Z0-9]+)$)");
  static const std::regex bad_enum(R"(^\(([^)]*)\): invalid value (.*) for type type\.googleapis\.com/(.+)$)");
  std::smatch m;
  if (std::regex_match(message, m, bad_enum)) {
    std::string names;
    if (const auto* e = google::protobuf::DescriptorPool::generated_pool()->FindEnumTypeByName(m[3].str())) {
      for (int k = 0; k < e->value_count(); ++k) {
        const std::string& name = e->value(k)->name();
        if (name.find("UNSPECIFIED") != std::string::npos) continue;
        names += (names.empty() ? "" : ", ") + name;
      }
    }
    return m[1].str() + ": expected one of " + (names.empty() ? m[3].str() : names) + ", got " + m[2].str();
  }
  if (std::regex_match(message, m, unknown)) return m[1].str() + "." + m[2].str() + ": unknown field";
  if (std::regex_match(message, m, unknown_top)) return m[1].str() + ": unknown field";
  if (std::regex_match(message, m, bad_value)) {
    const std::string type = m[3].str();
    const std::string expected = type == "DOUBLE" || type == "FLOAT"     ? "a number"
                                 : type == "BOOL"                        ? "true or false"
                                 : type == "STRING"                      ? "a string"
                                 : type.find("INT") != std::string::npos ? "a whole number"
                                                                         : "a value of type " + type;
    return m[1].str() + ": expected " + expected + ", got " + m[2].str();
  }
  return "spec: " + message;
}

api::JobSpec parse_json(const std::string& text) {
  // Syntax first, with a line and column (protobuf's parser gives neither).
  try {
    const auto syntax_only = nlohmann::json::parse(text);
    (void)syntax_only;
  } catch (const nlohmann::json::parse_error& e) {
    throw SpecError({std::string("spec: malformed JSON: ") + e.what()});
  } catch (const nlohmann::json::exception& e) {  // a number too large for a double (1e999)
    throw SpecError({std::string("spec: malformed JSON: ") + e.what()});
  }
  std::vector<std::string> repeated = repeated_keys(text);
  if (!repeated.empty()) {
    for (std::string& path : repeated) path += ": is given twice in its object (the parser would keep the last one)";
    throw SpecError(repeated);
  }
  api::JobSpec spec;
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = false;
  const auto status = google::protobuf::util::JsonStringToMessage(text, &spec, options);
  if (!status.ok()) throw SpecError({reword_protobuf_error(std::string(status.message()))});
  return spec;
}

api::JobSpec parse_binary(const std::string& bytes) {
  api::JobSpec spec;
  if (!spec.ParseFromString(bytes)) throw SpecError({"spec: not a valid protobuf JobSpec message"});
  return spec;
}

api::JobSpec read_json_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SpecError({path + ": cannot open the spec file"});
  std::stringstream text;
  text << in.rdbuf();
  try {
    return parse_json(text.str());
  } catch (const SpecError& e) {
    throw SpecError({path + ": " + e.what()});
  }
}

Scene to_scene(const api::JobSpec& spec, const std::string& base_dir, const SpecLimits& limits) {
  Checker check(limits, spec.has_bonds() ? kEstimatedBytesPerBondedParticle : kEstimatedBytesPerParticle);
  if (spec.name().size() > limits.max_name)
    check.fail("name", "must be at most " + std::to_string(limits.max_name) + " bytes (got " +
                           std::to_string(spec.name().size()) + ")");
  // a name is shown in lists, terminals and file headers: no line breaks or escape sequences
  for (std::size_t k = 0; k < spec.name().size(); ++k) {
    const auto c = static_cast<unsigned char>(spec.name()[k]);
    if (c < 0x20 || c == 0x7F) {
      char buf[120];
      std::snprintf(buf, sizeof buf, "must not hold control characters (byte %zu is 0x%02X)", k, c);
      check.fail("name", buf);
      break;
    }
  }
  Scene scene;
  scene.name = spec.name();

  // contact models, and the material properties and parameters they ask for
  const ContactChoice contact = contact_models_of(spec.contact(), check);
  scene.contact = contact.settings;

  // materials: refused at once past the limit, before anything grows with the square of their count
  if (spec.materials_size() > limits.max_materials)
    throw SpecError({"materials: at most " + std::to_string(limits.max_materials) + " materials (got " +
                     std::to_string(spec.materials_size()) + ")"});
  std::map<std::string, int> material_index;
  if (spec.materials().empty()) check.fail("materials", "at least one material is required");
  for (int m = 0; m < spec.materials_size(); ++m) {
    const auto& in = spec.materials(m);
    const std::string path = at("materials", m);
    Material out;
    out.name = in.name();
    out.density = in.density();
    out.youngs_modulus = in.youngs_modulus();
    out.poisson_ratio = in.poisson_ratio();
    out.normal_stiffness = in.normal_stiffness();
    out.rigid = in.rigid();
    if (in.name().empty())
      check.fail(path + ".name", "a material needs a name");
    else if (!material_index.emplace(in.name(), m).second)
      check.fail(path + ".name", "duplicate material name \"" + in.name() + "\"");
    if (!out.rigid) {
      // every particle needs a density (its mass); a Poisson ratio, where given, must be one
      check.positive(path + ".density", out.density, kDensity);
      check.in_range(path + ".poissonRatio", out.poisson_ratio, -1, 0.5, true, true);
      if (contact.normal) check_required_properties(*contact.normal, out, path, check);
    }
    scene.materials.push_back(out);
  }
  auto material = [&](const std::string& name, const std::string& path) {
    auto it = material_index.find(name);
    if (it == material_index.end()) {
      check.fail(path, "unknown material \"" + name + "\"");
      return -1;
    }
    return it->second;
  };

  // interactions
  const int nm = static_cast<int>(scene.materials.size());
  scene.interactions.assign(static_cast<size_t>(nm) * nm, Interaction{});
  std::vector<char> given(static_cast<size_t>(nm) * nm, 0);
  for (int k = 0; k < spec.interactions_size(); ++k) {
    const auto& in = spec.interactions(k);
    const std::string path = at("interactions", k);
    const int a = material(in.a(), path + ".a"), b = material(in.b(), path + ".b");
    check.in_range(path + ".restitution", in.restitution(), 0, 1, true, false);
    check.non_negative(path + ".friction", in.friction(), kCoefficient);
    // mu_r is the rolling moment's lever over the radius: past 1 it would act outside the sphere
    // (and EPSD's rolling spring, 2.25 k_n mu_r^2 R^2, would outrun the step chosen for k_n)
    check.in_range(path + ".rollingFriction", in.rolling_friction(), 0, 1, false, false);
    if (in.rolling_friction() > 0 && scene.contact.rolling == NoRolling::kName)
      check.fail(path + ".rollingFriction", "is " + num(in.rolling_friction()) +
                                                " but contact.rolling is NONE: choose CDT or EPSD, or set it to 0");
    if (a < 0 || b < 0) continue;
    if (given[a * nm + b]) check.fail(path, "a second interaction for \"" + in.a() + "\" and \"" + in.b() + "\"");
    const Interaction value{in.restitution(), in.friction(), in.rolling_friction()};
    scene.interactions[a * nm + b] = scene.interactions[b * nm + a] = value;
    given[a * nm + b] = given[b * nm + a] = 1;
  }

  // particles: listed ones first, then lattices, in the order given
  std::set<int> particle_materials;
  auto particle_material = [&](const std::string& name, const std::string& path) {
    const int m = material(name, path);
    if (m >= 0 && scene.materials[m].rigid) {
      check.fail(path, "material \"" + name + "\" is rigid: only walls may use it");
      return -1;
    }
    if (m >= 0) particle_materials.insert(m);
    return m;
  };
  for (int k = 0; k < spec.particles_size(); ++k) {
    const auto& in = spec.particles(k);
    const std::string path = at("particles", k);
    ParticleInit p;
    check.vector(path + ".position", in.position(), kLength);
    check.vector(path + ".velocity", in.velocity(), kSpeed);
    check.vector(path + ".angularVelocity", in.angular_velocity(), kAngularSpeed);
    check.positive(path + ".radius", in.radius(), kRadius);
    p.position = vec(in.position());
    p.velocity = vec(in.velocity());
    p.angular_velocity = vec(in.angular_velocity());
    p.radius = in.radius();
    p.material = particle_material(in.material(), path + ".material");
    p.fixed = in.fixed();
    check.vector(path + ".force", in.force(), kForce);
    p.force = vec(in.force());
    scene.particles.push_back(p);
  }
  for (int k = 0; k < spec.lattices_size(); ++k) {
    const auto& in = spec.lattices(k);
    const std::string path = at("lattices", k);
    const int m = particle_material(in.material(), path + ".material");
    const double spacing = in.spacing() == 0 ? 1.0 : in.spacing();
    check.positive(path + ".radius", in.radius(), kRadius);
    check.in_range(path + ".spacing", spacing, 0.5, 100, true, false);
    check.vector(path + ".min", in.min(), kLength);
    check.vector(path + ".max", in.max(), kLength);
    check.vector(path + ".velocity", in.velocity(), kSpeed);
    const Vec3 lo = vec(in.min()), hi = vec(in.max());
    if (!(lo.array() < hi.array()).all()) {
      check.fail(path + ".max", "must be above min in x, y and z");
      continue;
    }
    if (in.kind() == api::Lattice::KIND_UNSPECIFIED) {
      check.fail(path + ".kind", "must be CUBIC, FCC or HEX");
      continue;
    }
    if (!(in.radius() > 0) || !(spacing > 0.5)) continue;
    const LatticeKind kind = in.kind() == api::Lattice::CUBIC ? LatticeKind::Cubic
                             : in.kind() == api::Lattice::FCC ? LatticeKind::Fcc
                                                              : LatticeKind::Hex;
    if (!check.room(path, scene.particles.size(), lattice_site_bound(kind, lo, hi, in.radius(), spacing))) continue;
    const std::vector<Vec3> sites = lattice_sites(kind, lo, hi, in.radius(), spacing);
    if (sites.empty()) check.fail(path, "the box is too small to hold one particle of radius " + num(in.radius()));
    for (const Vec3& x : sites) {
      ParticleInit p;
      p.position = x;
      p.velocity = vec(in.velocity());
      p.radius = in.radius();
      p.material = m;
      scene.particles.push_back(p);
    }
  }
  for (int k = 0; k < spec.packings_size(); ++k)
    add_packing(spec.packings(k), at("packings", k), base_dir, check, scene,
                particle_material(spec.packings(k).material(), at("packings", k) + ".material"));
  add_clumps(spec, base_dir, check, scene, particle_material);
  for (int k = 0; k < spec.ballast_stones_size(); ++k)
    add_stones(spec.ballast_stones(k), at("ballastStones", k), spec.has_bonds(), check, scene,
               particle_material(spec.ballast_stones(k).material(), at("ballastStones", k) + ".material"));
  if (!scene.clumps.empty() && spec.has_growth() && spec.growth().factor() != 1)
    check.fail("growth", "radius growth and rigid clumps cannot be combined (a clump's shape is fixed)");
  if (spec.particles().empty() && spec.lattices().empty() && spec.packings().empty() && spec.clumps().empty() &&
      spec.ballast_stones().empty())
    check.fail("particles", "the scene has no particles");
  check.room("particles", 0, static_cast<double>(scene.particles.size()));  // clumps' and stones' included

  // walls: refused at once past the limit (300,000 planes in a 24 MB spec took 744 MB and 12 s to
  // check, and every step tests every particle against every plane)
  if (spec.walls_size() > limits.max_walls)
    throw SpecError({"walls: at most " + std::to_string(limits.max_walls) + " walls (got " +
                     std::to_string(spec.walls_size()) + "); a terrain is one mesh wall of many triangles"});
  std::set<int> wall_materials;
  for (int k = 0; k < spec.walls_size(); ++k) {
    const auto& in = spec.walls(k);
    const std::string path = at("walls", k);
    WallInit w;
    w.name = in.name().empty() ? "wall" + std::to_string(k + 1) : in.name();
    w.material = material(in.material(), path + ".material");
    if (w.material >= 0) wall_materials.insert(w.material);
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
      load_mesh(in.mesh(), path + ".mesh", base_dir, check, w);
    } else {
      check.fail(path, "needs a shape: plane, plate or mesh");
    }
    if (in.has_motion() && in.has_load()) check.fail(path, "has both a motion and a load: give one");
    if (in.has_motion()) w.motion = motion(in.motion(), path + ".motion", check);
    if (in.has_load()) w.load = load(in.load(), path + ".load", check);
    scene.walls.push_back(w);
  }

  if (spec.has_growth()) {
    check.in_range("growth.factor", spec.growth().factor(), 1, 3, false, false);
    if (spec.growth().steps() < 1)
      check.fail("growth.steps", "must be >= 1 (got " + std::to_string(spec.growth().steps()) + ")");
    scene.growth = Scene::Growth{spec.growth().factor(), spec.growth().steps()};
  }

  // bonds
  if (spec.has_bonds()) {
    const auto& in = spec.bonds();
    BondSettings b;
    b.model = api::Bonds::Model_Name(in.model());  // the enum's names are the bond models' (bonds/bond_models.hpp)
    b.radius_multiplier = in.radius_multiplier() == 0 ? 1.0 : in.radius_multiplier();
    check.positive("bonds.radiusMultiplier", b.radius_multiplier, kRatio);
    check.positive("bonds.youngsModulus", in.youngs_modulus(), kModulus);
    b.youngs_modulus = in.youngs_modulus();
    b.shear_stiffness_ratio = in.shear_stiffness_ratio() == 0 ? 1.0 : in.shear_stiffness_ratio();
    check.positive("bonds.shearStiffnessRatio", b.shear_stiffness_ratio, kCoefficient);
    check.non_negative("bonds.tensileStrength", in.tensile_strength(), kModulus);
    check.non_negative("bonds.shearStrength", in.shear_strength(), kModulus);
    check.non_negative("bonds.strengthSpread", in.strength_spread(), kCoefficient);
    b.tensile_strength = in.tensile_strength();
    b.shear_strength = in.shear_strength();
    b.strength_spread = in.strength_spread();
    b.seed = in.seed() == 0 ? 1u : in.seed();
    b.gap_tolerance = in.gap_tolerance() == 0 ? 1e-3 : in.gap_tolerance();
    check.positive("bonds.gapTolerance", b.gap_tolerance, kCoefficient);
    if (in.has_region()) {
      check.vector("bonds.region.min", in.region().min(), kLength);
      check.vector("bonds.region.max", in.region().max(), kLength);
      b.region = Box{vec(in.region().min()), vec(in.region().max())};
      if ((b.region->max.array() < b.region->min.array()).any()) check.fail("bonds.region", "max is below min");
    }
    for (int k = 0; k < in.zones_size(); ++k) {
      const auto& z = in.zones(k);
      const std::string path = at("bonds.zones", k);
      check.vector(path + ".min", z.min(), kLength);
      check.vector(path + ".max", z.max(), kLength);
      check.non_negative(path + ".strengthRatio", z.strength_ratio(), kCoefficient);
      b.zones.push_back({Box{vec(z.min()), vec(z.max())}, z.strength_ratio()});
    }
    scene.bonds = b;
  }

  // every pair that can meet needs an interaction
  for (int a : particle_materials) {
    for (int b : particle_materials)
      if (b >= a && !given[a * nm + b])
        check.fail("interactions", "no interaction between \"" + scene.materials[a].name + "\" and \"" +
                                       scene.materials[b].name + "\" (both are particle materials)");
    for (int w : wall_materials)
      if (!given[a * nm + w])
        check.fail("interactions", "no interaction between \"" + scene.materials[a].name + "\" and wall material \"" +
                                       scene.materials[w].name + "\"");
  }

  std::size_t triangles = 0;
  for (const WallInit& w : scene.walls)
    if (const MeshShape* m = std::get_if<MeshShape>(&w.shape)) triangles += m->triangles.size();
  if (static_cast<std::int64_t>(triangles) > limits.max_triangles)
    check.fail("walls", std::to_string(triangles) + " mesh triangles in all, more than the limit of " +
                            std::to_string(limits.max_triangles));

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
  if (t.duration() == 0 && t.steps() == 0) check.fail("time", "give the run's duration (s) or its number of steps");
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
  scene.outputs.length_unit = length_unit(o.length_unit(), check);
  scene.outputs.length_unit_name = o.length_unit().empty() ? "m" : o.length_unit();
  scene.outputs.number_format = o.number_format() == api::Outputs::LEGACY_FIXED ? FileNumberFormat::LegacyFixed
                                : o.number_format() == api::Outputs::FULL       ? FileNumberFormat::Full
                                                                                : FileNumberFormat::Scientific;
  scene.outputs.every_steps = o.every_steps();
  scene.outputs.interval_seconds = o.interval();

  if (spec.has_domain()) {
    // Written into every animation frame header, where a non-finite number cannot be read back.
    check.vector("domain.min", spec.domain().min(), kLength);
    check.vector("domain.max", spec.domain().max(), kLength);
    const Vec3 lo = vec(spec.domain().min()), hi = vec(spec.domain().max());
    if (!(lo.array() < hi.array()).all()) check.fail("domain.max", "must be above domain.min in x, y and z");
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

  if (check.failed()) throw SpecError(check.listed());
  return scene;
}

}  // namespace dem::spec
