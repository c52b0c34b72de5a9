// A small scene with every kind of state and work but growth and sources: loose spheres and a
// two-sphere clump on a mesh floor, bonded pairs, a cyclically loaded plate (its lid at `lid_z`),
// rolling resistance (rolling springs). For the tests of saved states and of the profile.
#pragma once

#include <string>

namespace dem::test {

inline std::string everything_spec(double lid_z, double duration, const std::string& outputs = "{}") {
  const std::string z = std::to_string(lid_z);
  return R"({"name": "everything",
  "materials": [{"name": "rock", "density": 2600, "youngsModulus": 1e7, "poissonRatio": 0.25}],
  "interactions": [{"a": "rock", "b": "rock", "restitution": 0.5, "friction": 0.5, "rollingFriction": 0.05}],
  "contact": {"normal": "HERTZ", "rolling": "EPSD"},
  "gravity": {"z": -9.81},
  "particles": [
    {"material": "rock", "position": {"x": 0.0, "z": 0.0101}, "radius": 0.01},
    {"material": "rock", "position": {"x": 0.0199, "z": 0.0101}, "radius": 0.01},
    {"material": "rock", "position": {"x": 0.05, "z": 0.0102}, "radius": 0.01, "velocity": {"x": 0.1}},
    {"material": "rock", "position": {"x": 0.0, "y": 0.03, "z": 0.012}, "radius": 0.012}],
  "bonds": {"youngsModulus": 1e7, "tensileStrength": 1e6, "shearStrength": 1e6, "gapTolerance": 0.05},
  "clumpShapes": [{"name": "pair", "spheres": [{"center": {"x": -0.006}, "radius": 0.01}, {"center": {"x": 0.006}, "radius": 0.01}]}],
  "clumps": [{"shape": "pair", "material": "rock", "position": {"x": 0.05, "y": 0.04, "z": 0.0105}}],
  "walls": [
    {"name": "floor", "material": "rock", "mesh": {
      "vertices": [{"x": -0.1, "y": -0.1}, {"x": 0.2, "y": -0.1}, {"x": 0.2, "y": 0.2}, {"x": -0.1, "y": 0.2}],
      "triangles": [{"i": 1, "j": 2, "k": 3}, {"i": 1, "j": 3, "k": 4}]}},
    {"name": "lid", "material": "rock", "plate": {"c1": {"x": -0.1, "y": -0.1, "z": )" +
         z + R"(}, "c2": {"x": 0.2, "y": -0.1, "z": )" + z + R"(}, "c3": {"x": 0.2, "y": 0.2, "z": )" + z +
         R"(}, "c4": {"x": -0.1, "y": 0.2, "z": )" + z + R"(}},
     "load": {"mass": 0.1, "cyclic": {"fMin": 0.1, "fMax": 1, "frequency": 10, "cycles": 1}}}],
  "time": {"duration": )" +
         std::to_string(duration) + R"(},
  "outputs": )" +
         outputs + "}";
}

}  // namespace dem::test
