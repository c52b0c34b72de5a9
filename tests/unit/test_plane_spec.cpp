// A 2D run in the spec (JobSpec.dimension, .discThickness; spec/plane_section.cpp): discs made in the plane by
// lattices, packings and sources, and each field that would leave the plane refused by its path.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "spec/spec_loader.hpp"
#include "support/spec_problems.hpp"

namespace dem::test {
namespace {

// Discs in a box 0.1 m wide, open at the top; `particles` and `extra` are spliced in.
std::string planar(const std::string& particles, const std::string& extra = "",
                   const std::string& dimension = R"("dimension": 2,)") {
  return R"({
  )" + dimension +
         R"(
  "materials": [
    {"name": "glass", "density": 2500, "youngsModulus": 1e8, "poissonRatio": 0.25},
    {"name": "steel", "rigid": true}
  ],
  "interactions": [
    {"a": "glass", "b": "glass", "restitution": 0.5, "friction": 0.5},
    {"a": "glass", "b": "steel", "restitution": 0.5, "friction": 0.5}
  ],
  "contact": {"normal": "HERTZ"},
  "walls": [
    {"name": "floor", "material": "steel", "plane": {"normal": {"z": 1}}},
    {"name": "left", "material": "steel", "plane": {"normal": {"x": 1}}},
    {"name": "right", "material": "steel", "plane": {"point": {"x": 0.1}, "normal": {"x": -1}}}
  ],
  "gravity": {"z": -9.81},
  "time": {"duration": 0.1},
  )" + extra +
         particles + "\n}";
}

const char* kHexLattice = R"("lattices": [{"kind": "HEX", "min": {}, "max": {"x": 0.1, "y": 0.01, "z": 0.05},
  "radius": 0.005, "spacing": 0.999, "material": "glass"}])";

TEST(PlaneSpec, ADimensionTwoSceneHasDiscsOfItsThicknessAtYZero) {
  const Scene scene = spec::to_scene(spec::parse_json(planar(kHexLattice, R"("discThickness": 0.02,)")));
  ASSERT_TRUE(scene.plane);
  EXPECT_EQ(scene.plane->thickness, 0.02);
  EXPECT_EQ(scene.grain().mass(2500, 0.005), 2500 * std::numbers::pi * 0.005 * 0.005 * 0.02);
  EXPECT_EQ(scene.grain().inertia(2, 0.5), 0.25);
  ASSERT_FALSE(scene.particles.empty());
  for (const ParticleInit& p : scene.particles) EXPECT_EQ(p.position.y(), 0);
  EXPECT_EQ(spec::to_scene(spec::parse_json(planar(kHexLattice))).plane->thickness, 1.0);  // PFC2D's unit thickness
  EXPECT_FALSE(spec::to_scene(spec::parse_json(planar(kHexLattice, "", ""))).plane);
}

TEST(PlaneSpec, AHexLatticeInThePlaneIsTheHexagonalPackingOfDiscs) {
  const Scene scene = spec::to_scene(spec::parse_json(planar(kHexLattice)));
  // rows 0.00999 m apart along x, layers sqrt(3)/2 of that apart, each disc touching six inside the packing
  const double s = 0.999 * 0.01;
  int inside = 0;
  for (const ParticleInit& a : scene.particles) {
    int touching = 0;
    for (const ParticleInit& b : scene.particles)
      if (&a != &b && (a.position - b.position).norm() < 1.0001 * s) ++touching;
    const bool interior =
        a.position.x() > 0.015 && a.position.x() < 0.085 && a.position.z() > 0.015 && a.position.z() < 0.035;
    if (interior) {
      EXPECT_EQ(touching, 6) << a.position.transpose();
      ++inside;
    }
  }
  EXPECT_GT(inside, 10);
  // the same as counts: 10 a row, 5 layers, countY left out
  const Scene counted = spec::to_scene(spec::parse_json(planar(R"("lattices": [{"kind": "HEX", "min": {},
    "radius": 0.005, "countX": 10, "countZ": 5, "material": "glass"}])")));
  EXPECT_EQ(counted.particles.size(), 50u);
  EXPECT_NEAR(counted.particles[10].position.z() - counted.particles[0].position.z(), 0.01 * std::sqrt(3.0) / 2, 1e-15);
  EXPECT_NEAR(counted.particles[10].position.x() - counted.particles[0].position.x(), 0.005, 1e-15);
}

