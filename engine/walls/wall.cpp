#include "walls/wall.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dem {
namespace {

Vec3 closest_on_segment(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0 ? std::clamp((x - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return a + s * ab;
}

}  // namespace

Wall Wall::from(const WallInit& init) {
  Wall w;
  w.material = init.material;
  if (const auto* plane = std::get_if<PlaneShape>(&init.shape)) {
    w.kind = Kind::Plane;
    w.point = plane->point;
    w.normal = plane->normal.normalized();
  } else {
    const auto& plate = std::get<PlateShape>(init.shape);
    w.kind = Kind::Plate;
    w.corners = plate.corners;
    w.point = plate.corners[0];
    // Newell's normal: robust for any planar polygon; corners are then counter-clockwise about it.
    // Summed relative to corner 1: over absolute coordinates the terms grow with the distance from
    // the origin and cancel down to the plate's area, losing every digit for a small plate far away.
    Vec3 n = Vec3::Zero();
    for (int k = 0; k < 4; ++k) n += (w.corners[k] - w.point).cross(w.corners[(k + 1) % 4] - w.point);
    w.normal = n.normalized();
  }
  w.point0_ = w.point;
  w.normal0_ = w.normal;
  w.corners0_ = w.corners;
  return w;
}

Vec3 Wall::centroid() const {
  if (kind == Kind::Plane) return point;
  return 0.25 * (corners[0] + corners[1] + corners[2] + corners[3]);
}

void Wall::move_to(const WallPose& next) {
  pose = next;
  point = next.place(point0_);
  normal = next.turn(normal0_);
  if (kind == Kind::Plate)
    for (int k = 0; k < 4; ++k) corners[k] = next.place(corners0_[k]);
}

Vec3 Wall::closest_on_plate(const Vec3& x) const {
  const Vec3 q = x - (x - point).dot(normal) * normal;
  bool inside = true;
  for (int k = 0; k < 4 && inside; ++k)
    inside = (corners[(k + 1) % 4] - corners[k]).cross(q - corners[k]).dot(normal) >= 0;
  if (inside) return q;
  Vec3 best = corners[0];
  double best_d2 = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 4; ++k) {
    const Vec3 c = closest_on_segment(x, corners[k], corners[(k + 1) % 4]);
    const double d2 = (x - c).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = c;
    }
  }
  return best;
}

bool Wall::contact(const Vec3& x, double r, Vec3& n, double& delta) const {
  if (kind == Kind::Plane) {
    const double d = (x - point).dot(normal);
    if (d >= r) return false;
    n = normal;
    delta = r - d;
    return true;
  }
  const Vec3 gap = x - closest_on_plate(x);
  const double d2 = gap.squaredNorm();
  if (d2 >= r * r) return false;
  const double d = std::sqrt(d2);
  n = d > 0 ? Vec3(gap / d) : normal;
  delta = r - d;
  return true;
}

Vec3 Wall::normal_towards(const Vec3& x) const {
  if (kind == Kind::Plane) return normal;
  const Vec3 gap = x - closest_on_plate(x);
  const double d = gap.norm();
  return d > 0 ? Vec3(gap / d) : normal;
}

double Wall::distance(const Vec3& x) const {
  if (kind == Kind::Plane) return (x - point).dot(normal);
  return (x - closest_on_plate(x)).norm();
}

}  // namespace dem
