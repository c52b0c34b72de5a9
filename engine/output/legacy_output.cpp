#include "output/legacy_output.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace dem {
namespace {

legacy::NumberFormat file_format(const Simulation& sim) {
  return sim.scene().outputs.number_format == FileNumberFormat::LegacyFixed ? legacy::NumberFormat::LegacyFixed
                                                                            : legacy::NumberFormat::Scientific;
}

}  // namespace

FilePtr open_for_writing(const std::string& path) {
  FilePtr f(std::fopen(path.c_str(), "wb"));
  if (!f) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  return f;
}

std::array<double, 6> frame_domain(const Simulation& sim) {
  const double unit = sim.scene().outputs.length_unit;
  Vec3 lo, hi;
  if (sim.scene().domain) {
    lo = sim.scene().domain->min;
    hi = sim.scene().domain->max;
  } else {
    lo = Vec3::Constant(1e300);
    hi = -lo;
    const Particles& p = sim.particles();
    for (std::size_t i = 0; i < p.size(); ++i) {
      lo = lo.cwiseMin(p.x[i] - Vec3::Constant(p.radius[i]));
      hi = hi.cwiseMax(p.x[i] + Vec3::Constant(p.radius[i]));
    }
    for (const Wall& w : sim.state().walls) {
      if (w.kind != Wall::Kind::Plate) continue;
      for (const Vec3& c : w.corners) {
        lo = lo.cwiseMin(c);
        hi = hi.cwiseMax(c);
      }
    }
    if (lo[0] > hi[0]) lo = hi = Vec3::Zero();
  }
  return {lo[0] / unit, hi[0] / unit, lo[1] / unit, hi[1] / unit, lo[2] / unit, hi[2] / unit};
}

AnimationWriter::AnimationWriter(const std::string& path, const Simulation& sim)
    : file_(open_for_writing(path)), domain_(frame_domain(sim)) {}

legacy::AnimationFrame AnimationWriter::make_frame(const Simulation& sim, const std::array<double, 6>& domain) {
  const double unit = sim.scene().outputs.length_unit;
  const Particles& p = sim.particles();
  legacy::AnimationFrame frame;
  frame.domain = domain;
  // time, loading-plate displacement and force (no loading plate yet), kinetic energy
  frame.scalars = {sim.time(), 0.0, 0.0, sim.kinetic_energy()};
  frame.step = sim.step_count();
  int plate_id = 0;
  for (const Wall& w : sim.state().walls) {
    if (w.kind != Wall::Kind::Plate) continue;
    legacy::AnimationPlate plate;
    plate.id = ++plate_id;
    for (int k = 0; k < 4; ++k) plate.corners[k] = w.corners[k] / unit;
    frame.plates.push_back(plate);
  }
  const std::vector<int> contacts = sim.contact_counts();
  frame.particles.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    legacy::AnimationParticle& out = frame.particles[p.id[i]];  // rows in scene order
    out.id = p.id[i] + 1;
    out.position = p.x[i] / unit;
    out.diameter = 2 * p.radius[i] / unit;
    out.velocity = p.v[i] / unit;
    out.contacts = contacts[i];
    out.angular_velocity = p.w[i];
    out.part = 0;  // no bonded fragments or clumps in this scene
  }
  return frame;
}

void AnimationWriter::frame(const Simulation& sim) {
  legacy::write_animation_frame(file_.get(), make_frame(sim, domain_), file_format(sim));
  std::fflush(file_.get());
}

ForceChainWriter::ForceChainWriter(const std::string& path) : file_(open_for_writing(path)) {}

legacy::ForceChainFrame ForceChainWriter::make_frame(const Simulation& sim) {
  const std::vector<int>& id = sim.particles().id;
  legacy::ForceChainFrame frame;
  frame.step = sim.step_count();
  for (const PairContact& c : sim.pair_contacts()) {
    const int a = id[c.i] + 1, b = id[c.j] + 1;
    frame.chains.push_back({std::min(a, b), std::max(a, b), c.fn, c.ft});
  }
  std::sort(frame.chains.begin(), frame.chains.end(),
            [](const legacy::ForceChain& x, const legacy::ForceChain& y) { return x.i != y.i ? x.i < y.i : x.j < y.j; });
  return frame;
}

void ForceChainWriter::frame(const Simulation& sim) {
  legacy::write_force_chain_frame(file_.get(), make_frame(sim), file_format(sim));
  std::fflush(file_.get());
}

}  // namespace dem
