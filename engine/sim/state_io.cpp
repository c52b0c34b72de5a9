#include "sim/state_io.hpp"

#include <cstdio>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace dem {
namespace {

constexpr char kMagic[8] = {'D', 'E', 'M', 'S', 'T', 'A', 'T', '4'};  // 4: orientations, bonds' bonded states

// The state is made of fixed-size values without pointers (doubles, ints, Eigen fixed-size vectors
// and matrices, plain structs of them) and std::vectors of such: their bytes are their value for
// the build that wrote them.
template <class T>
void put(std::ostream& out, const T& value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof(T));
}

template <class T>
void put(std::ostream& out, const std::vector<T>& values) {
  const std::uint64_t n = values.size();
  put(out, n);
  if (n > 0) out.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(n * sizeof(T)));
}

class Reader {
 public:
  explicit Reader(std::istream& in) : in_(in) {}

  template <class T>
  void get(T& value, const char* what) {
    if (!in_.read(reinterpret_cast<char*>(&value), sizeof(T))) fail(what);
  }

  template <class T>
  void get(std::vector<T>& values, const char* what) {
    std::uint64_t n = 0;
    get(n, what);
    if (n > (std::uint64_t{1} << 34) / sizeof(T)) fail(what);
    values.resize(n);
    if (n > 0 && !in_.read(reinterpret_cast<char*>(values.data()), static_cast<std::streamsize>(n * sizeof(T)))) fail(what);
  }

  [[noreturn]] void fail(const char* what) {
    throw std::runtime_error(std::string("the saved state ends inside ") + what + " (truncated or not a state file)");
  }

 private:
  std::istream& in_;
};

}  // namespace

void StateIO::write(const Simulation& sim, std::ostream& out) {
  const SimState& s = sim.state_;
  out.write(kMagic, sizeof kMagic);
  put(out, static_cast<std::uint64_t>(s.particles.size()));
  put(out, static_cast<std::uint64_t>(sim.drivers_.size()));
  put(out, static_cast<std::uint64_t>(s.bonds.bonds().size()));
  put(out, s.dt);
  put(out, sim.step_);
  put(out, sim.builds_);
  put(out, sim.last_build_step_);
  put(out, sim.contacts_recorded_);
  put(out, s.time);
  const Particles& p = s.particles;
  put(out, p.x); put(out, p.v); put(out, p.w); put(out, p.f); put(out, p.t);
  put(out, p.radius); put(out, p.mass); put(out, p.inv_mass); put(out, p.inv_inertia);
  put(out, p.material); put(out, p.id); put(out, p.external);
  put(out, s.half_kick);
  put(out, sim.x_at_build_);
  const NeighborList& nl = s.neighbors;
  put(out, nl.row_start); put(out, nl.partner); put(out, nl.shear); put(out, nl.roll);
  put(out, nl.sqrt_m_eff); put(out, nl.r_eff); put(out, nl.i_roll);
  put(out, s.pairs.fn); put(out, s.pairs.ft_squared); put(out, s.pairs.touching);
  const BlockPlan& b = s.blocks;
  put(out, b.block_size);  // the rest of the plan follows from the neighbour list (read: plan_blocks)
  const WallContacts& wc = s.wall_contacts;
  put(out, wc.row_start); put(out, wc.wall); put(out, wc.shear); put(out, wc.roll); put(out, wc.constants);
  put(out, wc.fn); put(out, wc.ft); put(out, wc.touching); put(out, wc.force); put(out, wc.point);
  const MeshContacts& mc = s.mesh_contacts;
  put(out, mc.row_start); put(out, mc.mesh); put(out, mc.triangle); put(out, mc.slots); put(out, mc.used); put(out, mc.constants);
  put(out, s.walls);
  for (const MeshWall& m : s.meshes) put(out, m.pose);
  for (const WallDriver& d : sim.drivers_) put(out, d);
  put(out, sim.pose_at_build_);
  put(out, sim.boundary_loads_);
  put(out, sim.growth_at_build_);
  put(out, sim.growth_scale_);
  put(out, s.bonds.bonds());
  put(out, p.body); put(out, p.body_offset); put(out, p.q);
  put(out, sim.ledger_);
  const ClumpBodies& cb = s.bodies;
  put(out, cb.x); put(out, cb.v); put(out, cb.rotation); put(out, cb.force); put(out, cb.torque);
  if (!out) throw std::runtime_error("cannot write the saved state");
}

