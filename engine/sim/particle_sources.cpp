#include "sim/particle_sources.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <unordered_map>

namespace dem {
namespace {

// SplitMix64's output function (Steele, Lea & Flood 2014): a well-mixed 64-bit value of each input,
// so that the n-th random number of a source is a function of its seed and n alone.
std::uint64_t mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Uniform in [0, 1) from the top 53 bits.
double unit(std::uint64_t seed, std::uint64_t n) { return static_cast<double>(mix(mix(seed) ^ n) >> 11) * 0x1.0p-53; }

// Tries this many places for a particle before the batch stops (the region is full for now).
constexpr int kAttempts = 40;
// A face's particle starts this much (of its radius) clear of the face, which must not count as touching.
constexpr double kFaceClearance = 1e-6;

// The particles near the region, binned in cells of the source's largest diameter; larger ones apart.
class NearParticles {
 public:
  explicit NearParticles(double cell) : cell_(cell) {}

  void add(const Vec3& x, double r) {
    if (2 * r > cell_) {
      large_.push_back({x, r});
      return;
    }
    cells_[key(cell_of(x))].push_back({x, r});
  }

  bool overlaps(const Vec3& x, double r) const {
    for (const Ball& b : large_)
      if ((b.x - x).squaredNorm() < (b.r + r) * (b.r + r)) return true;
    const std::array<std::int64_t, 3> c = cell_of(x);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto found = cells_.find(key({c[0] + dx, c[1] + dy, c[2] + dz}));
          if (found == cells_.end()) continue;
          for (const Ball& b : found->second)
            if ((b.x - x).squaredNorm() < (b.r + r) * (b.r + r)) return true;
        }
    return false;
  }

 private:
  struct Ball {
    Vec3 x;
    double r;
  };
  std::array<std::int64_t, 3> cell_of(const Vec3& x) const {
    return {static_cast<std::int64_t>(std::floor(x[0] / cell_)), static_cast<std::int64_t>(std::floor(x[1] / cell_)),
            static_cast<std::int64_t>(std::floor(x[2] / cell_))};
  }
  // 21 bits per axis: cells of one region never wrap into each other (the spec bounds a region's cells)
  static std::int64_t key(const std::array<std::int64_t, 3>& c) {
    constexpr std::int64_t mask = (std::int64_t{1} << 21) - 1;
    return (c[0] & mask) | ((c[1] & mask) << 21) | ((c[2] & mask) << 42);
  }
  double cell_;
  std::unordered_map<std::int64_t, std::vector<Ball>> cells_;
  std::vector<Ball> large_;
};

// The side of face f the particles go to: the velocity's, or the face's normal when they move along it.
Vec3 side_of(const Face& f, const Vec3& velocity) {
  const Vec3 n = (f[1] - f[0]).cross(f[2] - f[0]).normalized();
  return velocity.dot(n) < -1e-12 * velocity.norm() ? Vec3(-n) : n;
}

}  // namespace

double source_radius(const ParticleSource& source, std::int64_t k) {
  if (source.sizes.kind == SizeKind::One) return source.sizes.mean / 2;
  std::mt19937_64 rng(mix(source.seed) ^ mix(static_cast<std::uint64_t>(k) + 0x5851f42d4c957f2dULL));
  return sample_diameters(source.sizes, 1, rng)[0] / 2;
}

std::vector<ParticleInit> source_extremes(const Scene& scene, const ParticleSource& source) {
  Vec3 lo = source.box.min, hi = source.box.max;
  if (source.region == ParticleSource::Region::Face) {
    const WallInit& wall = scene.walls[source.face_wall];
    lo = Vec3::Constant(1e300);
    hi = -lo;
    auto include = [&](const Vec3& x) {
      lo = lo.cwiseMin(x - Vec3::Constant(source.depth));
      hi = hi.cwiseMax(x + Vec3::Constant(source.depth));
    };
    if (const auto* plate = std::get_if<PlateShape>(&wall.shape))
      for (const Vec3& c : plate->corners) include(c);
    if (const auto* mesh = std::get_if<MeshShape>(&wall.shape))
      for (const Vec3& v : mesh->vertices) include(v);
  }
  ParticleInit smallest, largest;
  smallest.radius = smallest_diameter(source.sizes) / 2;
  largest.radius = largest_diameter(source.sizes) / 2;
  smallest.position = lo + Vec3::Constant(smallest.radius);
  largest.position = hi - Vec3::Constant(largest.radius);
  for (ParticleInit* p : {&smallest, &largest}) {
    p->material = source.material;
    p->velocity = source.velocity;
    if (scene.plane) p->position.y() = 0;  // a 2D run's discs lie in y = 0
  }
  return {smallest, largest};
}

namespace {

// Whether the next particle, of mass `next`, is still within the source's total (to the nearest
// particle: it may pass a mass total by half itself).
bool within_total(const ParticleSource& source, const SourceProgress& progress, double next) {
  return progress.mass + next / 2 <= source.total_mass &&
         (source.total_count < 0 || progress.inserted < source.total_count);
}

}  // namespace

