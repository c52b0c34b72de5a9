#include "output/statistics_output.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace dem {

StatisticsWriter::StatisticsWriter(const std::string& folder, const Simulation& sim, bool append)
    : mass_centre_(folder + "/Masscenter.dat", append),
      max_displacement_(folder + "/Disp_Max.dat", append),
      coordination_(folder + "/Coord_OL.dat", append) {
  // bonds now, or from the stage that glues them (the rows before count every sphere as a fragment)
  const bool glued_later = sim.scene().bonds && sim.scene().bonding_stage() >= 0;
  if (!sim.bonds().empty() || glued_later) {
    fragments_ = OutputFile(folder + "/Fragments.dat", append);
    fragment_sizes_ = OutputFile(folder + "/Fragment_Sizes.dat", append);
    breaks_ = OutputFile(folder + "/Bond_Breaks.dat", append);
    // a continued run has written the breaks before its saved state already
    const std::vector<int>& id = sim.particles().id;
    if (append)
      for (const Bond& b : sim.bonds().bonds())
        if (b.state != BondBreak::Intact) break_written_.insert(std::minmax(id[b.i], id[b.j]));
  }
}

void StatisticsWriter::frame(const Simulation& sim) {
  const Particles& p = sim.particles();
  const Scene& scene = sim.scene();
  const double unit = scene.outputs.length_unit;
  const legacy::NumberFormat format = file_format(sim), counts = counts_format(sim);
  const std::size_t n = p.size();
  Vec3 centre = Vec3::Zero();
  double mass = 0, largest = 0;
  for (std::size_t i = 0; i < n; ++i) {
    largest = std::max(largest, (p.x[i] - scene.particles[p.id[i]].position).norm());
    // a clump member carries its whole body's mass: its body is counted once, below
    if (p.inv_mass[i] == 0 || (!p.body.empty() && p.body[i] >= 0)) continue;
    centre += p.mass[i] * p.x[i];
    mass += p.mass[i];
  }
  const ClumpBodies& bodies = sim.state().bodies;
  for (std::size_t b = 0; b < bodies.x.size(); ++b) {
    centre += bodies.mass[b] * bodies.x[b];
    mass += bodies.mass[b];
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
  mass_centre_.flush();
  max_displacement_.flush();
  coordination_.flush();

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
                      counts);
    fragments_.flush();
    std::map<int, int> by_size;  // fragment size -> how many
    for (const auto& [f, count] : size) ++by_size[count];
    for (const auto& [s, count] : by_size)
      legacy::write_row(fragment_sizes_.get(), {t, static_cast<double>(s), static_cast<double>(count)}, counts);
    fragment_sizes_.flush();
    struct Break {
      double time;
      int i, j, mode;
    };
    std::vector<Break> fresh;
    const std::vector<Bond>& bonds = sim.bonds().bonds();
    for (const Bond& bond : bonds) {
      if (bond.state == BondBreak::Intact) continue;
      const auto ids = std::minmax(p.id[bond.i], p.id[bond.j]);
      if (!break_written_.insert(ids).second) continue;
      fresh.push_back({bond.broken_at, ids.first + 1, ids.second + 1, bond.state == BondBreak::Tension ? 1 : 2});
    }
    std::sort(fresh.begin(), fresh.end(), [](const Break& x, const Break& y) {
      return x.time != y.time ? x.time < y.time : (x.i != y.i ? x.i < y.i : x.j < y.j);
    });
    for (const Break& b : fresh)
      legacy::write_row(breaks_.get(),
                        {b.time, static_cast<double>(b.i), static_cast<double>(b.j), static_cast<double>(b.mode)},
                        counts);
    breaks_.flush();
  }
}

}  // namespace dem
