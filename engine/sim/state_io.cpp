#include "sim/state_io.hpp"

#include <boost/crc.hpp>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace dem {
namespace {

// 11: the sources' progress and the particles they inserted; 10: the stage (Scene::stages) and the walls' motion
// clocks; 9: the walls' contact response (a servo's gain cap); 5: a CRC-32 of everything before it as the last four
// bytes; 4: orientations, bonds' bonded states
constexpr char kMagic[8] = {'D', 'E', 'M', 'S', 'T', 'A', '1', '1'};

// The state is made of fixed-size values without pointers (doubles, ints, Eigen fixed-size vectors
// and matrices, plain structs of them) and std::vectors of such: their bytes are their value for
// the build that wrote them.
class Writer {
 public:
  explicit Writer(std::ostream& out) : out_(out) {}

  void bytes(const void* data, std::size_t size) {
    out_.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
    crc_.process_bytes(data, size);
  }
  template <class T>
  void put(const T& value) {
    bytes(&value, sizeof(T));
  }
  template <class T>
  void put(const std::vector<T>& values) {
    const std::uint64_t n = values.size();
    put(n);
    if (n > 0) bytes(values.data(), n * sizeof(T));
  }
  // A rigid rotation ends in padding (8 bytes, to the quaternion's alignment), which holds whatever
  // the memory held: each is written as its two values in a zeroed record of its size, so the state
  // is the same bytes for the same run (the reader reads the record whole, as before).
  void put(const std::vector<RigidRotation>& values) {
    const std::uint64_t n = values.size();
    put(n);
    auto offset_of = [](const RigidRotation& whole, const void* part) {
      return static_cast<std::size_t>(static_cast<const char*>(part) - reinterpret_cast<const char*>(&whole));
    };
    for (const RigidRotation& value : values) {
      char record[sizeof(RigidRotation)] = {};
      // their doubles (the Eigen types themselves are not trivially copyable)
      const double* orientation = value.orientation.coeffs().data();
      const double* angular_momentum = value.angular_momentum.data();
      std::memcpy(record + offset_of(value, orientation), orientation, 4 * sizeof(double));
      std::memcpy(record + offset_of(value, angular_momentum), angular_momentum, 3 * sizeof(double));
      bytes(record, sizeof record);
    }
  }
  void seal() {
    const std::uint32_t sum = crc_.checksum();
    out_.write(reinterpret_cast<const char*>(&sum), sizeof sum);
  }

 private:
  std::ostream& out_;
  boost::crc_32_type crc_;
};

// Reads the values of a state whose checksum has been verified, from memory.
class Reader {
 public:
  Reader(const char* data, std::size_t size) : at_(data), end_(data + size) {}

  template <class T>
  void get(T& value, const char* what) {
    if (static_cast<std::size_t>(end_ - at_) < sizeof(T)) fail(what);
    std::memcpy(reinterpret_cast<char*>(&value), at_, sizeof(T));
    at_ += sizeof(T);
  }

  template <class T>
  void get(std::vector<T>& values, const char* what) {
    std::uint64_t n = 0;
    get(n, what);
    if (n > static_cast<std::uint64_t>(end_ - at_) / sizeof(T)) fail(what);
    values.resize(n);
    if (n > 0) std::memcpy(reinterpret_cast<char*>(values.data()), at_, n * sizeof(T));
    at_ += n * sizeof(T);
  }

  bool at_end() const { return at_ == end_; }

  [[noreturn]] void fail(const char* what) {
    throw std::runtime_error(std::string("the saved state ends inside ") + what + " (truncated or not a state file)");
  }

