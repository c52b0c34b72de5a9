// The run statistics of legacy-formats.md section 5 (project-defined columns), one row per frame:
//   Masscenter.dat  time, centre of mass x y z of the moving (not held) particles   [s, length unit]
//   Disp_Max.dat    time, largest particle displacement since the start            [s, length unit]
//   Coord_OL.dat    time, mean coordination number (contacts per particle, walls included), mean
//                   overlap / (r_i + r_j) over touching particle pairs              [s, -, -]
//   Fragments.dat   (bonded scenes) time, fragments, particles in the largest, intact bonds, bonds
//                   broken in tension, in shear                                      [s, counts]
#pragma once

#include <string>

#include "output/legacy_output.hpp"

namespace dem {

class StatisticsWriter final : public Observer {
 public:
  // Opens the files in `folder` (appending for a continued run).
  StatisticsWriter(const std::string& folder, const Simulation& sim, bool append = false);
  void frame(const Simulation& sim) override;

 private:
  FilePtr mass_centre_, max_displacement_, coordination_, fragments_;
};

}  // namespace dem
