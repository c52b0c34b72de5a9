#include "clumps/mass_properties.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <map>
#include <cmath>
#include <cstring>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include <Eigen/Eigenvalues>

namespace dem {
namespace {

// Levels of halving below a root cell (about the largest sphere's diameter): compared from the
// first plus one, up to 2^11 cells a side of a root cell.
constexpr int kFirstLevels = 3, kMostLevels = 11;

// Zeroth, first and second moments of a region: integral of 1, x and x x^T.
struct Moments {
  double m0 = 0;
  Vec3 m1 = Vec3::Zero();
  Eigen::Matrix3d m2 = Eigen::Matrix3d::Zero();

  // A cube of side h centred at c: integral of x_i x_j = h^3 (c_i c_j + delta_ij h^2 / 12); with
  // `share` < 1, that share of it, as if spread through it.
  void add_cube(const Vec3& c, double h, double share = 1) {
    if (share <= 0) return;
    const double v = share * h * h * h;
    m0 += v;
    m1 += v * c;
    m2 += v * (c * c.transpose() + (h * h / 12.0) * Eigen::Matrix3d::Identity());
  }
};

// The adaptive subdivision of the root cells. A cell is tested only against the spheres that reach
// its parent (a sphere that misses a cell misses its children), so a shape of thousands of spheres
// costs about what its spheres' surfaces do, not cells times spheres.
class Subdivision {
 public:
  Subdivision(const std::vector<MemberSphere>& spheres, int levels)
      : spheres_(spheres), levels_(levels), near_(static_cast<std::size_t>(levels) + 2) {}

  // Adds the union's part in the cube of side h centred at c; `candidates`: the spheres that may
  // reach it. A cell the surface cuts at the finest level counts by its share inside (inside_share).
  void integrate(const std::vector<int>& candidates, const Vec3& c, double h, int depth) {
    std::vector<int>& near = near_[depth];
    near.clear();
    const double half = 0.5 * h;
    for (int i : candidates) {
      const MemberSphere& s = spheres_[i];
      const Vec3 offset = (c - s.centre).cwiseAbs();
      // farthest corner within the sphere: the (convex) sphere holds the whole cube
      if ((offset + Vec3::Constant(half)).squaredNorm() <= s.radius * s.radius) {
        moments_.add_cube(c, h);
        return;
      }
      // nearest point of the cube within the radius: this sphere may reach into it
      if ((offset - Vec3::Constant(half)).cwiseMax(0.0).squaredNorm() < s.radius * s.radius) near.push_back(i);
    }
    if (near.empty()) return;
    if (depth == levels_) {
      moments_.add_cube(c, h, inside_share(near, c, h));
      return;
    }
    const double q = 0.25 * h;
    for (int k = 0; k < 8; ++k)  // near_[depth] stays as it is while the children fill near_[depth + 1]
      integrate(near, c + Vec3((k & 1) ? q : -q, (k & 2) ? q : -q, (k & 4) ? q : -q), 0.5 * h, depth + 1);
  }

  const Moments& moments() const { return moments_; }

 private:
  // The share of a finest cell inside the union: the surface taken as the plane of the sphere whose
  // surface lies farthest out at the centre (the union's signed distance), and the cube's share
  // below that plane as a linear ramp across the cube's extent along its normal (exact for a plane
  // along an axis). Its error is second order in the cell's size, where counting a cut cell by its
  // centre (in or out) was first order and jumped from level to level, so that two levels could
  // agree by chance and stop the refinement early.
  double inside_share(const std::vector<int>& near, const Vec3& c, double h) const {
    double depth_in = -INFINITY, extent = h;
    for (int i : near) {
      const Vec3 out = c - spheres_[i].centre;
      const double distance = out.norm(), d = spheres_[i].radius - distance;
      if (d <= depth_in) continue;
      depth_in = d;
      extent = distance > 0 ? h * out.cwiseAbs().sum() / distance : h;  // the cube's width along the normal
    }
    return std::clamp(0.5 + depth_in / extent, 0.0, 1.0);
  }