 private:
  const char* at_;
  const char* end_;
};

// A state that passed its checksum but does not fit the job (written by hand, or by a bug): refused
// before any index in it is followed.
// A particle a source inserted, as it entered (the scene's entry for it: statistics measure from there).
struct InsertedParticle {
  Vec3 position;
  Vec3 velocity;
  double radius;  // its given size (Scene::particles)
  int source;     // index in Scene::sources
  int material;
};

// Saved as their bytes: no padding may lie in them, or two runs would save whatever the memory held
// there (an independent tester found restart.dat differing between two runs of one spec).
static_assert(sizeof(BoundaryLoad) == 2 * sizeof(Vec3) + 2 * sizeof(int) + sizeof(ContactResponse));
static_assert(sizeof(MeshSlot) == 2 * sizeof(int) + 6 * sizeof(Vec3) + 6 * sizeof(double));
static_assert(sizeof(LoadControl) == sizeof(LoadControl::Kind) + sizeof(int) + sizeof(Vec3) + 7 * sizeof(double));
static_assert(sizeof(WallDriver::Record) == 8 + sizeof(PlainMotion) + sizeof(LoadControl) + sizeof(WallPose) +
                                                6 * sizeof(double) + sizeof(Vec3) + sizeof(Eigen::Matrix3d));
static_assert(sizeof(Bond) == 2 * sizeof(int) + sizeof(BondGeometry) + 4 * sizeof(double) + 8 + 3 * sizeof(double) +
                                  2 * sizeof(Vec3) + sizeof(double) + sizeof(Quat) + sizeof(double) + 3 * sizeof(Vec3));
static_assert(sizeof(Wall) == 2 * sizeof(int) + 2 * sizeof(Vec3) + 4 * sizeof(Vec3) + sizeof(WallPose) +
                                  2 * sizeof(Vec3) + 4 * sizeof(Vec3));
static_assert(sizeof(SourceProgress) == 5 * sizeof(std::int64_t) &&
              sizeof(InsertedParticle) == 2 * sizeof(Vec3) + sizeof(double) + 2 * sizeof(int));
static_assert(sizeof(PairConstants) == 3 * sizeof(double) && sizeof(EnergyLedger) == 7 * sizeof(double));

[[noreturn]] void inconsistent(const std::string& what) {
  throw std::runtime_error("the saved state does not hold together: " + what);
}

template <class T>
void expect_size(const std::vector<T>& values, std::size_t size, const char* what) {
  if (values.size() != size)
    inconsistent(std::string(what) + " has " + std::to_string(values.size()) + " entries where " +
                 std::to_string(size) + " belong");
}

// Compressed rows over n particles: n + 1 starts from 0, never decreasing, ending at `entries`.
void expect_rows(const std::vector<int>& row_start, std::size_t n, std::size_t entries, const char* what) {
  expect_size(row_start, n + 1, what);
  if (row_start[0] != 0 || static_cast<std::size_t>(row_start[n]) != entries)
    inconsistent(std::string(what) + " do not span its entries");
  for (std::size_t i = 0; i < n; ++i)
    if (row_start[i + 1] < row_start[i])
      inconsistent(std::string(what) + " go backwards at particle " + std::to_string(i));
}

void expect_indices(const std::vector<int>& index, int lo, int hi, const char* what) {
  for (std::size_t k = 0; k < index.size(); ++k)
    if (index[k] < lo || index[k] >= hi)
      inconsistent(std::string(what) + " " + std::to_string(k) + " is " + std::to_string(index[k]) + ", outside " +
                   std::to_string(lo) + ".." + std::to_string(hi - 1));
}

template <class T>
void expect_finite(const std::vector<T>& values, const char* what) {
  for (std::size_t k = 0; k < values.size(); ++k) {
    bool finite;
    if constexpr (std::is_floating_point_v<T>)
      finite = std::isfinite(values[k]);
    else
      finite = values[k].allFinite();
    if (!finite) inconsistent(std::string(what) + " " + std::to_string(k) + " is not finite");
  }
}

// A pose places a wall's or a mesh's every point: a non-finite one, or a "rotation" that stretches,
// would put the wall nowhere (and the triangle grid's cells at NaN).
void expect_pose(const WallPose& pose, const std::string& what) {
  const bool finite = pose.center0.allFinite() && pose.displacement.allFinite() && pose.rotation.allFinite() &&
                      pose.velocity.allFinite() && pose.angular_velocity.allFinite();
  if (!finite) inconsistent(what + " is not finite");
  if (!(pose.rotation.transpose() * pose.rotation).isIdentity(1e-9) || !(pose.rotation.determinant() > 0))
    inconsistent(what + "'s rotation is not a rotation");
}

}  // namespace

