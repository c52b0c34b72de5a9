// ParaView's files of a run (VTK XML, output/vtk_files.hpp), beside the legacy ones, one set per
// frame, named by the frame's step, with a .pvd series per kind that ParaView opens as one dataset
// in time:
//   particles_STEP.vtu  the spheres as points (lengths in m, SI units throughout) with id, radius,
//                       mass, material, velocity, angularVelocity, displacement, force, and where
//                       the run has them contacts, clump and fragment;
//   contacts_STEP.vtp   each touching pair as a line between the centres, normalForce and
//                       tangentialForce (the force chains);
//   bonds_STEP.vtp      each bond as a line, its state (0 intact, 1 broken in tension, 2 in shear),
//                       normalForce and shearForce (runs with bonds);
//   walls_STEP.vtp      the walls that move, come or go, where they are: plates, meshes' triangles,
//                       and each plane as a square about the particles;
//   walls.vtp           the walls that stay where they are all run, once.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "output/vtk_files.hpp"
#include "sim/runner.hpp"

namespace dem {

class VtkWriter final : public Observer {
 public:
  // `folder` is the run folder. A continued run (`append`) lists in its series the frames already
  // there up to the step it continues from.
  VtkWriter(const std::string& folder, const Simulation& sim, bool append = false);
  void frame(const Simulation& sim) override;

  // The frame file of `kind` at `step` (particles_0000012000.vtu).
  static std::string frame_name(const std::string& kind, std::int64_t step);
  // Removes the files of this kind an earlier run left in `folder` (its frames, series and static
  // walls): a new run's series must not pick up another run's frames, and stale frames must not
  // look like this run's.
  static void remove_earlier(const std::string& folder);

 private:
  void add_to_series(const std::string& kind, std::int64_t step, double time);

  std::string folder_;
  std::vector<int> moving_walls_, fixed_walls_;  // scene walls
  struct Series {
    std::unique_ptr<vtk::SeriesFile> file;
    std::int64_t last_step = -1;
  };
  std::map<std::string, Series> series_;  // by kind
};

}  // namespace dem
