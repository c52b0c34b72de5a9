// Prescribed wall motions: the pose follows the exact integral of the velocity, turns about its
// centre, and a simulation moves planes, plates and meshes with it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/meshes.hpp"
#include "support/scenes.hpp"
#include "walls/wall_motion.hpp"

namespace dem::test {
namespace {

WallInit moving_plate(const PrescribedMotion& m) {
  WallInit w{"plate", 1, PlateShape{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}}, m, {}};
  return w;
}

TEST(WallDriver, SinusoidalVelocityIsIntegratedExactly) {
  PrescribedMotion m;
  m.velocity = {0.1, 0, 0};
  m.amplitude = {0, 0, 0.02};
  m.frequency = 3;
  m.phase = 0.3;
  WallDriver d(moving_plate(m), {0.5, 0.5, 0}, Vec3::Zero());
  const double t = 0.37, w = 2 * std::numbers::pi * 3;
  d.begin_step(t, 1e-4);
  const Vec3 want = m.velocity * t + m.amplitude * ((std::cos(0.3) - std::cos(w * t + 0.3)) / w);
  EXPECT_TRUE(d.pose().displacement.isApprox(want, 1e-14));
  EXPECT_NEAR(d.pose().velocity.z(), 0.02 * std::sin(w * t + 0.3), 1e-15);
  EXPECT_TRUE(d.moves());
  EXPECT_FALSE(d.load_controlled());
}

TEST(WallDriver, SpinTurnsAboutTheCentre) {
  PrescribedMotion m;
  m.angular_velocity = {0, 0, 2.0};
  m.center = Vec3(0.5, 0.5, 0);
  WallDriver d(moving_plate(m), Vec3::Zero(), Vec3::Zero());
  d.begin_step(std::numbers::pi / 4, 1e-3);  // a quarter turn
  const Vec3 corner = d.pose().place({1, 0.5, 0});
  EXPECT_TRUE(corner.isApprox(Vec3(0.5, 1.0, 0), 1e-12)) << corner.transpose();
  EXPECT_TRUE(d.pose().velocity_at({1, 0.5, 0}).isApprox(Vec3(0, 1.0, 0), 1e-12));
}

// A servo's gain is its own below what its contacts allow, and alpha / (K dt / 2 + C) past it
// (alpha = 1/2): then g (K dt + 2 C) = 1 and g C <= 1/2, inside the loop's stability bounds 2 and 1.
TEST(WallDriver, ServoGainIsCappedByItsContactsResponse) {
  LoadControl servo;
  servo.kind = LoadControl::Kind::Servo;
  servo.gain = 1e-5;
  const double dt = 1e-4;
  EXPECT_EQ(WallDriver::servo_gain(servo, dt, {}), 1e-5);                   // no contacts: its own
  EXPECT_EQ(WallDriver::servo_gain(servo, dt, {1e8, 1e3}), 1e-5);           // g (K dt + 2 C) = 0.12
  const double capped = WallDriver::servo_gain(servo, dt, {2.6e8, 7.8e4});  // the ballast bed's plate
  EXPECT_DOUBLE_EQ(capped, 0.5 / (0.5 * 2.6e8 * dt + 7.8e4));
  EXPECT_DOUBLE_EQ(capped * (2.6e8 * dt + 2 * 7.8e4), 1.0);
  EXPECT_LT(capped * 7.8e4, 0.5 + 1e-15);
}

TEST(MovingWalls, PlatesAndMeshesFollowTheirMotionInASimulation) {
  Scene s = base_scene(LinearNormal::kName, 2500, 1e7, 0.25, 0.5, 0.3, 1e4);
  s.particles.push_back(sphere({5, 5, 5}, 0.01));  // far away: only the walls move
  PrescribedMotion slide;
  slide.velocity = {0.2, 0, 0};
  s.walls.push_back(moving_plate(slide));
  PrescribedMotion spin;
  spin.angular_velocity = {0, 0, 1.0};
  spin.center = Vec3::Zero();
  WallInit mesh = mesh_wall(grid_rectangle({-1, -1, -0.5}, {2, 0, 0}, {0, 2, 0}, 2, 2));
  mesh.motion = spin;
  s.walls.push_back(mesh);
  s.time.dt = 1e-4;
  Simulation sim(s);
  for (int k = 0; k < 1000; ++k) sim.step();
  const double t = sim.time();
  EXPECT_NEAR(sim.walls()[0].corners[0].x(), 0.2 * t, 1e-12);
  const MeshWall& m = sim.meshes()[0];
  const Vec3 want = Eigen::AngleAxisd(t, Vec3::UnitZ()) * m.vertices0[0];
  EXPECT_TRUE(m.vertices[0].isApprox(want, 1e-12)) << m.vertices[0].transpose() << " vs " << want.transpose();
  EXPECT_TRUE(sim.has_moving_walls());
}

// A sphere at rest on a belt that starts moving at V: friction brings it to rolling without slip
// at 2V/7 (angular momentum about the contact point is conserved). The belt is a moving plane or a
// moving mesh; the contact must use the wall's velocity.
class Belt : public ::testing::TestWithParam<bool> {};

TEST_P(Belt, SphereReachesTwoSeventhsOfTheBeltSpeed) {
  const bool as_mesh = GetParam();
  const double r = 0.01, belt = 0.5;
  Scene s = base_scene(LinearNormal::kName, 2500, 1e8, 0.25, 0.5, 0.4, 1e5);
  s.gravity = {0, 0, -9.81};
  PrescribedMotion motion;
  motion.velocity = {belt, 0, 0};
  WallInit floor = as_mesh ? mesh_wall(grid_rectangle({-0.5, -0.5, 0}, {3, 0, 0}, {0, 1, 0}, 30, 10))
                           : plane(Vec3::Zero(), Vec3::UnitZ());
  floor.motion = motion;
  s.walls.push_back(floor);
  s.particles.push_back(sphere({0, 0, r * 0.9999}, r));
  Simulation sim(s);
  while (sim.time() < 0.3) sim.step();
  const Vec3 v = sim.particles().v[0], w = sim.particles().w[0];
  EXPECT_NEAR(v.x(), 2.0 / 7.0 * belt, 2e-3 * belt);
  // the contact point (v + w x (-r z)) moves with the belt, but for the undamped ringing of the
  // tangential spring (rzs = 0), loaded when sliding stopped
  EXPECT_NEAR(v.x() - r * w.y(), belt, 1e-2 * belt);
}

INSTANTIATE_TEST_SUITE_P(PlaneAndMesh, Belt, ::testing::Values(false, true),
                         [](const auto& info) { return std::string(info.param ? "mesh" : "plane"); });

}  // namespace
}  // namespace dem::test