void StateIO::write(const Simulation& sim, std::ostream& out) {
  const SimState& s = sim.state_;
  Writer w(out);
  w.bytes(kMagic, sizeof kMagic);
  w.put(static_cast<std::uint64_t>(s.particles.size()));
  w.put(static_cast<std::uint64_t>(sim.boundaries_.drivers_.size()));
  w.put(static_cast<std::uint64_t>(s.bonds.bonds().size()));
  w.put(s.dt);
  w.put(sim.step_);
  w.put(sim.builds_);
  w.put(sim.last_build_step_);
  w.put(sim.contacts_recorded_);
  w.put(s.time);
  w.put(sim.stage_);
  w.put(sim.stage_start_step_);
  w.put(sim.stage_end_step_);
  w.put(static_cast<std::uint8_t>(sim.stage_ended_early_));
  w.put(sim.source_progress_);
  std::vector<InsertedParticle> inserted;
  for (std::size_t id = sim.given_particles_; id < sim.scene_.particles.size(); ++id) {
    const ParticleInit& init = sim.scene_.particles[id];
    inserted.push_back({init.position, init.velocity, init.radius, init.source, init.material});
  }
  w.put(inserted);
  const Particles& p = s.particles;
  w.put(p.x);
  w.put(p.v);
  w.put(p.w);
  w.put(p.f);
  w.put(p.t);
  w.put(p.radius);
  w.put(p.mass);
  w.put(p.inv_mass);
  w.put(p.inv_inertia);
  w.put(p.material);
  w.put(p.id);
  w.put(p.external);
  w.put(s.half_kick);
  w.put(sim.x_at_build_);
  const NeighborList& nl = s.neighbors;
  w.put(nl.row_start);
  w.put(nl.partner);
  w.put(nl.shear);
  w.put(nl.roll);
  w.put(nl.touched);
  w.put(nl.sqrt_m_eff);
  w.put(nl.r_eff);
  w.put(nl.i_roll);
  w.put(s.pairs.fn);
  w.put(s.pairs.ft_squared);
  w.put(s.pairs.touching);
  const BlockPlan& b = s.blocks;
  w.put(b.block_size);  // the rest of the plan follows from the neighbour list (read: plan_blocks)
  const WallContacts& wc = s.wall_contacts;
  w.put(wc.row_start);
  w.put(wc.wall);
  w.put(wc.shear);
  w.put(wc.roll);
  w.put(wc.constants);
  w.put(wc.fn);
  w.put(wc.ft);
  w.put(wc.touching);
  w.put(wc.force);
  w.put(wc.point);
  const MeshContacts& mc = s.mesh_contacts;
  w.put(mc.row_start);
  w.put(mc.mesh);
  w.put(mc.triangle);
  w.put(mc.slots);
  w.put(mc.used);
  w.put(mc.constants);
  w.put(s.walls);
  for (const MeshWall& m : s.meshes) w.put(m.pose);
  for (const WallDriver& d : sim.boundaries_.drivers_) w.put(d.record());
  w.put(sim.boundaries_.pose_at_build_);
  w.put(sim.boundary_loads_);
  w.put(sim.growth_at_build_);
  w.put(sim.growth_scale_);
  w.put(s.bonds.bonds());
  w.put(p.body);
  w.put(p.body_offset);
  w.put(p.q);
  w.put(sim.ledger_);
  const ClumpBodies& cb = s.bodies;
  w.put(cb.x);
  w.put(cb.v);
  w.put(cb.rotation);
  w.put(cb.force);
  w.put(cb.torque);
  w.seal();
  if (!out) throw std::runtime_error("cannot write the saved state");
}

