#include "spec/ballast_stones.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Geometry>

#include "clumps/mass_properties.hpp"
#include "core/parallel.hpp"
#include "spec/stone_fill.hpp"

namespace dem::spec {
namespace {

// A stone's shape at unit scale: spheres about its centroid in its principal frame.
struct StoneShape {
  std::vector<MemberSphere> spheres;
  double volume = 0;
  Vec3 moments = Vec3::Zero();  // principal, density 1
  double reach = 0;             // the bounding sphere's radius about the centroid
};

Vec3 random_direction(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0, 1);
  Vec3 d;
  do d = Vec3(n(rng), n(rng), n(rng));
  while (d.squaredNorm() < 1e-12);
  return d.normalized();
}

// Spheres grown one at a time, each overlapping a random earlier one (so the stone is one piece),
// radii 0.5..1 of the first: irregular, elongated or flat at random.
std::vector<MemberSphere> random_spheres(int spheres, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<MemberSphere> s{{Vec3::Zero(), 1.0}};
  while (static_cast<int>(s.size()) < spheres) {
    const MemberSphere& base = s[static_cast<std::size_t>(u(rng) * static_cast<double>(s.size())) % s.size()];
    const double r = 0.5 + 0.5 * u(rng);
    const double distance = (base.radius + r) * (0.3 + 0.4 * u(rng));  // always overlapping
    s.push_back({base.centre + distance * random_direction(rng), r});
  }
  return s;
}

// The stone of those spheres: its mass properties (the set-up's costliest work) and its frame.
StoneShape shape_of(const std::vector<MemberSphere>& s) {
  const MassProperties mp = union_mass_properties(s, 1e-3);
  StoneShape shape;
  shape.volume = mp.volume;
  shape.moments = mp.principal_moments;
  for (const MemberSphere& m : s) {
    const Vec3 c = mp.principal_axes.transpose() * (m.centre - mp.centroid);
    shape.spheres.push_back({c, m.radius});
    shape.reach = std::max(shape.reach, c.norm() + m.radius);
  }
  return shape;
}

// A breakable stone of mass `mass`: the shape scaled until the small spheres that fill it weigh
// `mass`. The filled solid fraction (~0.6-0.7) depends on the shape and the scale, and the count of
// spheres is a step function of the scale, so the scale is found by bisection, keeping the closest.
struct FilledStone {
  std::vector<Vec3> centres;
  double scale = 0;
};

FilledStone fill_stone(const StoneShape& shape, double mass, double density, double r) {
  const double sphere_mass = density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  FilledStone best;
  double best_error = 0;
  auto weigh = [&](double scale) {  // the filled mass at this scale; remembers the closest
    std::vector<MemberSphere> scaled = shape.spheres;
    for (MemberSphere& m : scaled) {
      m.centre *= scale;
      m.radius *= scale;
    }
    std::vector<Vec3> centres = fill_with_spheres(scaled, r);
    const double got = sphere_mass * static_cast<double>(centres.size());
    if (best.centres.empty() || std::abs(got - mass) < best_error) {
      best = {std::move(centres), scale};
      best_error = std::abs(got - mass);
    }
    return got;
  };
  const double guess = std::cbrt(mass / (0.65 * density * shape.volume));
  double lo = 0.8 * guess, hi = 1.25 * guess;
  while (weigh(lo) > mass && lo > 1e-3 * guess) lo *= 0.8;
  while (weigh(hi) < mass && hi < 1e3 * guess) hi *= 1.25;
  for (int k = 0; k < 40 && best_error > 0.5 * sphere_mass; ++k) {
    const double mid = 0.5 * (lo + hi);
    (weigh(mid) < mass ? lo : hi) = mid;
  }
  return best;
}

}  // namespace

std::vector<double> sample_stone_masses(const StoneRequest& r, std::mt19937_64& rng) {
  if (r.log_sigma == 0) return std::vector<double>(r.count, std::exp(r.log_mean));  // one mass (checked in bounds)
  std::normal_distribution<double> log_mass(r.log_mean, r.log_sigma);
  std::vector<double> masses;
  while (static_cast<int>(masses.size()) < r.count) {
    const double m = std::exp(log_mass(rng));
    if (m >= r.mass_min && m <= r.mass_max) masses.push_back(m);  // the bounded distribution
  }
  return masses;
}

