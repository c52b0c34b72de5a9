#include "output/legacy_output.hpp"

#include <limits>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "mesh/mesh_io.hpp"
#include "sim/state_io.hpp"

namespace dem {

legacy::NumberFormat file_format(const Simulation& sim) {
  switch (sim.scene().outputs.number_format) {
    case FileNumberFormat::LegacyFixed:
      return legacy::NumberFormat::LegacyFixed;
    case FileNumberFormat::Full:
      return legacy::NumberFormat::Full;
    case FileNumberFormat::Scientific:
      break;
  }
  return legacy::NumberFormat::Scientific;
}

legacy::NumberFormat counts_format(const Simulation& sim) {
  return file_format(sim) == legacy::NumberFormat::Full ? legacy::NumberFormat::Full : legacy::NumberFormat::Scientific;
}

FilePtr open_for_writing(const std::string& path, bool append) {
  FilePtr f(std::fopen(path.c_str(), append ? "ab" : "wb"));
  if (!f) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  return f;
}

void OutputFile::flush() {
  if (!file_) return;
  // errno is not cleared first: a frame larger than the buffer fails inside its writes, and their
  // errno (ENOSPC) is the reason; the flush after them may then have nothing left to fail on
  const bool flushed = std::fflush(file_.get()) == 0;
  const int reason = errno;
  if (!flushed || std::ferror(file_.get()))
    throw std::runtime_error("cannot write " + path_ + ": " + std::strerror(reason != 0 ? reason : EIO) +
                             " (the file holds what was written before this frame)");
}

std::array<double, 6> frame_domain(const Simulation& sim) {
  // From the scene as given (the start), not the particles now: a continued run writes the same box.
  const double unit = sim.scene().outputs.length_unit;
  Vec3 lo, hi;
  if (sim.scene().domain) {
    lo = sim.scene().domain->min;
    hi = sim.scene().domain->max;
  } else {
    lo = Vec3::Constant(1e300);
    hi = -lo;
    auto include = [&](const Vec3& x) {
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    };
    // the particles given, and where the sources put theirs
    for (std::size_t k = 0; k < sim.given_particles(); ++k) {
      const ParticleInit& p = sim.scene().particles[k];
      include(p.position - Vec3::Constant(p.radius));
      include(p.position + Vec3::Constant(p.radius));
    }
    for (const ParticleSource& source : sim.scene().sources)
      for (const ParticleInit& p : source_extremes(sim.scene(), source)) {
        include(p.position - Vec3::Constant(p.radius));
        include(p.position + Vec3::Constant(p.radius));
      }
    for (const WallInit& w : sim.scene().walls) {
      if (const auto* plate = std::get_if<PlateShape>(&w.shape))
        for (const Vec3& c : plate->corners) include(c);
      if (const auto* mesh = std::get_if<MeshShape>(&w.shape))
        for (const Vec3& v : mesh->vertices) include(v);
    }
    if (lo[0] > hi[0]) lo = hi = Vec3::Zero();
  }
  return {lo[0] / unit, hi[0] / unit, lo[1] / unit, hi[1] / unit, lo[2] / unit, hi[2] / unit};
}

AnimationWriter::AnimationWriter(const std::string& path, const Simulation& sim, bool append)
    : file_(path, append), domain_(frame_domain(sim)) {}

legacy::AnimationFrame AnimationWriter::make_frame(const Simulation& sim, const std::array<double, 6>& domain) {
  const double unit = sim.scene().outputs.length_unit;
  const Particles& p = sim.particles();
  legacy::AnimationFrame frame;
  frame.domain = domain;
  // time, loading-plate displacement and force, kinetic energy
  const int loading = ForceDisplacementWriter::loading_wall(sim);
  const double displacement = loading >= 0 ? sim.wall_driver(loading).load_displacement() / unit : 0.0;
  const double force = loading >= 0 ? sim.wall_driver(loading).applied_force() : 0.0;
  frame.scalars = {sim.time(), displacement, force, sim.kinetic_energy()};
  frame.step = sim.step_count();
  const legacy::WallFrame walls = WallWriter::make_frame(sim);
  frame.plates = walls.plates;
  frame.triangles = walls.triangles;
  const std::vector<int> contacts = sim.contact_counts();
  const std::vector<int> fragment = sim.fragments();
  frame.particles.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    legacy::AnimationParticle& out = frame.particles[p.id[i]];  // rows in scene order
    out.id = p.id[i] + 1;
    out.position = p.x[i] / unit;
    out.diameter = 2 * p.radius[i] / unit;
    out.velocity = p.v[i] / unit;
    out.contacts = contacts[i];
    out.angular_velocity = p.w[i];
    out.part = fragment[i];  // bonded fragments (0 without bonds)
  }
  return frame;
}

bool WallWriter::wanted(const Simulation& sim) { return !sim.meshes().empty() || sim.any_wall_varies(); }

WallWriter::WallWriter(const std::string& folder, const Simulation& sim, bool append) {
  const double unit = sim.scene().outputs.length_unit;
  if (!sim.meshes().empty() && !append) {
    TriangleMesh all;
    for (const MeshWall& m : sim.meshes()) {
      // a mesh a stage adds or removes is drawn in the frames while it is there, not here
      const WallInit& init = sim.scene().walls[m.boundary];
      if (init.first_stage > 0 || init.last_stage != std::numeric_limits<int>::max()) continue;
      const int base = static_cast<int>(all.vertices.size());
      all.vertices.insert(all.vertices.end(), m.vertices.begin(), m.vertices.end());
      for (const auto& t : m.triangles) all.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    }
    if (!all.triangles.empty()) {
      OutputFile mesh_file(folder + "/Wall.dat", false);
      write_legacy_mesh(mesh_file.get(), all, unit);
      mesh_file.flush();
    }
  }
  if (sim.any_wall_varies()) animation_ = OutputFile(folder + "/Wall_Animation_3D.dat", append);
}

