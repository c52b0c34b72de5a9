// Analytic walls: infinite planes (one-sided) and planar quadrilateral plates (two-sided, the BallastDEM manual's
// rplate), with the closest-point query the contact loop needs.
#pragma once

#include <array>

#include "core/scene.hpp"
#include "walls/wall_motion.hpp"

namespace dem {

struct Wall {
  enum class Kind { Plane, Plate };
  Kind kind = Kind::Plane;
  int material = 0;
  Vec3 point = Vec3::Zero();    // plane: a point; plate: corner 1
  Vec3 normal = Vec3::UnitZ();  // unit
  // plate only, counter-clockwise about `normal`; a plane's are 0 (Eigen leaves a vector unset, and a saved state
  // would carry whatever the memory held: two runs of one spec then saved other bytes)
  std::array<Vec3, 4> corners{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  WallPose pose;  // where it is relative to its start, and how fast it moves

  static Wall from(const WallInit& init);

  // Centre of the plate's corners, or the plane's point.
  Vec3 centroid() const;
  // Places the wall at `pose` (from the geometry it started with).
  void move_to(const WallPose& next);

  // For a sphere at x of radius r: true if it overlaps the wall; then n (unit, wall -> sphere) and
  // the overlap delta. A sphere behind a plane still touches it (pushed back out along the normal).
  bool contact(const Vec3& x, double r, Vec3& n, double& delta) const;

  // Distance from x to the wall's solid (negative behind a plane), for candidate lists.
  double distance(const Vec3& x) const;
  // The unit normal from the wall towards x (what contact() gives where they touch).
  Vec3 normal_towards(const Vec3& x) const;

 private:
  Vec3 closest_on_plate(const Vec3& x) const;

  Vec3 point0_ = Vec3::Zero(), normal0_ = Vec3::UnitZ();
  std::array<Vec3, 4> corners0_{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
};

}  // namespace dem
