// Observers that write the legacy files (docs/formats.md) into a run folder as the run goes:
// every frame is written whole and flushed, so the file is readable up to its last frame even if
// the process is killed.
#pragma once

#include <cstdio>
#include <memory>
#include <string>

#include "legacy/legacy_formats.hpp"
#include "output/csv_table.hpp"
#include "output/output_file.hpp"
#include "sim/runner.hpp"

namespace dem {

// The number format of a run's files (outputs.numberFormat), and of its columns that hold counts and
// times (never the legacy fixed widths, which would round them).
legacy::NumberFormat file_format(const Simulation& sim);
legacy::NumberFormat counts_format(const Simulation& sim);

// ANIMATION_3D.dat: particles (and plates) in the scene's file length unit.
class AnimationWriter final : public Observer {
 public:
  AnimationWriter(const std::string& path, const Simulation& sim, bool append = false);
  void frame(const Simulation& sim) override;

  // The frame the writer would write now (exposed for the server's frame stream and for tests).
  static legacy::AnimationFrame make_frame(const Simulation& sim, const std::array<double, 6>& domain);

 private:
  OutputFile file_;
  std::array<double, 6> domain_{};
};

// ForceChain_3D.dat: particle-particle contacts, i < j by 1-based particle id, sorted by i.
class ForceChainWriter final : public Observer {
 public:
  explicit ForceChainWriter(const std::string& path, bool append = false);
  void frame(const Simulation& sim) override;

  static legacy::ForceChainFrame make_frame(const Simulation& sim);

 private:
  OutputFile file_;
};

// Wall.dat (the meshes at the start, merged into one, in the file length unit), written once, and
// Wall_Animation_3D.dat: each frame, every plate and the triangles of every moving mesh.
class WallWriter final : public Observer {
 public:
  // Writes Wall.dat at once when the scene has meshes; opens Wall_Animation_3D.dat when any
  // plate or mesh moves. `folder` is the run folder.
  WallWriter(const std::string& folder, const Simulation& sim, bool append = false);
  void frame(const Simulation& sim) override;

  static legacy::WallFrame make_frame(const Simulation& sim);
  static bool wanted(const Simulation& sim);  // the scene has meshes or moving walls

 private:
  OutputFile animation_;
};

// Wall_ForceChain_3D.dat: particle-wall contacts of each frame.
class WallForceChainWriter final : public Observer {
 public:
  explicit WallForceChainWriter(const std::string& path, bool append = false);
  void frame(const Simulation& sim) override;
  static legacy::WallForceChainFrame make_frame(const Simulation& sim);

 private:
  OutputFile file_;
};

// Force_Displacement.dat: time, displacement and force of the loading plate (the first
// load-controlled wall) at each output time.
class ForceDisplacementWriter final : public Observer {
 public:
  ForceDisplacementWriter(const std::string& path, const Simulation& sim, bool append = false);
  void frame(const Simulation& sim) override;
  static int loading_wall(const Simulation& sim);  // index in Scene::walls, or -1 (now)
  // Some wall has a load, from the start or from a stage on (rows are written while one has).
  static bool wanted(const Simulation& sim);

 private:
  SeriesFiles file_;
};

// restart.dat: the whole state at each frame (sim/state_io.hpp), replaced atomically, so that a run
// stopped for any reason can be continued from its last frame (`dem run --restart`).
class StateWriter final : public Observer {
 public:
  explicit StateWriter(std::string path) : path_(std::move(path)) {}
  void frame(const Simulation& sim) override;

 private:
  std::string path_;
};

// The domain box written in each frame header: the scene's, or the initial extent of the bodies.
std::array<double, 6> frame_domain(const Simulation& sim);

}  // namespace dem