// Every plate there now (numbered 1.. in scene order among plates, those of a staged run's other
// stages counted), then the triangles of the meshes that move, come or go, while they are there
// (numbered 1.. across those meshes).
legacy::WallFrame WallWriter::make_frame(const Simulation& sim) {
  const double unit = sim.scene().outputs.length_unit;
  legacy::WallFrame frame;
  frame.step = sim.step_count();
  int plate_id = 0;
  for (int k = 0; k < static_cast<int>(sim.walls().size()); ++k) {
    const Wall& w = sim.walls()[k];
    if (w.kind != Wall::Kind::Plate) continue;
    ++plate_id;
    if (!sim.wall_present(sim.boundary_of_plane(k))) continue;
    legacy::AnimationPlate plate;
    plate.id = plate_id;
    for (int k = 0; k < 4; ++k) plate.corners[k] = w.corners[k] / unit;
    frame.plates.push_back(plate);
  }
  int triangle_id = 0;
  for (const MeshWall& m : sim.meshes()) {
    if (!sim.wall_varies(m.boundary) || !sim.wall_present(m.boundary)) continue;
    for (const auto& t : m.triangles) {
      legacy::AnimationTriangle tri;
      tri.id = ++triangle_id;
      for (int k = 0; k < 3; ++k) tri.corners[k] = m.vertices[t[k]] / unit;
      frame.triangles.push_back(tri);
    }
  }
  return frame;
}

void WallWriter::frame(const Simulation& sim) {
  if (!animation_) return;
  legacy::write_wall_frame(animation_.get(), make_frame(sim), file_format(sim));
  animation_.flush();
}

WallForceChainWriter::WallForceChainWriter(const std::string& path, bool append) : file_(path, append) {}

legacy::WallForceChainFrame WallForceChainWriter::make_frame(const Simulation& sim) {
  const std::vector<int>& id = sim.particles().id;
  legacy::WallForceChainFrame frame;
  frame.step = sim.step_count();
  for (const WallContact& c : sim.wall_contacts()) frame.chains.push_back({id[c.i] + 1, c.wall + 1, c.fn, c.ft});
  std::stable_sort(frame.chains.begin(), frame.chains.end(),
                   [](const auto& a, const auto& b) { return a.i != b.i ? a.i < b.i : a.wall < b.wall; });
  return frame;
}

void WallForceChainWriter::frame(const Simulation& sim) {
  legacy::write_wall_force_chain_frame(file_.get(), make_frame(sim), file_format(sim));
  file_.flush();
}

ForceDisplacementWriter::ForceDisplacementWriter(const std::string& path, const Simulation& sim, bool append)
    : file_(path, {"time (s)", "displacement (" + sim.scene().outputs.length_unit_name + ")", "force (N)"},
            sim.scene().outputs.csv, append) {}

bool ForceDisplacementWriter::wanted(const Simulation& sim) {
  for (const WallInit& w : sim.scene().walls)
    if (w.load) return true;
  for (const Stage& stage : sim.scene().stages)
    for (const WallChange& c : stage.wall_changes)
      if (c.load) return true;
  return false;
}

int ForceDisplacementWriter::loading_wall(const Simulation& sim) {
  for (int k = 0; k < static_cast<int>(sim.scene().walls.size()); ++k)
    if (sim.wall_present(k) && sim.wall_driver(k).load_controlled()) return k;
  return -1;
}

void ForceDisplacementWriter::frame(const Simulation& sim) {
  const int k = loading_wall(sim);
  if (k < 0) return;
  const double unit = sim.scene().outputs.length_unit;
  const legacy::ForceDisplacementRow row{sim.time(), sim.wall_driver(k).load_displacement() / unit,
                                         sim.wall_driver(k).applied_force()};
  legacy::write_force_displacement_row(file_.dat(), row, file_format(sim));
  file_.write_csv({row.time, row.displacement, row.force});
  file_.flush();
}

void AnimationWriter::frame(const Simulation& sim) {
  legacy::write_animation_frame(file_.get(), make_frame(sim, domain_), file_format(sim));
  file_.flush();
}

ForceChainWriter::ForceChainWriter(const std::string& path, bool append) : file_(path, append) {}

void StateWriter::frame(const Simulation& sim) { StateIO::write_file(sim, path_); }

legacy::ForceChainFrame ForceChainWriter::make_frame(const Simulation& sim) {
  const std::vector<int>& id = sim.particles().id;
  legacy::ForceChainFrame frame;
  frame.step = sim.step_count();
  for (const PairContact& c : sim.pair_contacts()) {
    const int a = id[c.i] + 1, b = id[c.j] + 1;
    frame.chains.push_back({std::min(a, b), std::max(a, b), c.fn, c.ft});
  }
  std::sort(frame.chains.begin(), frame.chains.end(), [](const legacy::ForceChain& x, const legacy::ForceChain& y) {
    return x.i != y.i ? x.i < y.i : x.j < y.j;
  });
  return frame;
}

void ForceChainWriter::frame(const Simulation& sim) {
  legacy::write_force_chain_frame(file_.get(), make_frame(sim), file_format(sim));
  file_.flush();
}

}  // namespace dem
