#include "output/wall_statistics_output.hpp"

#include <algorithm>
#include <cmath>

namespace dem {

WallStatisticsWriter::WallStatisticsWriter(const std::string& folder, bool csv, bool append)
    : mean_force_(folder + "/Wall_Mean_Force_CN.dat",
                  {"time (s)", "mean wall contact force (N)", "wall coordination number (-)", "wall contacts"}, csv,
                  append),
      coordination_pdf_(folder + "/Wall_PDF_CoordN.dat", {"time (s)", "coordination number", "share of the grains (-)"},
                        csv, append),
      force_pdf_(folder + "/Wall_PDF_ForceChain.dat", {"time (s)", "force bin centre (N)", "probability density (1/N)"},
                 csv, append) {}

std::vector<std::pair<double, double>> WallStatisticsWriter::force_density(const std::vector<double>& forces) {
  double sum = 0, largest = 0;
  for (double f : forces) {
    sum += f;
    largest = std::max(largest, f);
  }
  if (!(largest > 0)) return {};
  // [0, largest] cut into bins about a tenth of the mean wide: the largest force closes the last
  // bin (a bin edge at the mean put equal forces in a bin past them, by round-off or not). A force
  // of 1e15 N beside thousands near zero would ask for 1e13 bins: past 1,000 the bins widen.
  const double tenths = 10 * largest / (sum / static_cast<double>(forces.size()));
  const auto bins = static_cast<std::size_t>(std::clamp(std::ceil(tenths * (1 - 1e-9)), 1.0, 1000.0));
  const double bin_width = largest / static_cast<double>(bins);
  std::vector<double> count(bins, 0.0);
  for (double f : forces) count[std::min(bins - 1, static_cast<std::size_t>(std::max(f, 0.0) / bin_width))] += 1;
  std::vector<std::pair<double, double>> rows;
  rows.reserve(bins);
  const double per_contact = 1 / (static_cast<double>(forces.size()) * bin_width);
  for (std::size_t b = 0; b < bins; ++b)
    rows.emplace_back((static_cast<double>(b) + 0.5) * bin_width, count[b] * per_contact);
  return rows;
}

void WallStatisticsWriter::frame(const Simulation& sim) {
  // The manuals print no sample of these files, so there are no legacy widths to keep; and a
  // density in 1/N printed with four decimals is 0.0000 for forces of kilonewtons.
  const legacy::NumberFormat format =
      file_format(sim) == legacy::NumberFormat::LegacyFixed ? legacy::NumberFormat::Scientific : file_format(sim);
  const double t = sim.time();

  const std::vector<WallContact> walls = sim.wall_contacts();
  double wall_force = 0;
  for (const WallContact& c : walls) wall_force += c.fn;
  const auto wall_count = static_cast<double>(walls.size());
  int present = 0;  // a staged run's walls there now
  for (int k = 0; k < static_cast<int>(sim.scene().walls.size()); ++k) present += sim.wall_present(k);
  mean_force_.write({t, walls.empty() ? 0.0 : wall_force / wall_count,
                     present > 0 ? wall_count / static_cast<double>(present) : 0.0, wall_count},
                    format);
  mean_force_.flush();

  // Contacts per grain: a clump's members sum into their body (pairs inside a clump are never
  // contacts), every other particle is its own grain.
  const std::vector<int> per_particle = sim.contact_counts();
  const std::vector<int>& body = sim.particles().body;
  const std::size_t bodies = sim.state().bodies.x.size();
  std::vector<int> per_body(bodies, 0);
  std::vector<double> grains_with;  // by coordination number
  auto count_grain = [&](int z) {
    if (static_cast<std::size_t>(z) >= grains_with.size()) grains_with.resize(static_cast<std::size_t>(z) + 1, 0.0);
    grains_with[static_cast<std::size_t>(z)] += 1;
  };
  std::size_t grains = bodies;
  for (std::size_t i = 0; i < per_particle.size(); ++i) {
    if (!body.empty() && body[i] >= 0) {
      per_body[static_cast<std::size_t>(body[i])] += per_particle[i];
    } else {
      count_grain(per_particle[i]);
      ++grains;
    }
  }
  for (int z : per_body) count_grain(z);
  for (std::size_t z = 0; z < grains_with.size(); ++z)
    coordination_pdf_.write({t, static_cast<double>(z), grains_with[z] / static_cast<double>(grains)}, format);
  coordination_pdf_.flush();

  std::vector<double> forces;
  const std::vector<PairContact> pairs = sim.pair_contacts();
  forces.reserve(pairs.size() + walls.size());
  for (const PairContact& c : pairs) forces.push_back(std::max(c.fn, 0.0));
  for (const WallContact& c : walls) forces.push_back(std::max(c.fn, 0.0));
  for (const auto& [centre, density] : force_density(forces)) force_pdf_.write({t, centre, density}, format);
  force_pdf_.flush();
}

}  // namespace dem