void StateIO::read(Simulation& sim, std::istream& in) {
  const std::string data{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (data.size() < sizeof kMagic) throw std::runtime_error("not a saved state of this engine (too short)");
  if (std::memcmp(data.data(), kMagic, sizeof kMagic - 1) == 0 && data[7] != kMagic[7])
    throw std::runtime_error("a saved state of another version of this engine (format byte " +
                             std::to_string(static_cast<unsigned char>(data[7])) + ", this one reads '" + kMagic[7] +
                             "'): run the job again from its start");
  if (std::memcmp(data.data(), kMagic, sizeof kMagic) != 0)
    throw std::runtime_error("not a saved state of this engine (wrong first bytes)");
  if (data.size() < sizeof kMagic + 4) throw std::runtime_error("the saved state ends inside the header (truncated)");
  const std::size_t body = data.size() - 4;
  boost::crc_32_type crc;
  crc.process_bytes(data.data(), body);
  std::uint32_t sum = 0;
  std::memcpy(&sum, data.data() + body, sizeof sum);
  if (sum != crc.checksum())
    throw std::runtime_error(
        "the saved state's checksum does not match its contents: the file was changed, damaged or "
        "cut short after it was written");

  SimState& s = sim.state_;
  // What the job itself fixes, to hold the saved state against.
  std::size_t n = s.particles.size();  // the given particles, and then those the sources inserted
  const std::size_t bodies = s.bodies.size();
  const std::vector<Wall> spec_walls = s.walls;
  // per particle id: its material and clump (-1: free), which the state must keep; and the sizes of
  // the arrays that only some scenes have
  std::vector<int> material_of_id(n), body_of_id(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    material_of_id[s.particles.id[i]] = s.particles.material[i];
    if (!s.particles.body.empty()) body_of_id[s.particles.id[i]] = s.particles.body[i];
  }
  std::size_t externals = s.particles.external.size(), members = s.particles.body.size(),
              offsets = s.particles.body_offset.size(), orientations = s.particles.q.size();
  const bool rolling_spring = sim.kernel_->has_rolling_spring();

  Reader r(data.data() + sizeof kMagic, body - sizeof kMagic);
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
  Boundaries& boundaries = sim.boundaries_;
  if (walls != boundaries.drivers_.size())
    mismatch("walls", static_cast<double>(walls), static_cast<double>(boundaries.drivers_.size()));
  if (dt != s.dt) mismatch("time step", dt, s.dt);
  r.get(sim.step_, "the step count");
  r.get(sim.builds_, "the step count");
  r.get(sim.last_build_step_, "the step count");
  r.get(sim.contacts_recorded_, "the step count");
  r.get(s.time, "the step count");
  if (sim.step_ < 0) inconsistent("its step count is " + std::to_string(sim.step_));
  if (sim.last_build_step_ < 0 || sim.last_build_step_ > sim.step_ || sim.builds_ < 0)
    inconsistent("the last neighbour build, step " + std::to_string(sim.last_build_step_) + ", is not before step " +
                 std::to_string(sim.step_));
  if (!std::isfinite(s.time)) inconsistent("the time is not finite");
  int stage = 0;
  std::int64_t stage_start = 0, stage_end = 0;
  r.get(stage, "the stage");
  r.get(stage_start, "the stage");
  r.get(stage_end, "the stage");
  std::uint8_t ended_early = 0;
  r.get(ended_early, "the stage");
  if (ended_early > 1) inconsistent("its stage's end flag is " + std::to_string(ended_early));
  const int stages = std::max<int>(1, static_cast<int>(sim.scene_.stages.size()));
  // (a run without stages may be stepped past its end by a caller of step(): its one stage's end is its length)
  if (stage < 0 || stage >= stages || stage_start < 0 || stage_start > sim.step_ ||
      (!sim.scene_.stages.empty() && stage_end < sim.step_))
    inconsistent("its stage " + std::to_string(stage) + " (steps " + std::to_string(stage_start) + " to " +
                 std::to_string(stage_end) + ") does not hold step " + std::to_string(sim.step_) + " of a run of " +
                 std::to_string(stages) + " stages");
  if (!sim.scene_.stages.empty()) {
    // A stage its end condition ended keeps the end it reached; any other ends where this spec says
    // (a continued run may lengthen it).
    const std::int64_t full_end = stage_start + sim.stage_steps(stage);
    const std::int64_t end = ended_early ? stage_end : full_end;
    if (end < sim.step_)
      throw std::runtime_error("the saved state is at step " + std::to_string(sim.step_) + ", past the end of stage " +
                               std::to_string(stage + 1) + " (\"" + sim.scene_.stages[stage].name + "\") at step " +
                               std::to_string(end) + " in this spec");
    sim.restore_stage(stage, stage_start, end, ended_early != 0);
  } else if (stage != 0 || stage_start != 0) {
    throw std::runtime_error("the saved state is of a staged run (in stage " + std::to_string(stage + 1) +
                             "), and this spec has no stages");
  }
  // The particles the sources inserted join the run first, as they entered: the arrays below hold them.
  std::vector<SourceProgress> progress;
  std::vector<InsertedParticle> inserted;
  r.get(progress, "the sources");
  r.get(inserted, "the sources");
  expect_size(progress, sim.scene_.sources.size(), "the sources' progress");
  if (particles != n + inserted.size())
    mismatch("particles", static_cast<double>(particles), static_cast<double>(n + inserted.size()));
  std::vector<std::int64_t> inserted_by(progress.size(), 0);
  for (std::size_t k = 0; k < inserted.size(); ++k) {
    const InsertedParticle& in = inserted[k];
    const std::string which = "inserted particle " + std::to_string(k);
    if (in.source < 0 || in.source >= static_cast<int>(progress.size()))
      inconsistent(which + " is of source " + std::to_string(in.source));
    if (in.material != sim.scene_.sources[in.source].material) inconsistent(which + " has another material");
    if (!in.position.allFinite() || !in.velocity.allFinite() || !(in.radius > 0) || !std::isfinite(in.radius))
      inconsistent(which + " has a position, velocity or radius that is not a number");
    ++inserted_by[in.source];
  }
  for (std::size_t k = 0; k < progress.size(); ++k)
    if (progress[k].inserted != inserted_by[k] || !std::isfinite(progress[k].mass) || progress[k].mass < 0)
      inconsistent("source " + std::to_string(k) + " counts " + std::to_string(progress[k].inserted) +
                   " particles inserted, and the state holds " + std::to_string(inserted_by[k]));
  sim.source_progress_ = progress;
  for (const InsertedParticle& in : inserted) {
    ParticleInit init;
    init.position = in.position;
    init.velocity = in.velocity;
    init.radius = in.radius;  // its size now is in the arrays read below
    init.material = in.material;
    init.source = in.source;
    sim.append_particle(init);
    material_of_id.push_back(in.material);
    body_of_id.push_back(-1);
  }
  n = s.particles.size();
  externals = s.particles.external.size();
  members = s.particles.body.size();
  offsets = s.particles.body_offset.size();
  orientations = s.particles.q.size();

  // bonds glued at a stage's start are in the state from that stage on, and only then
  const int bonding_stage = sim.scene_.bonding_stage();
  const bool glued_since_start = bonding_stage > 0 && bonding_stage <= stage;
  if (!glued_since_start && bonds != s.bonds.bonds().size())
    mismatch("bonds", static_cast<double>(bonds), static_cast<double>(s.bonds.bonds().size()));
  if (glued_since_start && bonds == 0) orientations = 0;  // a stage that glued nothing dropped them (glue_bonds)

  Particles& p = s.particles;
  r.get(p.x, "the particles");
  r.get(p.v, "the particles");
  r.get(p.w, "the particles");
  r.get(p.f, "the particles");
  r.get(p.t, "the particles");
  r.get(p.radius, "the particles");
  r.get(p.mass, "the particles");
  r.get(p.inv_mass, "the particles");
  r.get(p.inv_inertia, "the particles");
  r.get(p.material, "the particles");
  r.get(p.id, "the particles");
  r.get(p.external, "the particles");
  r.get(s.half_kick, "the particles");
  s.spin_kick.assign(n, Vec3::Zero());  // not saved: the next drift makes it before any contact reads it
  r.get(sim.x_at_build_, "the particles");
  for (const auto* v : {&p.x, &p.v, &p.w, &p.f, &p.t, &s.half_kick, &sim.x_at_build_})
    expect_size(*v, n, "a particle array");
  for (const auto* v : {&p.radius, &p.mass, &p.inv_mass, &p.inv_inertia}) expect_size(*v, n, "a particle array");
  expect_size(p.material, n, "the particles' materials");
  expect_size(p.id, n, "the particles' ids");
  expect_size(p.external, externals, "the particles' external forces");
  expect_finite(p.x, "the position of particle");
  expect_finite(sim.x_at_build_, "the position at the last build of particle");
  for (const auto* v : {&p.v, &p.w, &p.f, &p.t, &s.half_kick})
    expect_finite(*v, "a velocity, force or kick of particle");
  // no farther out than a spec may place a particle (Simulation::refuse_positions_past_precision)
  for (std::size_t i = 0; i < n; ++i)
    if (p.x[i].cwiseAbs().maxCoeff() > 1e9 * sim.smallest_given_radius_ ||
        sim.x_at_build_[i].cwiseAbs().maxCoeff() > 1e9 * sim.smallest_given_radius_)
      inconsistent("particle " + std::to_string(i) + " is farther out than 1e9 of the smallest radius");
  for (std::size_t i = 0; i < n; ++i)
    if (!(p.radius[i] > 0) || !std::isfinite(p.radius[i]) || !(p.mass[i] > 0) || !std::isfinite(p.mass[i]) ||
        !(p.inv_mass[i] >= 0) || !std::isfinite(p.inv_mass[i]) || !(p.inv_inertia[i] >= 0) ||
        !std::isfinite(p.inv_inertia[i]))
      inconsistent("particle " + std::to_string(i) + " has a radius, mass or inertia that is not a positive number");
  expect_indices(p.id, 0, static_cast<int>(n), "the id of particle");
  {
    std::vector<std::uint8_t> seen(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      if (seen[p.id[i]]) inconsistent("two particles have the id " + std::to_string(p.id[i]));
      seen[p.id[i]] = 1;
      if (p.material[i] != material_of_id[p.id[i]])
        inconsistent("particle id " + std::to_string(p.id[i]) + " has another material");
    }
  }

  NeighborList& nl = s.neighbors;
  r.get(nl.row_start, "the neighbour list");
  r.get(nl.partner, "the neighbour list");
  r.get(nl.shear, "the neighbour list");
  r.get(nl.roll, "the neighbour list");
  r.get(nl.touched, "the neighbour list");
  r.get(nl.sqrt_m_eff, "the neighbour list");
  r.get(nl.r_eff, "the neighbour list");
  r.get(nl.i_roll, "the neighbour list");
  r.get(s.pairs.fn, "the contacts");
  r.get(s.pairs.ft_squared, "the contacts");
  r.get(s.pairs.touching, "the contacts");
  const std::size_t pairs = nl.partner.size();
  expect_rows(nl.row_start, n, pairs, "the neighbour list's rows");
  for (std::size_t i = 0; i < n; ++i)
    for (int k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k)
      if (nl.partner[k] <= static_cast<int>(i) || nl.partner[k] >= static_cast<int>(n) ||
          (k > nl.row_start[i] && nl.partner[k] <= nl.partner[k - 1]))
        inconsistent("the neighbour list's pair " + std::to_string(k) + " of particle " + std::to_string(i) +
                     " has partner " + std::to_string(nl.partner[k]));
  expect_size(nl.shear, pairs, "the neighbour list's springs");
  expect_size(nl.roll, rolling_spring ? pairs : 0, "the neighbour list's rolling springs");
  for (const auto* v : {&nl.sqrt_m_eff, &nl.r_eff, &nl.i_roll, &s.pairs.fn, &s.pairs.ft_squared})
    expect_size(*v, pairs, "the neighbour list's pair values");
  expect_size(s.pairs.touching, pairs, "the neighbour list's pair values");
  expect_size(nl.touched, pairs, "the neighbour list's pair values");

  BlockPlan& b = s.blocks;
  r.get(b.block_size, "the block plan");
  // the engine's one size (BlockPlan): any other would sum in another order, or overflow n + size
  if (b.block_size != BlockPlan{}.block_size)
    inconsistent("the block size is " + std::to_string(b.block_size) + ", not the engine's " +
                 std::to_string(BlockPlan{}.block_size));
  sim.plan_blocks();

  WallContacts& wc = s.wall_contacts;
  r.get(wc.row_start, "the wall contacts");
  r.get(wc.wall, "the wall contacts");
  r.get(wc.shear, "the wall contacts");
  r.get(wc.roll, "the wall contacts");
  r.get(wc.constants, "the wall contacts");
  r.get(wc.fn, "the wall contacts");
  r.get(wc.ft, "the wall contacts");
  r.get(wc.touching, "the wall contacts");
  r.get(wc.force, "the wall contacts");
  r.get(wc.point, "the wall contacts");
  const std::size_t entries = wc.wall.size();
  expect_rows(wc.row_start, n, entries, "the wall contacts' rows");
  expect_indices(wc.wall, 0, static_cast<int>(spec_walls.size()), "the wall of wall contact");
  for (const auto* v : {&wc.shear, &wc.force, &wc.point}) expect_size(*v, entries, "the wall contacts' values");
  expect_size(wc.roll, rolling_spring ? entries : 0, "the wall contacts' rolling springs");
  expect_size(wc.constants, entries, "the wall contacts' constants");
  for (const auto* v : {&wc.fn, &wc.ft}) expect_size(*v, entries, "the wall contacts' values");
  wc.kn.assign(entries, 0.0);  // the next force pass sets them
  wc.cn.assign(entries, 0.0);
  expect_size(wc.touching, entries, "the wall contacts' values");

  MeshContacts& mc = s.mesh_contacts;
  r.get(mc.row_start, "the mesh contacts");
  r.get(mc.mesh, "the mesh contacts");
  r.get(mc.triangle, "the mesh contacts");
  r.get(mc.slots, "the mesh contacts");
  r.get(mc.used, "the mesh contacts");
  r.get(mc.constants, "the mesh contacts");
  if (!s.meshes.empty()) {
    const std::size_t candidates = mc.mesh.size();
    expect_rows(mc.row_start, n, candidates, "the mesh contacts' rows");
    expect_size(mc.triangle, candidates, "the mesh contacts' triangles");
    expect_indices(mc.mesh, 0, static_cast<int>(s.meshes.size()), "the mesh of mesh contact");
    for (std::size_t k = 0; k < candidates; ++k)
      if (mc.triangle[k] < 0 || static_cast<std::size_t>(mc.triangle[k]) >= s.meshes[mc.mesh[k]].triangles.size())
        inconsistent("mesh contact " + std::to_string(k) + " names triangle " + std::to_string(mc.triangle[k]) +
                     " of a mesh of " + std::to_string(s.meshes[mc.mesh[k]].triangles.size()));
    expect_size(mc.slots, n * MeshContacts::kSlots, "the mesh contacts' slots");
    for (std::size_t k = 0; k < mc.slots.size(); ++k)
      if (mc.slots[k].mesh < -1 || mc.slots[k].mesh >= static_cast<int>(s.meshes.size()))
        inconsistent("mesh contact slot " + std::to_string(k) + " names mesh " + std::to_string(mc.slots[k].mesh));
    expect_size(mc.used, n, "the mesh contacts' flags");
    expect_size(mc.constants, n, "the mesh contacts' constants");
    mc.parted.assign(n, MeshParting{});  // the loads saved already hold the last step's
  } else {
    for (const auto* v : {&mc.mesh, &mc.triangle}) expect_size(*v, 0, "the mesh contacts of a job without meshes");
    expect_size(mc.slots, 0, "the mesh contacts of a job without meshes");
  }

  // The planes and plates: their shape is the spec's, only where they are now comes from the state.
  std::vector<Wall> saved_walls;
  r.get(saved_walls, "the walls");
  expect_size(saved_walls, spec_walls.size(), "the planes and plates");
  for (std::size_t k = 0; k < spec_walls.size(); ++k) {
    expect_pose(saved_walls[k].pose, "the pose of plane or plate " + std::to_string(k));
    s.walls[k] = spec_walls[k];
    s.walls[k].move_to(saved_walls[k].pose);
  }
  std::vector<WallPose> mesh_poses(s.meshes.size());
  for (std::size_t m = 0; m < mesh_poses.size(); ++m) {
    r.get(mesh_poses[m], "the walls");
    expect_pose(mesh_poses[m], "the pose of mesh " + std::to_string(m));
  }
  std::vector<WallDriver> saved_drivers;
  for (std::size_t k = 0; k < boundaries.drivers_.size(); ++k) {
    WallDriver::Record record;
    r.get(record, "the walls");
    try {
      saved_drivers.push_back(WallDriver::from_record(record));
    } catch (const std::runtime_error& e) {
      inconsistent(sim.scene_.walls[k].where(k) + ": " + e.what());
    }
  }
  for (std::size_t m = 0; m < s.meshes.size();
       ++m) {  // a mesh that never moved keeps its vertices as read from the spec
    const WallPose& pose = mesh_poses[m];
    const bool moved = saved_drivers[s.meshes[m].boundary].moves() || !pose.displacement.isZero(0) ||
                       !pose.rotation.isIdentity(0);  // a load dropped earlier leaves it still, but elsewhere
    if (moved) s.meshes[m].move_to(pose);
  }
  std::vector<int> loads_starting;
  for (std::size_t k = 0; k < saved_drivers.size(); ++k) {
    try {
      if (boundaries.drivers_[k].continue_from(saved_drivers[k], sim.time()))
        loads_starting.push_back(static_cast<int>(k));
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(sim.scene_.walls[k].where(k) + " (" + sim.scene_.walls[k].name + "): " + e.what());
    }
  }
  r.get(boundaries.pose_at_build_, "the walls");
  r.get(sim.boundary_loads_, "the walls");
  expect_size(boundaries.pose_at_build_, boundaries.drivers_.size(), "the walls' poses");
  for (std::size_t k = 0; k < boundaries.pose_at_build_.size(); ++k)
    expect_pose(boundaries.pose_at_build_[k], "the pose at the last build of wall " + std::to_string(k));
  expect_size(sim.boundary_loads_, boundaries.drivers_.size(), "the walls' loads");
  for (int k : loads_starting) {  // a load that starts now feels the particles' push from the start, as at t = 0
    boundaries.drivers_[k].end_step(sim.time(), 0, sim.boundary_loads_[k].force, sim.boundary_loads_[k].response);
    boundaries.place(k, s.walls, s.meshes);
  }
  r.get(sim.growth_at_build_, "the walls");
  r.get(sim.growth_scale_, "the walls");
  if (!(sim.growth_scale_ > 0) || !std::isfinite(sim.growth_scale_) || !(sim.growth_at_build_ > 0) ||
      !std::isfinite(sim.growth_at_build_))
    inconsistent("the growth of the radii is not a positive number");
  // a continued run may not change a growth under way or done: the radii would jump to the new schedule
  const double expected_scale = sim.growth_scale_at(sim.step_);
  if (std::abs(sim.growth_scale_ - expected_scale) > 1e-12 * expected_scale) {
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "the saved state's particles have grown to %.12g times their given size by step %lld, and this "
                  "spec grows them to %.12g by then: a continued run may not change a growth under way or done "
                  "(its factor or its length)",
                  sim.growth_scale_, static_cast<long long>(sim.step_), expected_scale);
    throw std::runtime_error(buf);
  }

  std::vector<Bond> saved_bonds;
  r.get(saved_bonds, "the bonds");
  expect_size(saved_bonds, static_cast<std::size_t>(bonds), "the bonds");
  for (std::size_t k = 0; k < saved_bonds.size(); ++k) {
    const Bond& bond = saved_bonds[k];
    std::uint8_t state = 0, moments = 0;
    std::memcpy(&state, &bond.state, 1);      // its byte, not yet an enumerator
    std::memcpy(&moments, &bond.moments, 1);  // a bool that is neither 0 nor 1 must not be read as one
    if (bond.i < 0 || bond.j < 0 || bond.i >= static_cast<int>(n) || bond.j >= static_cast<int>(n) ||
        bond.i == bond.j || state > static_cast<std::uint8_t>(BondBreak::Shear) || moments > 1)
      inconsistent("bond " + std::to_string(k) + " joins particles " + std::to_string(bond.i) + " and " +
                   std::to_string(bond.j) + " (state " + std::to_string(state) + ", moments " +
                   std::to_string(moments) + ")");
  }
  s.bonds.restore(std::move(saved_bonds));

  r.get(p.body, "the clumps");
  r.get(p.body_offset, "the clumps");
  r.get(p.q, "the orientations");
  // A state saved with no bond and no orientation (its spec glued nothing by then, glue_bonds), read
  // for a spec with a bonding stage still to come: the bonds will measure their turns from their
  // gluing, so the orientations start there as they would at t = 0.
  if (p.q.empty() && orientations == n && bonds == 0) p.q.assign(n, Quat::Identity());
  expect_size(p.body, members, "the clump of each particle");
  expect_size(p.body_offset, offsets, "the clump offsets");
  expect_size(p.q, orientations, "the orientations");
  for (std::size_t i = 0; i < p.body.size(); ++i)  // the ids were checked above
    if (p.body[i] != body_of_id[p.id[i]])
      inconsistent("particle id " + std::to_string(p.id[i]) + " is in another clump");
  r.get(sim.ledger_, "the energy ledger");
  ClumpBodies& cb = s.bodies;
  r.get(cb.x, "the clumps");
  r.get(cb.v, "the clumps");
  r.get(cb.rotation, "the clumps");
  r.get(cb.force, "the clumps");
  r.get(cb.torque, "the clumps");
  for (const auto* v : {&cb.x, &cb.v, &cb.force, &cb.torque}) expect_size(*v, bodies, "the clumps");
  expect_size(cb.rotation, bodies, "the clumps' rotations");
  index_members(cb, p);  // the saved order of the members
  if (!r.at_end()) inconsistent("bytes follow its last value");
  // A free particle weighs what the spec makes of its radius: a state saved with another dimension, disc thickness
  // or density would go on with masses (and a plane) the spec does not describe.
  {
    const Grain grain = sim.scene_.grain();
    auto kg = [](double m) {
      char text[32];
      std::snprintf(text, sizeof text, "%.6g kg", m);
      return std::string(text);
    };
    for (std::size_t i = 0; i < n; ++i) {
      if (!p.body.empty() && p.body[i] >= 0) continue;  // a clump's member: its body's share
      const double expected = grain.mass(sim.scene_.materials[p.material[i]].density, p.radius[i]);
      if (std::abs(p.mass[i] - expected) > 1e-9 * expected || (sim.scene_.plane && p.x[i].y() != 0))
        throw std::runtime_error(
            "the saved state does not belong to this spec: particle " + std::to_string(p.id[i] + 1) + " weighs " +
            kg(p.mass[i]) + " there, and " + kg(expected) + " as the spec's " + (sim.scene_.plane ? "disc" : "sphere") +
            " of its radius: the spec's dimension, discThickness or density is not the one the state was saved with");
    }
  }
}

void StateIO::require_within_run(const Simulation& sim) {
  if (sim.step_count() > sim.total_steps())
    throw std::runtime_error("the saved state is at step " + std::to_string(sim.step_count()) +
                             " (t = " + std::to_string(sim.time()) + " s), past the end of this run at step " +
                             std::to_string(sim.total_steps()) + ": it cannot be continued to this run's duration");
}

void StateIO::write_file(const Simulation& sim, const std::string& path) {
  const std::string part = path + ".part";
  auto refuse = [&](int reason) {
    std::error_code ignored;
    std::filesystem::remove(part, ignored);  // the last whole state stays at `path`
    throw std::runtime_error("cannot write " + part + " (the saved state, renamed to " + path +
                             " when whole): " + std::strerror(reason != 0 ? reason : EIO));
  };
  {
    std::ofstream out(part, std::ios::binary | std::ios::trunc);
    if (!out) refuse(errno);
    try {
      write(sim, out);
      out.flush();
    } catch (const std::runtime_error&) {
      refuse(errno);
    }
    if (!out) refuse(errno);
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
