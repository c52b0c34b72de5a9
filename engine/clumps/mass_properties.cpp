#include "clumps/mass_properties.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>

namespace dem {
namespace {

// Zeroth, first and second moments of a region: integral of 1, x and x x^T.
struct Moments {
  double m0 = 0;
  Vec3 m1 = Vec3::Zero();
  Eigen::Matrix3d m2 = Eigen::Matrix3d::Zero();

  // A cube of side h centred at c: integral of x_i x_j = h^3 (c_i c_j + delta_ij h^2 / 12).
  void add_cube(const Vec3& c, double h) {
    const double v = h * h * h;
    m0 += v;
    m1 += v * c;
    m2 += v * (c * c.transpose() + (h * h / 12.0) * Eigen::Matrix3d::Identity());
  }
};

enum class Cover { Inside, Outside, Cut };

Cover classify(const std::vector<MemberSphere>& spheres, const Vec3& c, double h) {
  const double half = 0.5 * h;
  bool maybe = false;
  for (const MemberSphere& s : spheres) {
    // farthest corner within the sphere: the (convex) sphere holds the whole cube
    const Vec3 far = (c - s.centre).cwiseAbs() + Vec3::Constant(half);
    if (far.squaredNorm() <= s.radius * s.radius) return Cover::Inside;
    // nearest point of the cube beyond the radius: this sphere misses it
    const Vec3 near = ((c - s.centre).cwiseAbs() - Vec3::Constant(half)).cwiseMax(0.0);
    if (near.squaredNorm() < s.radius * s.radius) maybe = true;
  }
  return maybe ? Cover::Cut : Cover::Outside;
}

bool inside_any(const std::vector<MemberSphere>& spheres, const Vec3& p) {
  for (const MemberSphere& s : spheres)
    if ((p - s.centre).squaredNorm() <= s.radius * s.radius) return true;
  return false;
}

// Cells cut by the surface at the finest level count by their centre (the midpoint rule).
void integrate(const std::vector<MemberSphere>& spheres, const Vec3& c, double h, int levels_left, Moments& out) {
  switch (classify(spheres, c, h)) {
    case Cover::Outside:
      return;
    case Cover::Inside:
      out.add_cube(c, h);
      return;
    case Cover::Cut:
      break;
  }
  if (levels_left == 0) {
    if (inside_any(spheres, c)) out.add_cube(c, h);
    return;
  }
  const double q = 0.25 * h;
  for (int k = 0; k < 8; ++k) {
    const Vec3 child = c + Vec3((k & 1) ? q : -q, (k & 2) ? q : -q, (k & 4) ? q : -q);
    integrate(spheres, child, 0.5 * h, levels_left - 1, out);
  }
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
}  // namespace

std::uint64_t union_mass_property_integrations() { return integrations.load(std::memory_order_relaxed); }

MassProperties union_mass_properties(const std::vector<MemberSphere>& spheres, double relative_accuracy) {
  if (spheres.empty()) throw std::invalid_argument("a clump needs at least one sphere");
  integrations.fetch_add(1, std::memory_order_relaxed);
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const MemberSphere& s : spheres) {
    if (!(s.radius > 0)) throw std::invalid_argument("a clump's sphere needs a positive radius");
    lo = lo.cwiseMin(s.centre - Vec3::Constant(s.radius));
    hi = hi.cwiseMax(s.centre + Vec3::Constant(s.radius));
  }
  const Vec3 centre = 0.5 * (lo + hi);
  const double side = (hi - lo).maxCoeff() * 1.0001;  // the root cube holds every sphere
  MassProperties previous;
  for (int levels = 5;; ++levels) {
    Moments m;
    integrate(spheres, centre, side, levels, m);
    MassProperties now = from_moments(m);
    if (levels > 5) {
      double change = std::abs(now.volume - previous.volume) / now.volume;
      for (int k = 0; k < 3; ++k)
        change = std::max(change, std::abs(now.principal_moments[k] - previous.principal_moments[k]) /
                                      now.principal_moments.maxCoeff());
      now.relative_accuracy = change;
      if (change < relative_accuracy || levels == 11) return now;
    }
    previous = now;
  }
}

}  // namespace dem