void StateIO::read(Simulation& sim, std::istream& in) {
  SimState& s = sim.state_;
  Reader r(in);
  char magic[sizeof kMagic];
  if (!in.read(magic, sizeof magic)) throw std::runtime_error("not a saved state of this engine (too short)");
  if (std::memcmp(magic, kMagic, sizeof kMagic - 1) == 0 && magic[7] != kMagic[7])
    throw std::runtime_error(std::string("a saved state of another version of this engine (format ") + magic[7] +
                             ", this one reads " + kMagic[7] + "): run the job again from its start");
  if (std::memcmp(magic, kMagic, sizeof kMagic) != 0)
    throw std::runtime_error("not a saved state of this engine (wrong first bytes)");
  std::uint64_t particles = 0, walls = 0, bonds = 0;
  double dt = 0;
  r.get(particles, "the header");
  r.get(walls, "the header");
  r.get(bonds, "the header");
  r.get(dt, "the header");
  auto mismatch = [](const std::string& what, double saved, double now) {
    char buf[120];
    std::snprintf(buf, sizeof buf, "%s %.17g there, %.17g in this spec", what.c_str(), saved, now);
    throw std::runtime_error(std::string("the saved state was written for another job: ") + buf);
  };
  if (particles != s.particles.size()) mismatch("particles", static_cast<double>(particles), static_cast<double>(s.particles.size()));
  if (walls != sim.drivers_.size()) mismatch("walls", static_cast<double>(walls), static_cast<double>(sim.drivers_.size()));
  if (bonds != s.bonds.bonds().size()) mismatch("bonds", static_cast<double>(bonds), static_cast<double>(s.bonds.bonds().size()));
  if (dt != s.dt) mismatch("time step", dt, s.dt);
  r.get(sim.step_, "the step count");
  r.get(sim.builds_, "the step count");
  r.get(sim.last_build_step_, "the step count");
  r.get(sim.contacts_recorded_, "the step count");
  r.get(s.time, "the step count");
  Particles& p = s.particles;
  r.get(p.x, "the particles"); r.get(p.v, "the particles"); r.get(p.w, "the particles");
  r.get(p.f, "the particles"); r.get(p.t, "the particles");
  r.get(p.radius, "the particles"); r.get(p.mass, "the particles"); r.get(p.inv_mass, "the particles");
  r.get(p.inv_inertia, "the particles"); r.get(p.material, "the particles"); r.get(p.id, "the particles");
  r.get(p.external, "the particles");
  r.get(s.half_kick, "the particles");
  r.get(sim.x_at_build_, "the particles");
  NeighborList& nl = s.neighbors;
  r.get(nl.row_start, "the neighbour list"); r.get(nl.partner, "the neighbour list"); r.get(nl.shear, "the neighbour list");
  r.get(nl.roll, "the neighbour list"); r.get(nl.sqrt_m_eff, "the neighbour list"); r.get(nl.r_eff, "the neighbour list");
  r.get(nl.i_roll, "the neighbour list");
  r.get(s.pairs.fn, "the contacts"); r.get(s.pairs.ft_squared, "the contacts"); r.get(s.pairs.touching, "the contacts");
  BlockPlan& b = s.blocks;
  r.get(b.block_size, "the block plan");
  sim.plan_blocks();
  WallContacts& wc = s.wall_contacts;
  r.get(wc.row_start, "the wall contacts"); r.get(wc.wall, "the wall contacts"); r.get(wc.shear, "the wall contacts");
  r.get(wc.roll, "the wall contacts"); r.get(wc.constants, "the wall contacts"); r.get(wc.fn, "the wall contacts");
  r.get(wc.ft, "the wall contacts"); r.get(wc.touching, "the wall contacts"); r.get(wc.force, "the wall contacts");
  r.get(wc.point, "the wall contacts");
  MeshContacts& mc = s.mesh_contacts;
  r.get(mc.row_start, "the mesh contacts"); r.get(mc.mesh, "the mesh contacts"); r.get(mc.triangle, "the mesh contacts");
  r.get(mc.slots, "the mesh contacts"); r.get(mc.used, "the mesh contacts"); r.get(mc.constants, "the mesh contacts");
  r.get(s.walls, "the walls");
  std::vector<WallPose> mesh_poses(s.meshes.size());
  for (WallPose& pose : mesh_poses) r.get(pose, "the walls");
  std::vector<WallDriver> saved_drivers(sim.drivers_.size());
  for (WallDriver& d : saved_drivers) r.get(d, "the walls");
  for (std::size_t m = 0; m < s.meshes.size(); ++m) {  // a mesh that never moved keeps its vertices as read from the spec
    const WallPose& pose = mesh_poses[m];
    const bool moved = saved_drivers[s.meshes[m].boundary].moves() || !pose.displacement.isZero(0) ||
                       !pose.rotation.isIdentity(0);  // a load dropped earlier leaves it still, but elsewhere
    if (moved) s.meshes[m].move_to(pose);
  }
  std::vector<int> loads_starting;
  for (std::size_t k = 0; k < saved_drivers.size(); ++k) {
    try {
      if (sim.drivers_[k].continue_from(saved_drivers[k], sim.time())) loads_starting.push_back(static_cast<int>(k));
    } catch (const std::runtime_error& e) {
      throw std::runtime_error("walls[" + std::to_string(k) + "] (" + sim.scene_.walls[k].name + "): " + e.what());
    }
  }
  r.get(sim.pose_at_build_, "the walls");
  r.get(sim.boundary_loads_, "the walls");
  for (int k : loads_starting) {  // a load that starts now feels the particles' push from the start, as at t = 0
    WallDriver& d = sim.drivers_[k];
    d.end_step(sim.time(), 0, sim.boundary_loads_[k].force);
    if (sim.plane_index_[k] >= 0) s.walls[sim.plane_index_[k]].move_to(d.pose());
    else s.meshes[sim.mesh_index_[k]].move_to(d.pose());
  }
  r.get(sim.growth_at_build_, "the walls");
  r.get(sim.growth_scale_, "the walls");
  std::vector<Bond> saved_bonds;
  r.get(saved_bonds, "the bonds");
  s.bonds.restore(std::move(saved_bonds));
  r.get(p.body, "the clumps"); r.get(p.body_offset, "the clumps"); r.get(p.q, "the orientations");
  r.get(sim.ledger_, "the energy ledger");
  ClumpBodies& cb = s.bodies;
  r.get(cb.x, "the clumps"); r.get(cb.v, "the clumps"); r.get(cb.rotation, "the clumps");
  r.get(cb.force, "the clumps"); r.get(cb.torque, "the clumps");
}

void StateIO::write_file(const Simulation& sim, const std::string& path) {
  const std::string part = path + ".part";
  {
    std::ofstream out(part, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + part);
    write(sim, out);
    out.flush();
    if (!out) throw std::runtime_error("cannot write " + part);
  }
  std::filesystem::rename(part, path);
}

void StateIO::read_file(Simulation& sim, const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open the saved state");
  try {
    read(sim, in);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

}  // namespace dem
