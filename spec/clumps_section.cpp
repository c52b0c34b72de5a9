// Rigid clumps (JobSpec.clumpShapes, .clumps) and BallastDEM's stones (JobSpec.ballastStones).
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>
#include <numbers>

#include "clumps/mass_properties.hpp"
#include "spec/ballast_stones.hpp"
#include "spec/clump_template.hpp"
#include "spec/defaults.hpp"
#include "spec/referenced_files.hpp"
#include "spec/section_loaders.hpp"

namespace dem::spec {
namespace {

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
// shape's accuracy, or as given. A shape no clump uses is checked but not integrated (`used`).
ClumpBody clump_body(const api::ClumpShape& in, const std::string& path, const std::string& base_dir, bool used,
                     Checker& check) {
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
  const double scale = in.scale() == 0 ? defaults::kClumpScale : in.scale();
  check.positive(path + ".scale", scale);
  const double accuracy = in.accuracy() == 0 ? defaults::kClumpAccuracy : in.accuracy();
  constexpr double kFinest = 1e-5, kCoarsest = 0.1;  // finer is past the subdivision's 2^11 cells
  const bool accuracy_ok = accuracy >= kFinest && accuracy <= kCoarsest;
  check.in_range(path + ".accuracy", accuracy, kFinest, kCoarsest, false, false);
  for (MemberSphere& m : spheres) {
    m.centre *= scale;
    m.radius *= scale;
  }
  if (scale > 0 && std::isfinite(scale))  // the radii a spec may give, after the scale too (the first one off)
    for (std::size_t s = 0; s < spheres.size(); ++s) {
      const double r = spheres[s].radius;
      if (!(r > 0) || (r <= kRadius.max && r >= kRadius.min)) continue;
      char radius[32];
      std::snprintf(radius, sizeof radius, "%.3g", r);
      check.fail(path + ".scale",
                 "makes the radius of sphere " + std::to_string(s + 1) + " " + radius + " m: must be " +
                     (r > kRadius.max ? "at most " + num(kRadius.max) : "at least " + num(kRadius.min)) + " m");
      break;
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
  if (!accuracy_ok || !used) return body;
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
}  // namespace

void load_clumps(const api::JobSpec& spec, SpecContext& ctx) {
  Checker& check = ctx.check;
  Scene& scene = ctx.scene;
  std::map<std::string, int> shape_index;
  std::vector<ClumpBody> bodies;
  std::set<std::string> used;
  for (const api::Clump& clump : spec.clumps()) used.insert(clump.shape());
  for (int k = 0; k < spec.clump_shapes_size(); ++k) {
    const api::ClumpShape& in = spec.clump_shapes(k);
    const std::string path = "clumpShapes[" + std::to_string(k) + "]";
    if (in.name().empty())
      check.fail(path + ".name", "a clump shape needs a name");
    else if (!shape_index.emplace(in.name(), k).second)
      check.fail(path + ".name", "\"" + in.name() + "\" is given twice");
    bodies.push_back(clump_body(in, path, ctx.base_dir, used.count(in.name()) > 0, check));
  }
  for (int k = 0; k < spec.clumps_size(); ++k) {
    const api::Clump& in = spec.clumps(k);
    const std::string path = "clumps[" + std::to_string(k) + "]";
    const auto shape = shape_index.find(in.shape());
    if (shape == shape_index.end()) {
      check.fail(path + ".shape", "unknown clump shape \"" + in.shape() + "\"");
      continue;
    }
    const int material = ctx.particle_material(in.material(), path + ".material");
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
namespace {

void add_stones(const api::BallastStones& in, const std::string& path, bool has_bonds, Checker& check, Scene& scene,
                int material) {
  StoneRequest r;
  r.count = in.count();
  r.log_mean = in.mass_log_mean();
  r.log_sigma = in.mass_log_sigma();
  r.mass_min = in.mass_min();
  r.mass_max = in.mass_max();
  r.min_spheres = in.min_spheres() == 0 ? defaults::kStoneMinSpheres : in.min_spheres();
  r.max_spheres = in.max_spheres() == 0 ? std::max(defaults::kStoneMaxSpheresAtLeast, r.min_spheres) : in.max_spheres();
  r.shapes = in.shapes() == 0 ? defaults::kStoneShapes : in.shapes();
  r.lo = vec(in.min());
  r.hi = vec(in.max());
  r.seed = in.seed() == 0 ? defaults::kSeed : in.seed();
  check.in_range(path + ".count", r.count, 1, 1e6, false, false);
  if (!std::isfinite(r.log_mean)) check.fail(path + ".massLogMean", "must be a finite number");
  check.non_negative(path + ".massLogSigma", r.log_sigma);
  check.positive(path + ".massMin", r.mass_min);
  check.vector(path + ".min", in.min(), kLength);
  check.vector(path + ".max", in.max(), kLength);
  if (!std::isfinite(r.mass_max))
    check.fail(path + ".massMax", "must be a finite number (got " + num(r.mass_max) + ")");
  else if (!(r.mass_max > r.mass_min))
    check.fail(path + ".massMax", "must be above massMin (got " + num(r.mass_max) + ")");
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

}  // namespace

void load_stones(const api::JobSpec& spec, SpecContext& ctx) {
  for (int k = 0; k < spec.ballast_stones_size(); ++k)
    add_stones(spec.ballast_stones(k), at("ballastStones", k), spec.has_bonds(), ctx.check, ctx.scene,
               ctx.particle_material(spec.ballast_stones(k).material(), at("ballastStones", k) + ".material"));
}

}  // namespace dem::spec