TEST(PlaneSpec, ASquareAndAnFccLatticeInThePlane) {
  const Scene cubic = spec::to_scene(spec::parse_json(planar(R"("lattices": [{"kind": "CUBIC", "min": {},
    "max": {"x": 0.1, "z": 0.1}, "radius": 0.005, "material": "glass"}])")));
  EXPECT_EQ(cubic.particles.size(), 100u);
  const Scene fcc = spec::to_scene(spec::parse_json(planar(R"("lattices": [{"kind": "FCC", "min": {},
    "radius": 0.005, "countX": 4, "countZ": 3, "material": "glass"}])")));
  ASSERT_EQ(fcc.particles.size(), 12u);
  // the square lattice turned 45 degrees: each disc's nearest neighbours are one diameter away, on the diagonals
  const Vec3 d = fcc.particles[4].position - fcc.particles[0].position;  // the next layer's first
  EXPECT_NEAR(d.norm(), 0.01, 1e-15);
  EXPECT_NEAR(std::abs(d.x()), std::abs(d.z()), 1e-15);
}

TEST(PlaneSpec, ARandomPackingByAreaFractionFillsThatShareOfTheRectangle) {
  const Scene scene = spec::to_scene(spec::parse_json(planar(R"("packings": [{"min": {}, "max": {"x": 0.1, "z": 0.1},
    "sizes": {"kind": "UNIFORM", "dMin": 0.004, "dMax": 0.008}, "solidFraction": 0.3, "material": "glass"}])")));
  double area = 0;
  for (const ParticleInit& p : scene.particles) {
    EXPECT_EQ(p.position.y(), 0);
    area += std::numbers::pi * p.radius * p.radius;
  }
  EXPECT_NEAR(area / 0.01, 0.3, 0.01);  // within the last disc drawn
}

TEST(PlaneSpec, WhatWouldLeaveThePlaneIsRefusedByItsPath) {
  const std::string disc = R"("particles": [{"position": {"x": 0.05, "y": 0.001, "z": 0.05}, "radius": 0.005,
    "velocity": {"y": 1}, "angularVelocity": {"x": 2}, "force": {"y": 3}, "material": "glass"}])";
  const std::string problems = spec_problems(planar(disc, R"("stages": [{"duration": 0.1, "gravity": {"y": -1}}],)"));
  EXPECT_NE(problems.find("particles[0].position: a 2D run lies in the x-z plane: its y must be 0 (got 0.001)"),
            std::string::npos)
      << problems;
  EXPECT_NE(problems.find("particles[0].velocity: a 2D run lies in the x-z plane"), std::string::npos);
  EXPECT_NE(problems.find("particles[0].force: a 2D run lies"), std::string::npos);
  EXPECT_NE(problems.find("particles[0].angularVelocity: a 2D run's discs turn about y only"), std::string::npos);
  EXPECT_NE(problems.find("stages[0].gravity: a 2D run lies in the x-z plane"), std::string::npos);
}

TEST(PlaneSpec, ThreeDimensionalPartsAreRefusedWithTheReason) {
  EXPECT_EQ(spec_problems(planar(kHexLattice, R"("dimension": 4,)", "")),
            "dimension: must be 2 (discs in the x-z plane) or 3 (got 4)\n");
  EXPECT_EQ(spec_problems(planar(kHexLattice, R"("discThickness": 0.1,)", "")),
            "discThickness: is for a 2D run's discs: give dimension 2, or leave it out\n");
  EXPECT_NE(spec_problems(planar(kHexLattice, R"("discThickness": -1,)"))
                .find("discThickness: must be a positive number (got -1)"),
            std::string::npos);
  const std::string tilted = planar(kHexLattice, R"("stages": [{"duration": 0.1, "addWalls": [{"name": "tilted",
    "material": "steel", "plane": {"point": {"z": 1}, "normal": {"y": 1, "z": -1}}}]}],)");
  EXPECT_NE(spec_problems(tilted).find("stages[0].addWalls[0].plane.normal: a 2D run's plane walls stand across"),
            std::string::npos)
      << spec_problems(tilted);
  const std::string turning = planar(kHexLattice, R"("stages": [{"duration": 0.1, "wallChanges": [{"wall": "left",
    "motion": {"angularVelocity": {"z": 1}}}]}],)");
  EXPECT_NE(spec_problems(turning).find("stages[0].wallChanges[0].motion.angularVelocity: a 2D run's walls turn"),
            std::string::npos)
      << spec_problems(turning);
  const std::string face = planar(kHexLattice, R"("sources": [{"face": "floor", "material": "glass",
    "sizes": {"kind": "ONE_SIZE", "mean": 0.004}, "countRate": 10}],)");
  EXPECT_NE(spec_problems(face).find("sources[0].face: a 2D run's sources are boxes"), std::string::npos)
      << spec_problems(face);
  const std::string counted = planar(R"("lattices": [{"kind": "HEX", "min": {}, "radius": 0.005, "countX": 2,
    "countY": 3, "countZ": 2, "material": "glass"}])");
  EXPECT_NE(spec_problems(counted).find("lattices[0].countY: a 2D lattice is one layer at y = 0"), std::string::npos);
}

