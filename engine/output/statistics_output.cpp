#include "output/statistics_output.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace dem {

namespace {
std::string in_length(const Simulation& sim, const std::string& name) {
  return name + " (" + sim.scene().outputs.length_unit_name + ")";
}
}  // namespace

StatisticsWriter::StatisticsWriter(const std::string& folder, const Simulation& sim, bool append)
    : mass_centre_(folder + "/Masscenter.dat",
                   {"time (s)", in_length(sim, "x"), in_length(sim, "y"), in_length(sim, "z")}, sim.scene().outputs.csv,
                   append),
      max_displacement_(folder + "/Disp_Max.dat", {"time (s)", in_length(sim, "largest displacement")},
                        sim.scene().outputs.csv, append),
      coordination_(folder + "/Coord_OL.dat",
                    {"time (s)", "coordination number (-)", "mean overlap over radius sum (-)"},
                    sim.scene().outputs.csv, append) {
  const bool csv = sim.scene().outputs.csv;
  // bonds now, or from the stage that glues them (the rows before count every sphere as a fragment)
  const bool glued_later = sim.scene().bonds && sim.scene().bonding_stage() >= 0;
  if (!sim.bonds().empty() || glued_later) {
    fragments_ = SeriesFiles(folder + "/Fragments.dat",
                             {"time (s)", "fragments", "particles in the largest", "intact bonds",
                              "bonds broken in tension", "bonds broken in shear"},
                             csv, append);
    fragment_sizes_ = SeriesFiles(folder + "/Fragment_Sizes.dat",
                                  {"time (s)", "fragment size (particles)", "fragments of that size"}, csv, append);
    breaks_ =
        SeriesFiles(folder + "/Bond_Breaks.dat",
                    {"time of the break (s)", "particle i", "particle j", "mode (1 tension; 2 shear)"}, csv, append);
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
  mass_centre_.write({t, centre.x() / unit, centre.y() / unit, centre.z() / unit}, format);
  max_displacement_.write({t, largest / unit}, format);

  const std::vector<int> contacts = sim.contact_counts();
  double coordination = 0, overlap = 0;
  for (int c : contacts) coordination += c;
  const std::vector<PairContact> pairs = sim.pair_contacts();
  for (const PairContact& c : pairs) {
    const double rs = p.radius[c.i] + p.radius[c.j];
    overlap += (rs - (p.x[c.i] - p.x[c.j]).norm()) / rs;
  }
  coordination_.write({t, n > 0 ? coordination / static_cast<double>(n) : 0.0,
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
    fragments_.write({t, static_cast<double>(size.size()), static_cast<double>(biggest), static_cast<double>(c.intact),
                      static_cast<double>(c.tension), static_cast<double>(c.shear)},
                     counts);
    fragments_.flush();
    std::map<int, int> by_size;  // fragment size -> how many
    for (const auto& [f, count] : size) ++by_size[count];
    for (const auto& [s, count] : by_size)
      fragment_sizes_.write({t, static_cast<double>(s), static_cast<double>(count)}, counts);
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
      breaks_.write({b.time, static_cast<double>(b.i), static_cast<double>(b.j), static_cast<double>(b.mode)}, counts);
    breaks_.flush();
  }
}

}  // namespace dem
