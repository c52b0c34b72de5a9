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
//   walls_STEP.vtp      the walls where they are: plates, meshes' triangles, and each plane as a
//                       square about the particles (runs with walls).
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "output/vtk_files.hpp"
#include "sim/runner.hpp"

namespace dem {

class VtkWriter final : public Observer {
 public:
  // `folder` is the run folder. A continued run (`append`) lists in its series the frames already
  // there up to the step it continues from.
  VtkWriter(const std::string& folder, const Simulation& sim, bool append = false);
  void frame(const Simulation& sim) override;

  static constexpr const char* kKinds[] = {"particles", "contacts", "bonds", "walls"};
  // The frame file of `kind` at `step` (particles_0000012000.vtu).
  static std::string frame_name(const std::string& kind, std::int64_t step);

 private:
  void add_to_series(const std::string& kind, std::int64_t step, double time);

  std::string folder_;
  double dt_ = 0;
  std::map<std::string, std::map<std::int64_t, vtk::SeriesEntry>> series_;  // by kind, by step
};

}  // namespace dem