// A reviewer's finds: a source box and the domain needed a y range the docs said was not used; plates beside the
// plane, tilted across it or moved or loaded along y acted on the discs in 3D where the files drew nothing; a
// dimension or disc thickness of 0 was taken for its default.
TEST(PlaneSpec, BoxesNeedNoYRangeAndZeroIsNotADefault) {
  const std::string source = planar(kHexLattice, R"("sources": [{"min": {"z": 0.2}, "max": {"x": 0.1, "z": 0.3},
    "material": "glass", "sizes": {"kind": "ONE_SIZE", "mean": 0.004}, "countRate": 10}],
    "domain": {"min": {"x": -0.1}, "max": {"x": 0.2, "z": 0.4}},)");
  EXPECT_EQ(spec_problems(source), "");
  EXPECT_EQ(spec_problems(planar(kHexLattice, R"("dimension": 0,)", "")),
            "dimension: must be 2 (discs in the x-z plane) or 3 (got 0)\n");
  EXPECT_NE(spec_problems(planar(kHexLattice, R"("discThickness": 0,)")).find("discThickness: must be a positive"),
            std::string::npos);
}

TEST(PlaneSpec, PlatesAndMotionsThatWouldActOffThePlaneAreRefused) {
  auto with_plate = [](const std::string& c, const std::string& more = "") {
    return planar(kHexLattice, R"("stages": [{"duration": 0.1, "addWalls": [{"name": "p", "material": "steel",
      "plate": )" + c + "}" + more +
                                   "]}],");
  };
  const std::string across = R"({"c1": {"y": -1}, "c2": {"x": 1, "y": -1}, "c3": {"x": 1, "y": 1}, "c4": {"y": 1}})";
  EXPECT_EQ(spec_problems(with_plate(across)).find(".plate:"), std::string::npos);
  const std::string beside =
      R"({"c1": {"y": 0.005}, "c2": {"x": 1, "y": 0.005}, "c3": {"x": 1, "y": 1}, "c4": {"y": 1}})";
  EXPECT_NE(spec_problems(with_plate(beside))
                .find("stages[0].addWalls[0].plate: a 2D run's plates reach across the "
                      "plane y = 0 (this one spans y from 0.005 to 1)"),
            std::string::npos)
      << spec_problems(with_plate(beside));
  const std::string tilted = R"({"c1": {"y": -1, "z": -1}, "c2": {"x": 1, "y": -1, "z": -1}, "c3": {"x": 1, "y": 1,
    "z": 1}, "c4": {"y": 1, "z": 1}})";
  EXPECT_NE(spec_problems(with_plate(tilted)).find("stages[0].addWalls[0].plate: a 2D run's plates stand across"),
            std::string::npos);
  const std::string sliding = planar(kHexLattice, R"("stages": [{"duration": 0.1, "wallChanges": [{"wall": "left",
    "motion": {"velocity": {"y": 1}, "amplitude": {"y": 2}}}, {"wall": "right", "load": {"direction": {"y": -1},
    "servo": {"target": 1, "gain": 1e-3, "maxSpeed": 1}}}]}],)");
  const std::string problems = spec_problems(sliding);
  EXPECT_NE(problems.find("stages[0].wallChanges[0].motion.velocity: a 2D run's walls move in the x-z plane"),
            std::string::npos)
      << problems;
  EXPECT_NE(problems.find("stages[0].wallChanges[0].motion.amplitude: a 2D run's walls move"), std::string::npos);
  EXPECT_NE(problems.find("stages[0].wallChanges[1].load.direction: a 2D run's loaded walls push in the x-z plane"),
            std::string::npos);
}

}  // namespace
}  // namespace dem::test