std::optional<bool> total_reached(const Scene& scene, const ParticleSource& source, const SourceProgress& progress) {
  if (source.total_count < 0 && !std::isfinite(source.total_mass)) return std::nullopt;
  const double next =
      scene.grain().mass(scene.materials[source.material].density, source_radius(source, progress.inserted));
  return !within_total(source, progress, next);
}

std::vector<ParticleInit> due_particles(const Scene& scene, const ParticleSource& source, SourceProgress& progress,
                                        double next_radius, double active, const Particles& existing,
                                        const FacesNow& faces_now, const WallTest& touches_wall) {
  std::vector<ParticleInit> out;
  const double density = scene.materials[source.material].density;
  double r = next_radius;
  double m = scene.grain().mass(density, r);
  // rate times time to the nearest particle: within half a particle of it
  auto owed = [&] {
    return within_total(source, progress, m) &&
           (source.mass_rate > 0 ? progress.mass + m / 2 <= source.mass_rate * active
                                 : static_cast<double>(progress.inserted) + 0.5 <= source.count_rate * active);
  };
  if (!owed()) return out;

  // The region's box, and the faces' areas (a place on them is drawn by area).
  const bool on_faces = source.region == ParticleSource::Region::Face;
  Vec3 lo = source.box.min, hi = source.box.max;
  std::vector<double> area_below;  // cumulative
  std::vector<Vec3> side;
  const std::vector<Face> faces = on_faces ? faces_now() : std::vector<Face>{};
  if (on_faces) {
    // where the particles can be: over the faces, as far out as the layer or a largest diameter
    // (a layer thinner than a particle still holds it, at its radius off the face), a radius wide
    const double r_max = largest_diameter(source.sizes) / 2;
    const double out_to = std::max(source.depth, 2 * r_max);
    lo = Vec3::Constant(1e300);
    hi = -lo;
    double total = 0;
    for (const Face& f : faces) {
      side.push_back(side_of(f, source.velocity));
      total += 0.5 * (f[1] - f[0]).cross(f[2] - f[0]).norm();
      area_below.push_back(total);
      for (const Vec3& x : f) {
        lo = lo.cwiseMin(x.cwiseMin(x + side.back() * out_to));
        hi = hi.cwiseMax(x.cwiseMax(x + side.back() * out_to));
      }
    }
    lo -= Vec3::Constant(r_max);
    hi += Vec3::Constant(r_max);
    if (faces.empty() || !(total > 0)) return out;
  }
  NearParticles near(largest_diameter(source.sizes));
  for (std::size_t j = 0; j < existing.size(); ++j) {
    const Vec3 reach = Vec3::Constant(existing.radius[j]);
    if ((existing.x[j].array() >= (lo - reach).array()).all() && (existing.x[j].array() <= (hi + reach).array()).all())
      near.add(existing.x[j], existing.radius[j]);
  }
  auto next_unit = [&] { return unit(source.seed, progress.draws++); };
  auto draw_place = [&](double radius) -> Vec3 {
    if (!on_faces) {
      Vec3 x;
      for (int d = 0; d < 3; ++d) {
        if (d == 1 && scene.plane) {  // a 2D run's discs lie in y = 0
          x[d] = 0;
          continue;
        }
        const double room = std::max(0.0, hi[d] - lo[d] - 2 * radius);
        x[d] = lo[d] + radius + next_unit() * room;
      }
      return x;
    }
    const double pick = next_unit() * area_below.back();
    const std::size_t f = std::min<std::size_t>(
        faces.size() - 1, std::upper_bound(area_below.begin(), area_below.end(), pick) - area_below.begin());
    // uniform on the triangle (Osada et al. 2002, eq. 1)
    const double s = std::sqrt(next_unit()), t = next_unit();
    const Vec3 on = (1 - s) * faces[f][0] + s * (1 - t) * faces[f][1] + s * t * faces[f][2];
    const double clear = radius * (1 + kFaceClearance);
    return on + side[f] * (clear + next_unit() * std::max(0.0, source.depth - 2 * clear));
  };
  while (owed()) {
    bool placed = false;
    for (int attempt = 0; attempt < kAttempts && !placed; ++attempt) {
      const Vec3 x = draw_place(r);
      if (near.overlaps(x, r) || touches_wall(x, r)) continue;
      ParticleInit p;
      p.position = x;
      p.velocity = source.velocity;
      p.radius = r;
      p.material = source.material;
      out.push_back(p);
      near.add(x, r);
      placed = true;
    }
    if (!placed) {
      ++progress.crowded_batches;
      break;
    }
    ++progress.inserted;
    progress.mass += m;
    r = source_radius(source, progress.inserted);
    m = scene.grain().mass(density, r);
  }
  return out;
}

}  // namespace dem
