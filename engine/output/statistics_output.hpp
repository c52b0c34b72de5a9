// The run statistics of legacy-formats.md section 5 (project-defined columns), one row per frame:
//   Masscenter.dat  time, centre of mass x y z of the moving (not held) particles   [s, length unit]
//   Disp_Max.dat    time, largest particle displacement since the start            [s, length unit]
//   Coord_OL.dat    time, mean coordination number (contacts per particle, walls included), mean
//                   overlap / (r_i + r_j) over touching particle pairs              [s, -, -]
//   Fragments.dat   (bonded scenes) time, fragments, particles in the largest, intact bonds, bonds
//                   broken in tension, in shear                                      [s, counts]
//   Fragment_Sizes.dat  (bonded scenes) per frame, one row per fragment size: time, size
//                   (particles), number of fragments of that size                    [s, counts]
//   Bond_Breaks.dat (bonded scenes) one row per bond broken since the last frame: time of the
//                   break, 1-based ids i < j, mode (1 tension, 2 shear)              [s, -, -, -]
#pragma once

#include <set>
#include <string>
#include <utility>

#include "output/csv_table.hpp"
#include "output/legacy_output.hpp"

namespace dem {

class StatisticsWriter final : public Observer {
 public:
  // Opens the files in `folder` (appending for a continued run).
  StatisticsWriter(const std::string& folder, const Simulation& sim, bool append = false);
  void frame(const Simulation& sim) override;

 private:
  SeriesFiles mass_centre_, max_displacement_, coordination_, fragments_, fragment_sizes_, breaks_;
  std::set<std::pair<int, int>> break_written_;  // broken bonds already written, by their particles' ids
};

}  // namespace dem
