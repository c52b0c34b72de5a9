#include "server/frame_encoder.hpp"

#include <bit>
#include <cstring>

#include "dem.pb.h"
#include "output/legacy_output.hpp"

namespace dem::server {
namespace {

// The wire format says little-endian; the bytes are copied as they are in memory.
static_assert(std::endian::native == std::endian::little, "frame arrays are sent as the machine's little-endian bytes");

template <class T>
std::string bytes_of(const std::vector<T>& values) {
  std::string out(values.size() * sizeof(T), '\0');
  if (!values.empty()) std::memcpy(out.data(), values.data(), out.size());
  return out;
}

// x, y, z of each particle as float32, in the order of the particles' ids (the spec's order).
std::string vectors_by_id(const std::vector<Vec3>& values, const std::vector<int>& id) {
  std::vector<float> out(3 * values.size());
  for (std::size_t i = 0; i < values.size(); ++i)
    for (int d = 0; d < 3; ++d) out[3 * static_cast<std::size_t>(id[i]) + d] = static_cast<float>(values[i][d]);
  return bytes_of(out);
}

void add_walls(const Simulation& sim, api::Frame& frame) {
  const std::vector<Wall>& walls = sim.walls();
  for (int k = 0; k < static_cast<int>(sim.scene().walls.size()); ++k) {
    std::vector<float> corners;
    auto put = [&](const Vec3& c) {
      for (int d = 0; d < 3; ++d) corners.push_back(static_cast<float>(c[d]));
    };
    if (!sim.wall_present(k)) continue;  // a staged run's wall gone (or not yet come)
    if (const int p = sim.plane_index(k); p >= 0) {
      if (walls[p].kind != Wall::Kind::Plate) continue;  // infinite planes do not move into view
      const auto& c = walls[p].corners;
      for (const Vec3& v : {c[0], c[1], c[2], c[0], c[2], c[3]}) put(v);
    } else if (const int m = sim.mesh_index(k); m >= 0) {
      const MeshWall& mesh = sim.meshes()[m];
      if (!sim.wall_varies(k)) continue;  // a fixed mesh is the viewer's to load once (Wall.dat)
      for (const auto& t : mesh.triangles)
        for (int c = 0; c < 3; ++c) put(mesh.vertices[t[c]]);
    }
    api::WallShape* shape = frame.add_walls();
    shape->set_wall(static_cast<std::uint32_t>(k));
    shape->set_triangles(bytes_of(corners));
  }
}

}  // namespace

EncodedFrame FrameEncoder::encode(const Simulation& sim, bool with_force_chains) {
  const Particles& p = sim.particles();
  EncodedFrame out;
  out.step = sim.step_count();

  api::Frame base;
  base.set_job(job_);
  base.set_step(sim.step_count());
  base.set_total_steps(sim.total_steps());
  base.set_time(sim.time());
  base.set_particle_count(static_cast<std::uint32_t>(p.size()));
  base.set_positions(vectors_by_id(p.x, p.id));
  base.set_velocities(vectors_by_id(p.v, p.id));
  base.set_kinetic_energy(sim.kinetic_energy());
  base.set_planar(sim.scene().plane.has_value());
  if (!sim.bonds().empty() || !sim.state().bodies.empty()) {
    const std::vector<int> fragment = sim.fragments();
    std::vector<std::int32_t> by_id(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) by_id[p.id[i]] = fragment[i];
    base.set_fragments(bytes_of(by_id));
  }
  add_walls(sim, base);
  if (!sim.scene().stages.empty()) {
    base.set_stage(sim.stage_name());
    for (int k = 0; k < static_cast<int>(sim.scene().walls.size()); ++k)
      if (!sim.wall_present(k)) base.add_absent_walls(static_cast<std::uint32_t>(k));
  }
  const ClumpBodies& bodies = sim.state().bodies;
  if (!bodies.empty()) {
    std::vector<float> centres, turns;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      for (int d = 0; d < 3; ++d) centres.push_back(static_cast<float>(bodies.x[b][d]));
      const Eigen::Quaterniond& q = bodies.rotation[b].orientation;
      for (double c : {q.w(), q.x(), q.y(), q.z()}) turns.push_back(static_cast<float>(c));
    }
    base.set_clump_positions(bytes_of(centres));
    base.set_clump_orientations(bytes_of(turns));
  }
  out.base = std::make_shared<const std::string>(base.SerializeAsString());

  std::vector<float> radii(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) radii[p.id[i]] = static_cast<float>(p.radius[i]);
  if (!radii_part_ || radii != radii_) {
    ++radii_version_;
    api::Frame part;
    part.set_radii(bytes_of(radii));
    radii_part_ = std::make_shared<const std::string>(part.SerializeAsString());
    radii_ = std::move(radii);
  }
  out.radii = radii_part_;
  out.radii_version = radii_version_;

  if (with_force_chains && sim.contacts_recorded()) {
    struct Record {
      std::int32_t i, j;
      float normal, tangential;
    };
    static_assert(sizeof(Record) == 16);
    std::vector<Record> records;
    for (const legacy::ForceChain& c : ForceChainWriter::make_frame(sim).chains)
      records.push_back({c.i - 1, c.j - 1, static_cast<float>(c.normal_force), static_cast<float>(c.tangential_force)});
    api::Frame part;
    part.set_force_chains(bytes_of(records));
    out.force_chains = std::make_shared<const std::string>(part.SerializeAsString());
  }
  return out;
}

}  // namespace dem::server
