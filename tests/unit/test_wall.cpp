// Tests of the analytic walls (engine/walls/wall.hpp): one-sided planes and two-sided plates, with
// closest points worked out by hand for each region (face, edge, corner) of a plate.
#include <gtest/gtest.h>

#include <cmath>

#include "walls/wall.hpp"

namespace dem {
namespace {

constexpr double kTol = 1e-12;

Wall plane_wall(const Vec3& point, const Vec3& normal) {
  WallInit init;
  init.shape = PlaneShape{point, normal};
  return Wall::from(init);
}

Wall plate_wall(const Vec3& c1, const Vec3& c2, const Vec3& c3, const Vec3& c4) {
  WallInit init;
  init.shape = PlateShape{{c1, c2, c3, c4}};
  return Wall::from(init);
}

// The unit square in z = 0, counter-clockwise seen from +z.
Wall unit_square() { return plate_wall(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)); }

// Checks contact() against a closest point on the wall worked out by hand: the contact normal
// points from that point to the centre, the overlap is r minus their distance.
void expect_contact_via(const Wall& wall, const Vec3& x, double r, const Vec3& closest) {
  const double d = (x - closest).norm();
  ASSERT_LT(d, r) << "test set-up: the sphere must overlap";
  Vec3 n;
  double delta = -1;
  ASSERT_TRUE(wall.contact(x, r, n, delta)) << "x = " << x.transpose();
  EXPECT_NEAR(delta, r - d, kTol);
  EXPECT_NEAR((n - (x - closest) / d).norm(), 0.0, kTol) << "n = " << n.transpose();
  EXPECT_NEAR(wall.distance(x), d, kTol);
}

void expect_no_contact(const Wall& wall, const Vec3& x, double r) {
  Vec3 n = Vec3::Zero();
  double delta = 0;
  EXPECT_FALSE(wall.contact(x, r, n, delta)) << "x = " << x.transpose() << ", delta = " << delta;
}

// ---------------------------------------------------------------------------------------------
// Planes

TEST(WallPlane, NormalIsNormalizedAndPointKept) {
  const Wall w = plane_wall(Vec3(1, 2, 3), Vec3(0, 0, 5));
  EXPECT_EQ(w.kind, Wall::Kind::Plane);
  EXPECT_EQ(w.point, Vec3(1, 2, 3));
  EXPECT_NEAR((w.normal - Vec3::UnitZ()).norm(), 0.0, kTol);
}

TEST(WallPlane, SphereInFrontOverlapsByRadiusMinusHeight) {
  const Wall w = plane_wall(Vec3(0, 0, 1), Vec3(0, 0, 2));
  Vec3 n;
  double delta = 0;
  ASSERT_TRUE(w.contact(Vec3(7, -3, 1.3), 0.5, n, delta));
  EXPECT_NEAR(delta, 0.2, kTol);
  EXPECT_NEAR((n - Vec3::UnitZ()).norm(), 0.0, kTol);
  EXPECT_NEAR(w.distance(Vec3(7, -3, 1.3)), 0.3, kTol);
}

TEST(WallPlane, SphereJustClearOrTouchingHasNoContact) {
  const Wall w = plane_wall(Vec3(0, 0, 0), Vec3(0, 0, 1));
  expect_no_contact(w, Vec3(0, 0, 0.6), 0.5);
  expect_no_contact(w, Vec3(0, 0, 0.5), 0.5);  // touching: zero overlap is no contact
}

TEST(WallPlane, SphereBehindThePlaneIsPushedOutAlongTheNormal) {
  // Centre 0.3 behind the plane: the overlap counts the whole way back to the front side.
  const Wall w = plane_wall(Vec3(0, 0, 0), Vec3(0, 0, 1));
  Vec3 n;
  double delta = 0;
  ASSERT_TRUE(w.contact(Vec3(0.1, 0.2, -0.3), 0.5, n, delta));
  EXPECT_NEAR(delta, 0.8, kTol);
  EXPECT_NEAR((n - Vec3::UnitZ()).norm(), 0.0, kTol);
  EXPECT_NEAR(w.distance(Vec3(0.1, 0.2, -0.3)), -0.3, kTol);
  // Far behind, still in contact (one-sided wall), never with the normal flipped.
  ASSERT_TRUE(w.contact(Vec3(0, 0, -10), 0.5, n, delta));
  EXPECT_NEAR(delta, 10.5, kTol);
  EXPECT_NEAR((n - Vec3::UnitZ()).norm(), 0.0, kTol);
}

TEST(WallPlane, InclinedPlane) {
  // The plane x + y = 2 facing (1, 1, 0)/sqrt(2); the centre (2, 2, 5) is sqrt(2) in front.
  const Wall w = plane_wall(Vec3(1, 1, 0), Vec3(1, 1, 0));
  Vec3 n;
  double delta = 0;
  ASSERT_TRUE(w.contact(Vec3(2, 2, 5), 1.5, n, delta));
  EXPECT_NEAR(delta, 1.5 - std::sqrt(2.0), kTol);
  EXPECT_NEAR((n - Vec3(1, 1, 0) / std::sqrt(2.0)).norm(), 0.0, kTol);
  EXPECT_NEAR(w.distance(Vec3(2, 2, 5)), std::sqrt(2.0), kTol);
}

// ---------------------------------------------------------------------------------------------
// Plates

TEST(WallPlate, NormalFollowsTheCornerOrder) {
  const Wall ccw = unit_square();
  EXPECT_EQ(ccw.kind, Wall::Kind::Plate);
  EXPECT_NEAR((ccw.normal - Vec3::UnitZ()).norm(), 0.0, kTol);
  const Wall cw = plate_wall(Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(1, 0, 0));
  EXPECT_NEAR((cw.normal + Vec3::UnitZ()).norm(), 0.0, kTol);
}

TEST(WallPlate, NormalOfAnOffsetPlateIsItsOwn) {
  // Far from the origin: Newell's sum must not pick up the offset.
  const Vec3 o(100, -50, 20);
  const Wall w = plate_wall(o, o + Vec3(0, 2, 0), o + Vec3(0, 2, 3), o + Vec3(0, 0, 3));
  EXPECT_NEAR((w.normal - Vec3::UnitX()).norm(), 0.0, kTol);
}

TEST(WallPlate, SmallPlateFarFromTheOriginKeepsItsNormal) {
  // A 1/128 m plate at map-grid coordinates (UTM-like, metres): every corner is exact in binary,
  // so the true normal is exactly (0, -1, 1) / sqrt(2). Summing c_k x c_k+1 over absolute
  // coordinates cancels terms of 1e4 down to an area of 1e-4 and loses every digit.
  const double size = 1.0 / 128;
  const Vec3 o(452000, 4500000, 312);
  const Wall w = plate_wall(o, o + Vec3(size, 0, 0), o + Vec3(size, size, size), o + Vec3(0, size, size));
  const Vec3 normal = Vec3(0, -1, 1) / std::sqrt(2.0);
  EXPECT_NEAR((w.normal - normal).norm(), 0.0, 1e-12) << w.normal.transpose();
  // A sphere 1 mm in front of the middle of the face touches it there.
  const Vec3 middle = o + Vec3(size / 2, size / 2, size / 2);
  Vec3 n;
  double delta = 0;
  ASSERT_TRUE(w.contact(middle + 1e-3 * normal, 2e-3, n, delta));
  EXPECT_NEAR(delta, 1e-3, 1e-8);
  EXPECT_NEAR((n - normal).norm(), 0.0, 1e-5);
}

TEST(WallPlate, FaceRegionOnBothSides) {
  const Wall w = unit_square();
  expect_contact_via(w, Vec3(0.3, 0.4, 0.2), 0.25, Vec3(0.3, 0.4, 0));
  expect_contact_via(w, Vec3(0.3, 0.4, -0.2), 0.25, Vec3(0.3, 0.4, 0));
  // Just inside an edge the face, not the edge, is closest.
  expect_contact_via(w, Vec3(0.98, 0.5, 0.05), 0.1, Vec3(0.98, 0.5, 0));
  expect_contact_via(w, Vec3(0.5, 0.001, -0.05), 0.1, Vec3(0.5, 0.001, 0));
  expect_no_contact(w, Vec3(0.3, 0.4, 0.3), 0.25);
  expect_no_contact(w, Vec3(0.3, 0.4, -0.3), 0.25);
}

TEST(WallPlate, EdgeRegionOnBothSides) {
  const Wall w = unit_square();
  // Beyond the edge x = 1: the closest point is on that edge.
  expect_contact_via(w, Vec3(1.1, 0.5, 0.1), 0.2, Vec3(1, 0.5, 0));
  expect_contact_via(w, Vec3(1.1, 0.5, -0.1), 0.2, Vec3(1, 0.5, 0));
  // Beyond the edge y = 0, in the plate's plane: the normal lies in the plane.
  expect_contact_via(w, Vec3(0.25, -0.15, 0), 0.2, Vec3(0.25, 0, 0));
  // Out of reach of the edge although within r of the plate's infinite plane.
  expect_no_contact(w, Vec3(1.15, 0.5, 0.15), 0.2);
}

TEST(WallPlate, CornerRegionOnBothSides) {
  const Wall w = unit_square();
  expect_contact_via(w, Vec3(1.1, 1.2, 0.2), 0.35, Vec3(1, 1, 0));  // distance 0.3
  expect_contact_via(w, Vec3(1.1, 1.2, -0.2), 0.35, Vec3(1, 1, 0));
  expect_contact_via(w, Vec3(-0.2, -0.1, -0.2), 0.35, Vec3(0, 0, 0));  // distance 0.3
  expect_no_contact(w, Vec3(1.2, 1.2, 0.2), 0.3);                      // distance 0.3464
}

TEST(WallPlate, ClockwiseAndCounterClockwiseGiveTheSameContacts) {
  // A plate is solid on both faces, so the winding only flips the stored normal.
  const Wall ccw = unit_square();
  const Wall cw = plate_wall(Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(1, 0, 0), Vec3(0, 0, 0));
  for (const Vec3& x : {Vec3(0.3, 0.4, 0.2), Vec3(0.3, 0.4, -0.2), Vec3(1.1, 0.5, 0.1), Vec3(1.1, 1.2, -0.2),
                        Vec3(-0.1, 0.5, 0.0), Vec3(0.5, 0.5, 0.0)}) {
    Vec3 n1, n2;
    double d1 = 0, d2 = 0;
    ASSERT_TRUE(ccw.contact(x, 0.35, n1, d1)) << x.transpose();
    ASSERT_TRUE(cw.contact(x, 0.35, n2, d2)) << x.transpose();
    EXPECT_NEAR(d1, d2, kTol) << x.transpose();
    EXPECT_NEAR(ccw.distance(x), cw.distance(x), kTol) << x.transpose();
    // Off the plate the normal is the gap's direction, whatever the winding; in it, it is +-normal.
    if (ccw.distance(x) > 0) {
      EXPECT_NEAR((n1 - n2).norm(), 0.0, kTol) << x.transpose();
    }
  }
  expect_contact_via(cw, Vec3(0.3, 0.4, 0.2), 0.25, Vec3(0.3, 0.4, 0));
  expect_contact_via(cw, Vec3(1.1, 1.2, -0.2), 0.35, Vec3(1, 1, 0));
}

TEST(WallPlate, CentreInThePlateGivesFullRadiusOverlap) {
  // Exactly on the face there is no direction from the gap: the plate's normal is used.
  const Wall w = unit_square();
  Vec3 n;
  double delta = 0;
  ASSERT_TRUE(w.contact(Vec3(0.5, 0.5, 0), 0.1, n, delta));
  EXPECT_NEAR(delta, 0.1, kTol);
  EXPECT_NEAR(std::abs(n.dot(w.normal)), 1.0, kTol);
  EXPECT_NEAR(w.distance(Vec3(0.5, 0.5, 0)), 0.0, kTol);
}

TEST(WallPlate, TiltedPlateRegions) {
  // A 2 x sqrt(2) plate rising at 45 degrees: corners (0,0,0) (2,0,0) (2,1,1) (0,1,1), normal
  // (0,-1,1)/sqrt(2) for this order.
  const Wall w = plate_wall(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 1), Vec3(0, 1, 1));
  const Vec3 normal = Vec3(0, -1, 1) / std::sqrt(2.0);
  EXPECT_NEAR((w.normal - normal).norm(), 0.0, kTol);
  // Face: 0.1 above the middle, and 0.1 below it.
  const Vec3 middle(1, 0.5, 0.5);
  expect_contact_via(w, middle + 0.1 * normal, 0.15, middle);
  expect_contact_via(w, middle - 0.1 * normal, 0.15, middle);
  // Beyond the upper edge (y = z = 1), straight up: closest point (1, 1, 1), distance 0.1.
  expect_contact_via(w, Vec3(1, 1, 1.1), 0.15, Vec3(1, 1, 1));
  // Beyond the corner (2, 0, 0) (x > 2 and below the lower edge): distance sqrt(0.015).
  expect_contact_via(w, Vec3(2.05, -0.1, -0.05), 0.15, Vec3(2, 0, 0));
}

