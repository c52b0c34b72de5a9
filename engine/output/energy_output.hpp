// Energy.dat (docs/formats.md, project-defined): one row per frame, so that conservation can be
// checked from the files:
//   time, kinetic energy of translation, of rotation, elastic energy of the contacts, of the bonds,
//   gravitational potential energy (-sum m g.x), work on the particles since the start by the walls,
//   by the external forces, by radius growth, energy dissipated since the start (the energy at the
//   start plus the work, minus the energy now: damping, friction, plastic rolling, integration
//   error), linear momentum x y z, angular momentum about the origin x y z           [s, J, N s, N m s]
// SI units whatever outputs.lengthUnit says; written in the run's number format (FULL gives every
// double exactly).
#pragma once

#include <string>

#include "output/csv_table.hpp"
#include "output/legacy_output.hpp"

namespace dem {

class EnergyWriter final : public Observer {
 public:
  EnergyWriter(const std::string& path, bool csv, bool append = false);
  void frame(const Simulation& sim) override;

  // The row the writer would write now.
  static std::vector<double> make_row(const Simulation& sim);

 private:
  SeriesFiles file_;
};

}  // namespace dem
