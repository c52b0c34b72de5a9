#include "output/statistics_output.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace dem {

StatisticsWriter::StatisticsWriter(const std::string& folder, const Simulation& sim, bool append)
    : mass_centre_(open_for_writing(folder + "/Masscenter.dat", append)),
      max_displacement_(open_for_writing(folder + "/Disp_Max.dat", append)),
      coordination_(open_for_writing(folder + "/Coord_OL.dat", append)) {
  if (!sim.bonds().empty()) fragments_ = open_for_writing(folder + "/Fragments.dat", append);
}

void StatisticsWriter::frame(const Simulation& sim) {
  const Particles& p = sim.particles();
  const Scene& scene = sim.scene();
  const double unit = scene.outputs.length_unit;
  const legacy::NumberFormat format = scene.outputs.number_format == FileNumberFormat::LegacyFixed
                                          ? legacy::NumberFormat::LegacyFixed
                                          : legacy::NumberFormat::Scientific;
  const std::size_t n = p.size();
  Vec3 centre = Vec3::Zero();
  double mass = 0, largest = 0;
  for (std::size_t i = 0; i < n; ++i) {
    largest = std::max(largest, (p.x[i] - scene.particles[p.id[i]].position).norm());
    if (p.inv_mass[i] == 0) continue;
    centre += p.mass[i] * p.x[i];
    mass += p.mass[i];
  }
  if (mass > 0) centre /= mass;
  const double t = sim.time();
  legacy::write_row(mass_centre_.get(), {t, centre.x() / unit, centre.y() / unit, centre.z() / unit}, format);
  legacy::write_row(max_displacement_.get(), {t, largest / unit}, format);

  const std::vector<int> contacts = sim.contact_counts();
  double coordination = 0, overlap = 0;
  for (int c : contacts) coordination += c;
  const std::vector<PairContact> pairs = sim.pair_contacts();
  for (const PairContact& c : pairs) {
    const double rs = p.radius[c.i] + p.radius[c.j];
    overlap += (rs - (p.x[c.i] - p.x[c.j]).norm()) / rs;
  }
  legacy::write_row(coordination_.get(),
                    {t, n > 0 ? coordination / static_cast<double>(n) : 0.0,
                     pairs.empty() ? 0.0 : overlap / static_cast<double>(pairs.size())},
                    format);
  std::fflush(mass_centre_.get());
  std::fflush(max_displacement_.get());
  std::fflush(coordination_.get());

  if (fragments_) {
    const std::vector<int> part = sim.fragments();
    std::map<int, int> size;
    for (int f : part) ++size[f];
    int biggest = 0;
    for (const auto& [f, count] : size) biggest = std::max(biggest, count);
    const BondCounts c = sim.bonds().counts();
    legacy::write_row(fragments_.get(),
                      {t, static_cast<double>(size.size()), static_cast<double>(biggest), static_cast<double>(c.intact),
                       static_cast<double>(c.tension), static_cast<double>(c.shear)},
                      legacy::NumberFormat::Scientific);
    std::fflush(fragments_.get());
  }
}

}  // namespace dem