void add_ballast_stones(const StoneRequest& r, Scene& scene) {
  std::mt19937_64 rng(r.seed);
  std::uniform_int_distribution<int> size(r.min_spheres, r.max_spheres);
  std::vector<StoneShape> shapes;
  std::vector<std::vector<MemberSphere>> spheres;  // drawn in order: the random stream stays the same
  spheres.reserve(static_cast<std::size_t>(r.shapes));
  for (int k = 0; k < r.shapes; ++k) spheres.push_back(random_spheres(size(rng), rng));
  shapes.resize(spheres.size());
  for_ranges(r.shapes, 2, [&](int begin, int end) {  // independent shapes: on every thread
    for (int k = begin; k < end; ++k) shapes[k] = shape_of(spheres[k]);
  });
  const std::vector<double> masses = sample_stone_masses(r, rng);
  std::uniform_int_distribution<int> pick(0, r.shapes - 1);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::pair<Vec3, double>> placed;  // bounding spheres of the stones placed
  int next_stone = 0;  // breakable stones are numbered across the scene: bonds glue only within one
  for (const ParticleInit& p : scene.particles) next_stone = std::max(next_stone, p.stone + 1);
  for (int s = 0; s < r.count; ++s) {
    const StoneShape& shape = shapes[pick(rng)];
    const bool breakable = r.bonded_sphere_radius > 0;
    FilledStone filled;
    if (breakable) {
      filled = fill_stone(shape, masses[s], r.density, r.bonded_sphere_radius);
      if (filled.centres.size() < 2)
        throw std::runtime_error("a stone of " + std::to_string(masses[s]) +
                                 " kg holds fewer than 2 bonded spheres of radius " +
                                 std::to_string(r.bonded_sphere_radius) + " m: make bonded.sphereRadius smaller");
    }
    const double scale = breakable ? filled.scale : std::cbrt(masses[s] / (r.density * shape.volume));
    // a filled stone's spheres have their centres inside the shape: they reach one radius further
    const double reach = scale * shape.reach + (breakable ? r.bonded_sphere_radius : 0.0);
    // random sequential addition of the bounding spheres, each wholly inside the box
    Vec3 at;
    bool fits = false;
    for (int attempt = 0; attempt < 2000 && !fits; ++attempt) {
      for (int d = 0; d < 3; ++d) at[d] = r.lo[d] + reach + u(rng) * std::max(0.0, r.hi[d] - r.lo[d] - 2 * reach);
      fits = (r.hi - r.lo).minCoeff() >= 2 * reach;
      for (const auto& [c, q] : placed)
        if (fits && (c - at).squaredNorm() < (q + reach) * (q + reach)) fits = false;
    }
    if (!fits)
      throw std::runtime_error("only " + std::to_string(s) + " of " + std::to_string(r.count) +
                               " stones fit in the box without overlap: enlarge it or ask for fewer");
    placed.emplace_back(at, reach);
    // uniform over rotations: a quaternion of four normal deviates, normalised (from the seeded rng)
    std::normal_distribution<double> n(0, 1);
    const Eigen::Quaterniond turn = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
    if (breakable) {
      for (const Vec3& centre : filled.centres) {
        ParticleInit p;
        p.position = at + turn * centre;
        p.radius = r.bonded_sphere_radius;
        p.material = r.material;
        p.stone = next_stone;
        scene.particles.push_back(p);
      }
      ++next_stone;
      continue;
    }
    ClumpInit c;
    c.first = static_cast<int>(scene.particles.size());
    c.count = static_cast<int>(shape.spheres.size());
    c.mass = masses[s];
    c.moments = r.density * std::pow(scale, 5) * shape.moments;
    c.position = at;
    c.orientation = turn;
    for (const MemberSphere& m : shape.spheres) {
      ParticleInit p;
      p.position = at + turn * (scale * m.centre);
      p.radius = scale * m.radius;
      p.material = r.material;
      p.clump = static_cast<int>(scene.clumps.size());
      scene.particles.push_back(p);
    }
    scene.clumps.push_back(c);
  }
}

}  // namespace dem::spec
