#include "sim/time_step.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <set>

#include <Eigen/Eigenvalues>

#include "bonds/bond_models.hpp"
#include "core/errors.hpp"

namespace dem {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Smallest {
  double mass = kInf;
  double radius = kInf;
};

// The corners of a plate or the vertices of a mesh (none for a plane).
std::vector<Vec3> wall_points(const WallInit& w) {
  if (const auto* plate = std::get_if<PlateShape>(&w.shape)) return {plate->corners.begin(), plate->corners.end()};
  if (const auto* mesh = std::get_if<MeshShape>(&w.shape)) return mesh->vertices;
  return {};
}

// A characteristic impact speed: twice the fastest initial particle or wall, or a free fall from
// the top of the particle cloud to the lowest body below it (a particle or a wall), or what a
// particle's constant force (with gravity) gives it from rest across the whole scene.
double reference_speed(const Scene& scene) {
  double v0 = 0;
  const double g = scene.gravity.norm();
  const Vec3 down = g > 0 ? Vec3(scene.gravity / g) : Vec3::Zero();
  double top = -kInf, bottom = kInf;
  Vec3 lo = Vec3::Constant(kInf), hi = Vec3::Constant(-kInf);  // the scene's extent
  for (const ParticleInit& p : scene.particles) {
    v0 = std::max(v0, p.velocity.norm());
    top = std::max(top, -p.position.dot(down));
    bottom = std::min(bottom, -p.position.dot(down));
    lo = lo.cwiseMin(p.position - Vec3::Constant(p.radius));
    hi = hi.cwiseMax(p.position + Vec3::Constant(p.radius));
  }
  for (const WallInit& w : scene.walls)
    for (const Vec3& x : wall_points(w)) {
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
  const double extent = (hi - lo).allFinite() ? (hi - lo).norm() : 0;
  double pushed = 0;
  for (const ParticleInit& p : scene.particles) {
    if (p.force.isZero(0) || p.fixed) continue;
    const double mass = scene.grain().mass(scene.materials[p.material].density, p.radius);
    pushed = std::max(pushed, std::sqrt(2 * (scene.gravity + p.force / mass).norm() * extent));
  }
  for (const WallInit& w : scene.walls) {
    if (w.motion || w.load) v0 = std::max(v0, fastest_wall_speed(scene, w));
    if (const auto* plate = std::get_if<PlateShape>(&w.shape)) {
      for (const Vec3& c : plate->corners) bottom = std::min(bottom, -c.dot(down));
    } else if (const auto* mesh = std::get_if<MeshShape>(&w.shape)) {
      for (const Vec3& v : mesh->vertices) bottom = std::min(bottom, -v.dot(down));
    } else if (const auto* plane = std::get_if<PlaneShape>(&w.shape)) {
      // height of the plane below each particle, along the vertical
      const double facing = -down.dot(plane->normal);
      if (facing <= 0) continue;
      for (const ParticleInit& p : scene.particles)
        bottom = std::min(bottom, -p.position.dot(down) - (p.position - plane->point).dot(plane->normal) / facing);
    }
  }
  double fall = 0;
  if (g > 0 && top > bottom) fall = std::sqrt(2 * g * (top - bottom));
  return std::max({2 * v0, fall, pushed, 0.1});
}

}  // namespace

double fastest_wall_speed(const Scene& scene, const WallInit& w) {
  double speed = 0;
  if (w.motion) {
    const PrescribedMotion& m = *w.motion;
    speed = m.velocity.norm() + m.amplitude.norm();
    const double spin = m.angular_velocity.norm();
    if (spin > 0) {
      const std::vector<Vec3> points = wall_points(w);
      Vec3 centre = Vec3::Zero();
      if (m.center)
        centre = *m.center;
      else if (!points.empty()) {
        for (const Vec3& x : points) centre += x;
        centre /= static_cast<double>(points.size());
      } else if (const auto* plane = std::get_if<PlaneShape>(&w.shape)) {
        centre = plane->point;
      }
      double reach = 0;
      for (const Vec3& x : points) reach = std::max(reach, (x - centre).norm());
      for (const ParticleInit& p : scene.particles) reach = std::max(reach, (p.position - centre).norm() + p.radius);
      speed += spin * reach;
    }
  }
  if (w.load && w.load->kind == LoadControl::Kind::Servo) speed = std::max(speed, w.load->max_speed);
  return speed;
}

std::string TimeStepReport::describe() const {
  char buf[320];
  std::snprintf(buf, sizeof buf, "dt = %.6e s (%s); shortest contact time %.6e s", dt,
                automatic ? "automatic" : "given", contact_time);
  std::string s = buf;
  if (rayleigh_time > 0) {
    std::snprintf(buf, sizeof buf, " at %.3g m/s; Rayleigh time %.6e s", reference_speed, rayleigh_time);
    s += buf;
  }
  if (bond_time > 0) {
    std::snprintf(buf, sizeof buf, "; shortest bond time %.6e s", bond_time);
    s += buf;
  }
  std::snprintf(buf, sizeof buf, "; stable limit %.6e s", stable_limit);
  return s + buf;
}

namespace {

// The mass a contact on this sphere moves. A free sphere: its own. A clump member: the body's
// effective mass at the member, 1 / (1/M + (a x n)^T I^-1 (a x n)) for arm a from the centroid and
// contact normal n, at its smallest over all n: 1 / (1/M + the largest eigenvalue of
// [a]x^T I^-1 [a]x) (the rigid-body impact mass, e.g. Brach, Mechanical Impact Dynamics, ch. 3).
// Member spheres overlap, so their own mass would understate the body's several times over.
double contact_mass(const Scene& scene, const ParticleInit& p) {
  const double own = scene.grain().mass(scene.materials[p.material].density, p.radius);
  if (p.clump < 0) return own;
  const ClumpInit& c = scene.clumps[p.clump];
  const Vec3 arm = c.orientation.conjugate() * (p.position - c.position);  // in the principal frame
  Eigen::Matrix3d cross;
  cross << 0, -arm.z(), arm.y(), arm.z(), 0, -arm.x(), -arm.y(), arm.x(), 0;
  const Eigen::Matrix3d turning = cross.transpose() * c.moments.cwiseInverse().asDiagonal() * cross;
  const double largest =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(turning, Eigen::EigenvaluesOnly).eigenvalues()[2];
  return 1.0 / (1.0 / c.mass + largest);
}

// A wall moved by a cyclic load is a body of mass M: a contact on it moves m M / (m + M), and a
// wall much lighter than the particles it presses rings on their contacts faster than the step
// resolves. The step is the particles' (a plate added to a settled bed keeps the bed's step, as a
// continued run needs); a wall too light for it is refused, with the mass it would need. A plate of
// 1e-6 kg on spheres of 2e-3 kg once ran 938 steps and was stopped, its load "driving it faster
// than the time step resolves" (an independent tester).
void refuse_light_loaded_walls(const Scene& scene, const ForceKernel& kernel, const std::vector<Smallest>& smallest,
                               const TimeStepReport& r) {
  for (std::size_t k = 0; k < scene.walls.size(); ++k) {
    const WallInit& w = scene.walls[k];
    if (!w.load || w.load->kind != LoadControl::Kind::Cyclic || !(w.load->mass > 0)) continue;
    // The least mass that resolves the contact with every material's smallest particle: named for the
    // one that needs the most (named for the first that failed, it was refused again for the next).
    int worst = -1;
    double least_mass = 0;
    // the reduced mass, and the contact time, of material a's smallest particle on the wall of mass `mass`
    auto reduced_mass = [&](int a, double mass) { return smallest[a].mass * mass / (smallest[a].mass + mass); };
    auto time_with = [&](int a, double mass) {
      return kernel.contact_time(a, w.material, reduced_mass(a, mass), smallest[a].radius, r.reference_speed);
    };
    for (int a = 0; a < static_cast<int>(smallest.size()); ++a) {
      if (smallest[a].mass == kInf) continue;
      const double m = smallest[a].mass, rad = smallest[a].radius;
      // Resolved: 10 steps in its contact (the stable limit's rule), or as many, within 1e-3, as the
      // particles' contact with the same wall held still (part of the step's choice): at the largest
      // dtFraction, 0.1, that contact has exactly 10 steps, and a wall of any finite mass fell short
      // of them (a 2 kg plate on 0.1 g spheres was refused, "give the wall at least 1 kg").
      const double held_still = kernel.contact_time(a, w.material, m, rad, r.reference_speed);
      const double needed = std::min(10 * r.dt / (1 + 1e-6), (1 - 1e-3) * held_still);
      if (time_with(a, w.load->mass) >= needed) continue;
      double lo = w.load->mass, hi = std::max(1.0, 1e3 * m);  // the lightest mass that passes
      for (int tries = 0; tries < 60 && time_with(a, hi) < needed; ++tries) hi *= 10;
      while (hi / lo > 1 + 1e-6) {
        const double mid = std::sqrt(lo * hi);
        (time_with(a, mid) >= needed ? hi : lo) = mid;
      }
      if (hi > least_mass) least_mass = hi, worst = a;
    }
    if (worst < 0) continue;
    const double m = smallest[worst].mass;
    const double m_star = reduced_mass(worst, w.load->mass);
    const double t = time_with(worst, w.load->mass);
    // rounded up to the three digits printed: the mass as printed passes (rounded to nearest, it was
    // refused again when given)
    const double unit = std::pow(10.0, std::floor(std::log10(least_mass)) - 2);
    const double printed = std::ceil(least_mass / unit) * unit;
    char buf[600];
    std::snprintf(buf, sizeof buf,
                  "%s.load.mass: %.6g kg is too light for the time step: on a contact with a %.3g kg "
                  "particle it moves %.3g kg, a contact of %.3e s, which the step of %.6e s does not resolve (10 "
                  "steps at least, or as many as with the wall held still); give the wall a mass of at least %.3g "
                  "kg, or a smaller %s",
                  w.where(k).c_str(), w.load->mass, m, m_star, t, r.dt, printed,
                  scene.time.dt > 0 ? "time.dt" : "time.dtFraction");
    throw SceneError(buf);
  }
}

}  // namespace

TimeStepReport choose_time_step(const Scene& scene, const ForceKernel& kernel, bool bonded, double release_speed) {
  const int materials = static_cast<int>(scene.materials.size());
  std::vector<Smallest> smallest(materials);
  for (const ParticleInit& p : scene.particles) {
    const double m = contact_mass(scene, p);
    smallest[p.material].mass = std::min(smallest[p.material].mass, m);
    smallest[p.material].radius = std::min(smallest[p.material].radius, p.radius);
  }
  std::set<int> wall_materials;
  for (const WallInit& w : scene.walls) wall_materials.insert(w.material);

  TimeStepReport r;
  // Spheres released from an initial overlap reach sqrt(2 U / m*): a Hertz release taken at the
  // initial velocities' speed had 13 steps and lost 1.2e-3 of its energy.
  if (kernel.contact_time_needs_speed())
    r.reference_speed = std::max(reference_speed(scene), std::isfinite(release_speed) ? release_speed : 0.0);
  double t_min = kInf, rayleigh_min = kInf;
  for (int a = 0; a < materials; ++a) {
    if (smallest[a].mass == kInf) continue;
    auto consider = [&](int b, double m_eff, double r_eff) {
      t_min = std::min(t_min, kernel.contact_time(a, b, m_eff, r_eff, r.reference_speed));
    };
    for (int b = 0; b < materials; ++b) {
      if (smallest[b].mass == kInf) continue;
      const Smallest& sa = smallest[a];
      const Smallest& sb = smallest[b];
      consider(b, sa.mass * sb.mass / (sa.mass + sb.mass), sa.radius * sb.radius / (sa.radius + sb.radius));
    }
    for (int w : wall_materials) consider(w, smallest[a].mass, smallest[a].radius);
    rayleigh_min = std::min(rayleigh_min, kernel.wave_time(scene.materials[a], smallest[a].radius));
  }
  if (bonded && scene.bonds && scene.bonds->youngs_modulus > 0) {
    // A bond between two of the smallest spheres is the stiffest per unit mass (the bond model says
    // how short its springs' periods are: bonds/bond_models.hpp).
    double t_bond = kInf;
    for (int a = 0; a < materials; ++a)
      if (smallest[a].mass != kInf)
        t_bond = std::min(t_bond, bond_shortest_time(*scene.bonds, smallest[a].radius, smallest[a].mass));
    if (t_bond < kInf) r.bond_time = t_bond;
  }
  if (t_min == kInf) t_min = 1.0;  // nothing can touch: any step resolves the free flight
  r.contact_time = t_min;
  if (r.bond_time > 0) t_min = std::min(t_min, r.bond_time);  // the step resolves bonds and contacts
  r.rayleigh_time = rayleigh_min < kInf ? rayleigh_min : 0;
  // Fewer than 10 steps per contact does not resolve it; past ~t_c/3 velocity Verlet is unstable.
  // A law with a wave time (Hertz: Rayleigh) is held to it too (infinite otherwise).
  r.stable_limit = std::min(t_min / 10, rayleigh_min);
  const double automatic = std::min(scene.time.dt_fraction * t_min, 0.2 * rayleigh_min);
  if (scene.time.dt > 0) {
    r.automatic = false;
    r.dt = scene.time.dt;
    // a step at the limit as printed (7 digits) or computed another way is at the limit
    if (r.dt > r.stable_limit * (1 + 1e-6) && !scene.time.allow_unstable_dt) {
      char buf[400];
      std::snprintf(buf, sizeof buf,
                    "time.dt: %.6e s is above the stable limit %.6e s (shortest contact time %.6e s / 10); "
                    "use a smaller dt, leave dt at 0 for an automatic one, or set time.allowUnstableDt",
                    r.dt, r.stable_limit, t_min);
      throw SceneError(buf);
    }
  } else {
    r.dt = automatic;
  }
  if (!scene.time.allow_unstable_dt) refuse_light_loaded_walls(scene, kernel, smallest, r);
  return r;
}

}  // namespace dem