TEST(WallPlate, EdgeRegionOfASlantedEdge) {
  // A trapezoid (0,0) (4,0) (3,2) (1,2) in z = 0. From (3.9, 1.5, 0.05), outside the slanted edge
  // (4,0)-(3,2): the projection onto that edge is at s = ((-0.1, 1.5).(-1, 2)) / 5 = 0.62 along it,
  // the point (3.38, 1.24, 0).
  const Wall w = plate_wall(Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(3, 2, 0), Vec3(1, 2, 0));
  expect_contact_via(w, Vec3(3.9, 1.5, 0.05), 0.6, Vec3(3.38, 1.24, 0));
  // Inside the trapezoid near the same edge the face is closest.
  expect_contact_via(w, Vec3(3.4, 1.0, -0.05), 0.1, Vec3(3.4, 1.0, 0));
}

TEST(WallPlate, DistanceIsUnsignedOnBothSides) {
  const Wall w = unit_square();
  EXPECT_NEAR(w.distance(Vec3(0.5, 0.5, 2)), 2.0, kTol);
  EXPECT_NEAR(w.distance(Vec3(0.5, 0.5, -2)), 2.0, kTol);
  EXPECT_NEAR(w.distance(Vec3(4, 5, 0)), 5.0, kTol);  // to the corner (1, 1, 0)
}

}  // namespace
}  // namespace dem