  const std::vector<MemberSphere>& spheres_;
  int levels_;
  std::vector<std::vector<int>> near_;  // by depth: the spheres reaching the cell being divided
  Moments moments_;
};

// The root cells: a grid of cubes about the largest sphere's diameter with a node at `origin`, those
// that some sphere's box reaches, each with those spheres, in grid order. The subdivision's depth counts from them, so
// a long or sparse shape is resolved as finely as a compact one.
struct RootCells {
  double side = 0;
  std::vector<Vec3> centres;
  std::vector<std::vector<int>> spheres;
};

RootCells root_cells(const std::vector<MemberSphere>& spheres, const Vec3& origin) {
  RootCells roots;
  for (const MemberSphere& s : spheres) roots.side = std::max(roots.side, 2.0001 * s.radius);
  std::map<std::array<std::int64_t, 3>, std::vector<int>> cells;
  for (int i = 0; i < static_cast<int>(spheres.size()); ++i) {
    const MemberSphere& s = spheres[i];
    std::array<std::int64_t, 3> first{}, last{};
    for (int d = 0; d < 3; ++d) {
      first[d] = static_cast<std::int64_t>(std::floor((s.centre[d] - s.radius - origin[d]) / roots.side));
      last[d] = static_cast<std::int64_t>(std::floor((s.centre[d] + s.radius - origin[d]) / roots.side));
    }
    for (std::int64_t x = first[0]; x <= last[0]; ++x)
      for (std::int64_t y = first[1]; y <= last[1]; ++y)
        for (std::int64_t z = first[2]; z <= last[2]; ++z) cells[{x, y, z}].push_back(i);
  }
  for (auto& [key, near] : cells) {
    roots.centres.push_back(origin + roots.side * Vec3(static_cast<double>(key[0]) + 0.5,
                                                       static_cast<double>(key[1]) + 0.5,
                                                       static_cast<double>(key[2]) + 0.5));
    roots.spheres.push_back(std::move(near));
  }
  return roots;
}

MassProperties from_moments(const Moments& m) {
  MassProperties p;
  p.volume = m.m0;
  p.centroid = m.m1 / m.m0;
  // second moments about the centroid S, then I = tr(S) 1 - S
  const Eigen::Matrix3d s = m.m2 - m.m0 * p.centroid * p.centroid.transpose();
  p.inertia = s.trace() * Eigen::Matrix3d::Identity() - s;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(p.inertia);
  p.principal_moments = solver.eigenvalues();
  p.principal_axes = solver.eigenvectors();
  if (p.principal_axes.determinant() < 0) p.principal_axes.col(2) *= -1;  // a rotation, not a reflection
  return p;
}

}  // namespace

namespace {
std::atomic<std::uint64_t> integrations{0};

// The integrations already made, by the bytes of what they were asked: the runs of a study (and the
// server's checks of them) build the same ballast stones again, each run's from the same seeds, and
// an integration is the set-up's costliest work. The result depends on its input alone, so a shape
// asked again gets the bits it got the first time. Emptied when its keys pass 16 MB.
class Integrated {
 public:
  static std::string key(const std::vector<MemberSphere>& spheres, double relative_accuracy) {
    std::string k(sizeof(double) * (1 + 4 * spheres.size()), '\0');
    char* at = k.data();
    auto put = [&at](double v) {
      std::memcpy(at, &v, sizeof v);
      at += sizeof v;
    };
    put(relative_accuracy);
    for (const MemberSphere& s : spheres) put(s.centre.x()), put(s.centre.y()), put(s.centre.z()), put(s.radius);
    return k;
  }
  std::optional<MassProperties> find(const std::string& key) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = done_.find(key);
    if (it == done_.end()) return std::nullopt;
    return it->second;
  }
  void keep(std::string key, const MassProperties& p) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (key_bytes_ + key.size() > kMostKeyBytes) done_.clear(), key_bytes_ = 0;
    key_bytes_ += key.size();
    done_.emplace(std::move(key), p);
  }

 private:
  static constexpr std::size_t kMostKeyBytes = std::size_t{16} << 20;
  std::mutex mutex_;
  std::unordered_map<std::string, MassProperties> done_;
  std::size_t key_bytes_ = 0;
};
Integrated integrated;

MassProperties integrate_union(const std::vector<MemberSphere>& spheres, double relative_accuracy) {
  integrations.fetch_add(1, std::memory_order_relaxed);
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const MemberSphere& s : spheres) {
    lo = lo.cwiseMin(s.centre - Vec3::Constant(s.radius));
    hi = hi.cwiseMax(s.centre + Vec3::Constant(s.radius));
  }
  const RootCells roots = root_cells(spheres, 0.5 * (lo + hi));  // cells symmetric about the box's centre
  MassProperties previous;
  for (int levels = kFirstLevels;; ++levels) {
    Subdivision cells(spheres, levels);
    for (std::size_t k = 0; k < roots.centres.size(); ++k)
      cells.integrate(roots.spheres[k], roots.centres[k], roots.side, 0);
    MassProperties now = from_moments(cells.moments());
    if (levels > kFirstLevels) {
      double change = std::abs(now.volume - previous.volume) / now.volume;
      for (int k = 0; k < 3; ++k)
        change = std::max(change, std::abs(now.principal_moments[k] - previous.principal_moments[k]) /
                                      now.principal_moments.maxCoeff());
      now.relative_accuracy = change;
      if (change < relative_accuracy || levels == kMostLevels) return now;
    }
    previous = now;
  }
}
}  // namespace

std::uint64_t union_mass_property_integrations() { return integrations.load(std::memory_order_relaxed); }

MassProperties union_mass_properties(const std::vector<MemberSphere>& spheres, double relative_accuracy) {
  if (spheres.empty()) throw std::invalid_argument("a clump needs at least one sphere");
  for (const MemberSphere& s : spheres)
    if (!(s.radius > 0)) throw std::invalid_argument("a clump's sphere needs a positive radius");
  std::string key = Integrated::key(spheres, relative_accuracy);
  if (std::optional<MassProperties> done = integrated.find(key)) return *done;
  MassProperties p = integrate_union(spheres, relative_accuracy);
  integrated.keep(std::move(key), p);
  return p;
}

}  // namespace dem
