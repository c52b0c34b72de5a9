// The particles a scene starts with: listed ones, lattices and random packings, in that order
// (JobSpec.particles, .lattices, .packings); clumps and stones follow (clumps_section.cpp).
#include <algorithm>
#include <array>
#include <functional>
#include <map>
#include <utility>
#include <numbers>
#include <random>

#include "spec/defaults.hpp"
#include "spec/inside_mesh.hpp"
#include "spec/lattice.hpp"
#include "spec/packing.hpp"
#include "spec/section_loaders.hpp"

namespace dem::spec {
namespace {

// A closed mesh to fill (the key block's funnel), and the volume it encloses.
struct Region {
  ClosedMesh mesh;
  double volume;
};

std::optional<Region> load_region(const api::Mesh& in, const std::string& path, SpecContext& ctx) {
  const std::optional<MeshShape> placed = load_mesh(in, path, ctx);
  if (!placed) return std::nullopt;
  // inside and outside mean something only for a closed surface: every edge shared by two faces
  std::map<std::pair<int, int>, int> faces_of_edge;
  for (const auto& t : placed->triangles)
    for (int e = 0; e < 3; ++e) ++faces_of_edge[std::minmax(t[e], t[(e + 1) % 3])];
  for (const auto& [edge, faces] : faces_of_edge)
    if (faces % 2 != 0) {
      ctx.check.fail(path, "is not a closed surface: the edge between vertices " + std::to_string(edge.first + 1) +
                               " and " + std::to_string(edge.second + 1) + " belongs to " + std::to_string(faces) +
                               " triangle(s) (every edge of a closed mesh belongs to two, or an even number)");
      return std::nullopt;
    }
  double six_v = 0;  // the enclosed volume by the divergence theorem: signed tetrahedra from the origin
  for (const auto& t : placed->triangles)
    six_v += placed->vertices[t[0]].dot(placed->vertices[t[1]].cross(placed->vertices[t[2]]));
  return Region{ClosedMesh(*placed), std::abs(six_v) / 6};
}

// max above min in x, y and z (in 2D, x and z: the discs lie at y = 0 whatever the box's y range).
bool check_box_order(const std::string& path, const Vec3& lo, const Vec3& hi, bool planar, Checker& check) {
  const bool ordered = lo.x() < hi.x() && lo.z() < hi.z() && (planar || lo.y() < hi.y());
  if (!ordered) check.fail(path, planar ? "must be above min in x and z" : "must be above min in x, y and z");
  return ordered;
}

}  // namespace

// Diameters (the manuals' IPATTERN), checked at `sp`.
SizeDistribution load_sizes(const api::SizeDistribution& sz, const std::string& sp, Checker& check) {
  SizeDistribution d;
  if (!api::SizeDistribution::Kind_IsValid(sz.kind())) {  // an open enum keeps any number given
    check.fail(sp + ".kind", "must be ONE_SIZE, TWO_SIZES, UNIFORM, NORMAL or LOGNORMAL (0 to 4; got " +
                                 std::to_string(sz.kind()) + ")");
    d.mean = 1;  // a valid stand-in: the problem is reported
    return d;
  }
  d.kind = static_cast<SizeKind>(sz.kind());
  d.mean = sz.mean();
  d.spread = sz.spread();
  d.d_min = sz.d_min();
  d.d_max = sz.d_max();
  d.small_fraction = sz.small_fraction() == 0 ? defaults::kSmallFraction : sz.small_fraction();
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
  return d;
}

namespace {

void add_packing(const api::Packing& in, const std::string& path, SpecContext& ctx, int material) {
  Checker& check = ctx.check;
  Scene& scene = ctx.scene;
  const std::size_t before = check.count();
  check.vector(path + ".min", in.min(), kLength);
  check.vector(path + ".max", in.max(), kLength);
  check.vector(path + ".velocity", in.velocity(), kSpeed);
  std::optional<ClosedMesh> region;
  double region_volume = 0;
  if (in.has_inside()) {
    std::optional<Region> placed = load_region(in.inside(), path + ".inside", ctx);
    if (!placed || check.count() != before) return;
    region.emplace(std::move(placed->mesh));
    region_volume = placed->volume;
  }
  // a closed mesh's box stands for a corner left out
  const Vec3 lo = region && !in.has_min() ? region->min() : vec(in.min());
  const Vec3 hi = region && !in.has_max() ? region->max() : vec(in.max());
  const bool planar = scene.plane.has_value();  // a 2D run: discs at y = 0, the box's y range unused
  check_box_order(path + ".max", lo, hi, planar, check);
  if (planar && region && in.solid_fraction() > 0)
    check.fail(path + ".solidFraction",
               "a 2D packing inside a mesh takes count (the area of the mesh's section is "
               "not computed)");
  const std::string sp = path + ".sizes";
  const SizeDistribution d = load_sizes(in.sizes(), sp, check);
  if ((in.count() > 0) == (in.solid_fraction() > 0)) check.fail(path, "give count or solidFraction (one of them)");
  check.in_range(path + ".solidFraction", in.solid_fraction(), 0, 0.74, false, false);
  if (in.count() < 0 || in.count() > 10000000)
    check.fail(path + ".count", "must be in [1, 10000000] (got " + std::to_string(in.count()) + ")");
  if (check.count() != before) return;
  std::mt19937_64 rng(in.seed() == 0 ? defaults::kSeed : in.seed());
  std::vector<double> diameters;
  try {
    if (in.count() > 0) {
      diameters = sample_diameters(d, in.count(), rng);
    } else {  // draw until the spheres' volume makes the solid fraction
      // in 2D the fraction of the rectangle's area the discs cover
      const double target = in.solid_fraction() * (planar   ? (hi - lo).x() * (hi - lo).z()
                                                   : region ? region_volume
                                                            : (hi - lo).prod());
      double volume = 0;
      SizeDraws draws;  // one budget for the whole packing, not one per diameter
      while (volume < target && diameters.size() < 10000000) {
        const double dia = sample_diameters(d, 1, rng, &draws)[0];
        diameters.push_back(dia);
        volume += planar ? std::numbers::pi / 4 * dia * dia : std::numbers::pi / 6 * dia * dia * dia;
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
    const std::vector<Vec3> sites = random_packing(lo, hi, diameters, rng, accept, there, planar);
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

void add_lattice(const api::Lattice& in, const std::string& path, SpecContext& ctx, int material) {
  Checker& check = ctx.check;
  Scene& scene = ctx.scene;
  const std::size_t before = check.count();
  const double spacing = in.spacing() == 0 ? defaults::kLatticeSpacing : in.spacing();
  check.in_range(path + ".spacing", spacing, 0.5, 100, true, false);
  check.vector(path + ".min", in.min(), kLength);
  check.vector(path + ".max", in.max(), kLength);
  check.vector(path + ".velocity", in.velocity(), kSpeed);
  if (in.kind() == api::Lattice::KIND_UNSPECIFIED || !api::Lattice::Kind_IsValid(in.kind()))
    check.fail(path + ".kind", "must be CUBIC, FCC or HEX");
  // one radius, or sizes drawn from a distribution into sites spaced for the largest
  std::optional<SizeDistribution> sizes;
  double site_radius = in.radius();
  if (in.has_sizes()) {
    if (in.radius() != 0) check.fail(path + ".radius", "give radius or sizes, not both");
    sizes = load_sizes(in.sizes(), path + ".sizes", check);
    site_radius = largest_diameter(*sizes) / 2;
  } else {
    check.positive(path + ".radius", in.radius(), kRadius);
  }
  const bool planar = scene.plane.has_value();  // a 2D run: the lattice's layer at y = 0
  std::array<int, 3> counts{in.count_x(), in.count_y(), in.count_z()};
  const bool counted = counts[0] != 0 || counts[1] != 0 || counts[2] != 0;
  if (counted && planar) {
    if (counts[1] > 1)
      check.fail(path + ".countY", "a 2D lattice is one layer at y = 0: leave countY out or give 1 (got " +
                                       std::to_string(counts[1]) + ")");
    counts[1] = 1;
  }
  if (counted) {
    const char* axis[] = {"countX", "countY", "countZ"};
    for (int d = 0; d < 3; ++d)
      if (counts[d] < 1 || counts[d] > 1000000)
        check.fail(path + "." + axis[d], "must be in [1, 1000000] when a count is given (got " +
                                             std::to_string(counts[d]) + "): give all three, or none");
    if (in.has_max()) check.fail(path + ".max", "the counts give the lattice's size: leave max out");
  }
  std::optional<ClosedMesh> region;
  if (in.has_inside()) {
    std::optional<Region> placed = load_region(in.inside(), path + ".inside", ctx);
    if (placed) region.emplace(std::move(placed->mesh));
  }
  if (check.count() != before) return;
  const LatticeKind kind = in.kind() == api::Lattice::CUBIC ? LatticeKind::Cubic
                           : in.kind() == api::Lattice::FCC ? LatticeKind::Fcc
                                                            : LatticeKind::Hex;
  const Vec3 lo = region && !in.has_min() ? region->min() : vec(in.min());
  std::vector<Vec3> sites;
  if (counted) {
    const double bound = static_cast<double>(counts[0]) * counts[1] * counts[2];
    if (!check.room(path, scene.particles.size(), bound)) return;
    sites = lattice_sites_counted(kind, lo, site_radius, spacing, counts, planar);
  } else {
    const Vec3 hi = region && !in.has_max() ? region->max() : vec(in.max());
    if (!check_box_order(path + ".max", lo, hi, planar, check)) return;
    if (!check.room(path, scene.particles.size(), lattice_site_bound(kind, lo, hi, site_radius, spacing, planar)))
      return;
    sites = lattice_sites(kind, lo, hi, site_radius, spacing, planar);
  }
  if (region)
    sites.erase(
        std::remove_if(sites.begin(), sites.end(), [&](const Vec3& x) { return !region->holds(x, site_radius); }),
        sites.end());
  if (sites.empty()) {
    check.fail(path, std::string(region ? "the mesh" : "the box") + " is too small to hold one particle of radius " +
                         num(site_radius));
    return;
  }
  std::vector<double> diameters(sites.size(), 2 * site_radius);
  if (sizes) {
    std::mt19937_64 rng(in.seed() == 0 ? defaults::kSeed : in.seed());
    try {
      diameters = sample_diameters(*sizes, static_cast<int>(sites.size()), rng);
    } catch (const std::runtime_error& e) {
      check.fail(path + ".sizes", e.what());
      return;
    }
  }
  for (std::size_t k = 0; k < sites.size(); ++k) {
    ParticleInit p;
    p.position = sites[k];
    p.velocity = vec(in.velocity());
    p.radius = diameters[k] / 2;
    p.material = material;
    scene.particles.push_back(p);
  }
}

}  // namespace

void load_particles(const api::JobSpec& spec, SpecContext& ctx) {
  Checker& check = ctx.check;
  Scene& scene = ctx.scene;
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
    p.material = ctx.particle_material(in.material(), path + ".material");
    p.fixed = in.fixed();
    check.vector(path + ".force", in.force(), kForce);
    p.force = vec(in.force());
    scene.particles.push_back(p);
  }
  for (int k = 0; k < spec.lattices_size(); ++k)
    add_lattice(spec.lattices(k), at("lattices", k), ctx,
                ctx.particle_material(spec.lattices(k).material(), at("lattices", k) + ".material"));
  for (int k = 0; k < spec.packings_size(); ++k)
    add_packing(spec.packings(k), at("packings", k), ctx,
                ctx.particle_material(spec.packings(k).material(), at("packings", k) + ".material"));
  load_clumps(spec, ctx);
  load_stones(spec, ctx);
  if (!scene.clumps.empty() && spec.has_growth() && spec.growth().factor() != 1)
    check.fail("growth", "radius growth and rigid clumps cannot be combined (a clump's shape is fixed)");
  if (spec.particles().empty() && spec.lattices().empty() && spec.packings().empty() && spec.clumps().empty() &&
      spec.ballast_stones().empty() && spec.sources().empty())
    check.fail("particles", "the scene has no particles (and no sources that insert some)");
  check.room("particles", 0, static_cast<double>(scene.particles.size()));  // clumps' and stones' included
}

}  // namespace dem::spec
