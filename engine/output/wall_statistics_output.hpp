// BallastDEM's three wall statistics, whose names its file dialog shows (the BallastDEM manual,
// figure 3.4) but whose columns it never prints; this project defines them (docs/formats.md
// section 5), one block of rows per frame, like the other statistics:
//   Wall_Mean_Force_CN.dat   time, mean normal force of the particle-wall contacts (N), mean wall
//                            coordination number (particles touching a wall, averaged over the
//                            scene's walls), particle-wall contacts                       [s, N, -, -]
//   Wall_PDF_CoordN.dat      per frame, one row per coordination number Z from 0 to the largest:
//                            time, Z, the share of grains with Z contacts (walls included; a clump
//                            is one grain with its members' contacts)                     [s, -, -]
//   Wall_PDF_ForceChain.dat  per frame, the probability density of the normal contact force over
//                            every touching contact (pairs and walls), [0, the largest] in bins
//                            about a tenth of the mean force wide: time, bin centre, density
//                                                                                         [s, N, 1/N]
// Written for every scene with a wall.
#pragma once

#include <string>
#include <vector>

#include "output/legacy_output.hpp"

namespace dem {

class WallStatisticsWriter final : public Observer {
 public:
  static bool wanted(const Simulation& sim) { return !sim.scene().walls.empty(); }
  // Opens the files in `folder` (appending for a continued run).
  WallStatisticsWriter(const std::string& folder, bool csv, bool append = false);
  void frame(const Simulation& sim) override;

  // The normal forces' histogram as (bin centre, density) rows: [0, the largest force] in
  // ceil(10 largest / mean) bins (at most 1,000); none without a positive force.
  static std::vector<std::pair<double, double>> force_density(const std::vector<double>& forces);

 private:
  SeriesFiles mean_force_, coordination_pdf_, force_pdf_;
};

}  // namespace dem
