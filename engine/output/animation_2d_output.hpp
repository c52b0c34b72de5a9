// ANIMATION_2D.dat: a 2D run's discs (Scene::plane) in the x-z plane, and where its plates and moving meshes
// cross the plane, in the scene's file length unit (docs/formats.md section 3a).
#pragma once

#include <array>
#include <optional>
#include <string>

#include "legacy/legacy_formats.hpp"
#include "output/legacy_output.hpp"

namespace dem {

class Animation2DWriter final : public Observer {
 public:
  Animation2DWriter(const std::string& path, const Simulation& sim, bool append = false);
  void frame(const Simulation& sim) override;

  // The frame the writer would write now (exposed for tests).
  static legacy::Animation2DFrame make_frame(const Simulation& sim, const std::array<double, 4>& domain);

 private:
  OutputFile file_;
  std::array<double, 4> domain_{};
};

// Where a flat convex polygon (a plate, a triangle) crosses the plane y = 0: the segment between its two farthest
// crossing points, or nothing when it misses the plane or only touches it at a point.
std::optional<std::array<Vec3, 2>> trace_on_plane(const Vec3* corners, int count);

}  // namespace dem
