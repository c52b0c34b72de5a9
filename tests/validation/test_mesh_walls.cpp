// Triangle-mesh walls against analytic ones (validation.md section 4): the same sphere on the same
// plane, once analytic and once cut into triangles, must move the same way, with no impulse where
// it crosses edges and vertices; a sphere bouncing in a box of triangles must follow the path it
// follows in a box of planes, corners included; rolling resistance and friction act as on a plane.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/meshes.hpp"
#include "support/report.hpp"
#include "support/scenes.hpp"

namespace dem::test::test_mesh_walls {
namespace {

constexpr double kR = 0.01, kG = 9.81;

struct MeshInclineCase {
  std::string_view model;
  double theta_deg, mu;
  double lateral;  // offset of the path across the grid: 0 runs along grid lines, through vertices
};

// An incline tilted about y (+x' downhill), as an analytic plane or as a 0.7 m x 0.2 m grid of
// 35 x 10 cells (700 triangles) in the same plane, cells of one sphere diameter.
Scene incline_scene(const MeshInclineCase& c, bool as_mesh) {
  const double th = c.theta_deg * std::numbers::pi / 180;
  Scene s = base_scene(c.model, 2500, 1e8, 0.25, 0.5, c.mu, 1e5);
  s.gravity = {0, 0, -kG};
  const Vec3 normal(std::sin(th), 0, std::cos(th));
  const Vec3 downhill(std::cos(th), 0, -std::sin(th));
  if (as_mesh) {
    s.walls.push_back(
        mesh_wall(grid_rectangle(-0.1 * downhill - Vec3(0, 0.1, 0), 0.7 * downhill, {0, 0.2, 0}, 35, 10)));
  } else {
    s.walls.push_back(plane(Vec3::Zero(), normal));
  }
  s.particles.push_back(sphere(normal * kR * 0.9999 + Vec3(0, c.lateral, 0), kR));
  return s;
}

class MeshIncline : public ::testing::TestWithParam<MeshInclineCase> {};

TEST_P(MeshIncline, MovesAsOnTheAnalyticPlaneWithNoKickAtEdges) {
  const MeshInclineCase c = GetParam();
  const double th = c.theta_deg * std::numbers::pi / 180;
  const Vec3 normal(std::sin(th), 0, std::cos(th));
  const Vec3 downhill(std::cos(th), 0, -std::sin(th));
  Simulation on_plane(incline_scene(c, false));
  Scene mesh_scene = incline_scene(c, true);
  mesh_scene.time.dt = on_plane.dt();  // the mesh reaches lower, which would shorten the automatic step
  Simulation on_mesh(mesh_scene);
  double worst_kick = 0, v1_plane = 0, v1_mesh = 0, t1 = 0;
  while (on_mesh.time() < 0.4) {
    on_plane.step();
    on_mesh.step();
    const Vec3 vp = on_plane.particles().v[0], vm = on_mesh.particles().v[0];
    worst_kick = std::max(worst_kick, std::abs((vm - vp).dot(normal)) / std::max(vm.norm(), 1e-3));
    if (t1 == 0 && on_mesh.time() >= 0.1) {
      t1 = on_mesh.time();
      v1_plane = vp.dot(downhill);
      v1_mesh = vm.dot(downhill);
    }
  }
  const double span = on_mesh.time() - t1;
  const double a_plane = (on_plane.particles().v[0].dot(downhill) - v1_plane) / span;
  const double a_mesh = (on_mesh.particles().v[0].dot(downhill) - v1_mesh) / span;
  const bool slides = std::tan(th) > 3.5 * c.mu;
  const double want = slides ? kG * (std::sin(th) - c.mu * std::cos(th)) : 5.0 / 7.0 * kG * std::sin(th);
  const std::string name = std::string(c.model == HertzNormal::kName ? "hertz" : "linear") +
                           (slides ? " sliding" : " rolling") +
                           (c.lateral == 0 ? " along grid lines" : " across cells");
  report(name + " acceleration on the mesh", a_mesh, want);
  report(name + " normal velocity kick / speed", worst_kick, 0.0);
  EXPECT_NEAR(a_mesh, a_plane, 1e-3 * a_plane);
  EXPECT_NEAR(a_mesh, want, 1e-3 * want);
  EXPECT_LT(worst_kick, 1e-6);
  // it did cross the grid: 0.15 m or more is over 7 cells and 15 edges
  EXPECT_GT((on_mesh.particles().x[0] - on_mesh.scene().particles[0].position).norm(), 0.15);
}

INSTANTIATE_TEST_SUITE_P(SphereOnTessellatedIncline, MeshIncline,
                         ::testing::Values(MeshInclineCase{LinearNormal::kName, 30, 0.1, 0.0},
                                           MeshInclineCase{LinearNormal::kName, 30, 0.1, 0.0073},
                                           MeshInclineCase{LinearNormal::kName, 20, 0.5, 0.0},
                                           MeshInclineCase{HertzNormal::kName, 30, 0.1, 0.0073},
                                           MeshInclineCase{HertzNormal::kName, 20, 0.5, 0.0}),
                         [](const auto& info) {
                           const auto& c = info.param;
                           return std::string(c.model == HertzNormal::kName ? "hertz" : "linear") +
                                  (std::tan(c.theta_deg * std::numbers::pi / 180) > 3.5 * c.mu ? "_sliding"
                                                                                               : "_rolling") +
                                  (c.lateral == 0 ? "_through_vertices" : "_across_cells");
                         });

// A spinning sphere thrown into a corner of a 10 cm box, with friction and e = 0.8 and no gravity
// (so that it meets the three faces of a corner at once, and again at the opposite corner): the
// box as six analytic planes, or as six faces of 3 x 3 cells (108 triangles).
Scene bouncing_box(bool as_mesh) {
  Scene s = base_scene(HertzNormal::kName, 2500, 1e8, 0.25, 0.8, 0.3);
  const double side = 0.1;
  if (as_mesh) {
    s.walls.push_back(mesh_wall(box_mesh(Vec3::Zero(), Vec3::Constant(side), 3)));
  } else {
    for (int axis = 0; axis < 3; ++axis) {
      const Vec3 e = Vec3::Unit(axis);
      s.walls.push_back(plane(Vec3::Zero(), e, "low"));
      s.walls.push_back(plane(side * e, -e, "high"));
    }
  }
  // aimed at the corner (0.1, 0.1, 0.1): it meets three faces at once
  s.particles.push_back(sphere(Vec3::Constant(0.05), kR, Vec3(1.0, 1.0, 1.0), Vec3(5, -20, 10)));
  return s;
}

TEST(MeshBox, SphereBouncesAsInABoxOfPlanesThroughCorners) {
  Simulation planes(bouncing_box(false)), mesh(bouncing_box(true));
  ASSERT_EQ(planes.dt(), mesh.dt());
  double worst = 0;
  int corner_hits = 0;
  while (mesh.time() < 0.5) {
    planes.step();
    mesh.step();
    worst = std::max(worst, (planes.particles().x[0] - mesh.particles().x[0]).norm() / 0.1);
    worst = std::max(worst, (planes.particles().v[0] - mesh.particles().v[0]).norm() / 1.7);
    int touching = 0;
    for (int c : mesh.contact_counts()) touching += c;
    corner_hits += touching >= 3;
  }
  report("box of triangles vs planes: largest relative difference", worst, 0.0);
  EXPECT_LT(worst, 1e-9);
  EXPECT_GT(corner_hits, 0) << "the sphere never touched three faces at once";
}

// Rolling resistance and friction on a mesh: a sphere rolling across a tessellated floor stops
// where it stops on the analytic floor (validation.md section 3: distance 7 v0^2 / (10 mu_r g)).
TEST(MeshFloor, RollingResistanceStopsTheSphereAsOnAPlane) {
  auto scene = [](bool as_mesh) {
    Scene s = base_scene(LinearNormal::kName, 2500, 1e8, 0.25, 0.5, 0.5, 1e5);
    set_rolling(s, CdtRolling::kName, 0.1);
    s.gravity = {0, 0, -kG};
    if (as_mesh)
      s.walls.push_back(mesh_wall(grid_rectangle({-0.2, -0.2, 0}, {1.0, 0, 0}, {0, 0.4, 0}, 50, 20)));
    else
      s.walls.push_back(plane(Vec3::Zero(), Vec3::UnitZ()));
    const double v0 = 0.5;
    s.particles.push_back(sphere({0, 0.0031, kR * 0.9999}, kR, {v0, 0, 0}, {0, v0 / kR, 0}));
    return s;
  };
  Simulation on_plane(scene(false)), on_mesh(scene(true));
  while (on_mesh.time() < 0.9) {  // it stops after 7 v0 / (5 mu_r g) = 0.71 s
    on_plane.step();
    on_mesh.step();
  }
  const double want = 7 * 0.5 * 0.5 / (10 * 0.1 * kG);
  const double d_plane = on_plane.particles().x[0].x(), d_mesh = on_mesh.particles().x[0].x();
  report("stopping distance on the mesh", d_mesh, want);
  EXPECT_NEAR(d_mesh, d_plane, 1e-3 * d_plane);
  EXPECT_NEAR(d_mesh, want, 0.02 * want);
  EXPECT_LT(on_mesh.particles().v[0].norm(), 1e-3);
}

}  // namespace
}  // namespace dem::test::test_mesh_walls
