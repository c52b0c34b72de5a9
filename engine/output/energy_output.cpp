#include "output/energy_output.hpp"

namespace dem {

EnergyWriter::EnergyWriter(const std::string& path, bool csv, bool append)
    : file_(path,
            {"time (s)", "kinetic translation (J)", "kinetic rotation (J)", "elastic contacts (J)", "elastic bonds (J)",
             "gravitational (J)", "work of walls (J)", "work of external forces (J)", "work of growth (J)",
             "dissipated (J)", "momentum x (N s)", "momentum y (N s)", "momentum z (N s)", "angular momentum x (N m s)",
             "angular momentum y (N m s)", "angular momentum z (N m s)"},
            csv, append) {}

std::vector<double> EnergyWriter::make_row(const Simulation& sim) {
  const double kinetic = sim.kinetic_energy(), rotation = sim.rotational_energy();
  const double translation = sim.translational_energy();  // on its own: the difference's round-off went below 0
  const double contacts = sim.contact_summary().elastic_energy, bonds = sim.bonds().elastic_energy();
  const double gravity = sim.gravitational_energy();
  const EnergyLedger& in = sim.energy_input();
  const double dissipated = in.initial_energy + in.total() - (kinetic + contacts + bonds + gravity);
  const Vec3 p = sim.linear_momentum(), l = sim.angular_momentum();
  return {sim.time(), translation, rotation, contacts, bonds, gravity, in.walls, in.external,
          in.growth,  dissipated,  p.x(),    p.y(),    p.z(), l.x(),   l.y(),    l.z()};
}

void EnergyWriter::frame(const Simulation& sim) {
  file_.write(make_row(sim), counts_format(sim));
  file_.flush();
}

}  // namespace dem
