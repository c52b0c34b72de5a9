#include "output/run_results.hpp"

#include "sim/particle_sources.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <unordered_set>

namespace dem {
namespace {

constexpr const char* kTrackMagic = "DEM-RESULTS-TRACK 1";

// Whether particle i moves (a free sphere or a clump's member): held ones are the scene's scenery.
bool moves(const Particles& p, std::size_t i) { return p.inv_mass[i] > 0 || (!p.body.empty() && p.body[i] >= 0); }

// Up: against the gravity of the run's last stage (the scene's when no stage sets one); +z without gravity.
Vec3 up_of(const Scene& scene) {
  Vec3 g = scene.gravity;
  for (const Stage& stage : scene.stages)
    if (stage.gravity) g = *stage.gravity;
  return g.norm() > 0 ? Vec3(-g.normalized()) : Vec3(Vec3::UnitZ());
}

Vec3 horizontal(const Vec3& v, const Vec3& up) { return v - v.dot(up) * up; }

// Each particle's share of the mass: its own, or its clump's divided among the clump's members (a
// member's Particles::mass is its whole clump's, which the contacts' damping wants).
std::vector<double> mass_shares(const Simulation& sim) {
  const Particles& p = sim.particles();
  std::vector<double> share = p.mass;
  if (p.body.empty()) return share;
  std::vector<int> members(sim.state().bodies.mass.size(), 0);
  for (int b : p.body)
    if (b >= 0) ++members[b];
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.body[i] >= 0) share[i] = sim.state().bodies.mass[p.body[i]] / members[p.body[i]];
  return share;
}

// A rigid clump's centroid from its members' centres: x_i = X + R o_i with o_i the members' offsets
// in the body frame, R the rotation that best fits the offsets to the centres (Kabsch 1976, by SVD).
// Exact for a rigid body; the members' plain mean is not the centroid of a clump of unequal spheres.
Vec3 centroid_from_members(const std::vector<Vec3>& offsets, const std::vector<Vec3>& centres) {
  const double n = static_cast<double>(centres.size());
  Vec3 mean_o = Vec3::Zero(), mean_x = Vec3::Zero();
  for (std::size_t k = 0; k < centres.size(); ++k) {
    mean_o += offsets[k] / n;
    mean_x += centres[k] / n;
  }
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < centres.size(); ++k) h += (offsets[k] - mean_o) * (centres[k] - mean_x).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d fix = Eigen::Matrix3d::Identity();
  fix(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1 : 1;
  const Eigen::Matrix3d r = svd.matrixV() * fix * svd.matrixU().transpose();
  return mean_x - r * mean_o;
}

// What moves as one mass at the reference and at the end: each loose particle, and each rigid clump
// at its centroid (not its members: a clump of unequal spheres turning would seem to travel).
struct MassPoint {
  int particle = 0;  // a loose particle's index, or a clump's first member's
  double mass = 0;
  Vec3 start = Vec3::Zero(), end = Vec3::Zero();
};

std::vector<MassPoint> mass_points(const Simulation& sim, const std::map<int, Vec3>& reference) {
  const Particles& p = sim.particles();
  const ClumpBodies& bodies = sim.state().bodies;
  std::vector<MassPoint> points;
  std::vector<std::vector<int>> members(bodies.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto then = reference.find(p.id[i]);
    if (!moves(p, i) || then == reference.end()) continue;
    if (!p.body.empty() && p.body[i] >= 0)
      members[p.body[i]].push_back(static_cast<int>(i));
    else
      points.push_back({static_cast<int>(i), p.mass[i], then->second, p.x[i]});
  }
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (members[b].empty()) continue;
    std::vector<Vec3> offsets, centres;
    for (int i : members[b]) {
      offsets.push_back(p.body_offset[i]);
      centres.push_back(reference.at(p.id[i]));
    }
    points.push_back({members[b].front(), bodies.mass[b], centroid_from_members(offsets, centres), bodies.x[b]});
  }
  return points;
}

double mean_of(const std::vector<double>& values) {
  double sum = 0;
  for (double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

// The quantiles of `values` (not empty) at n fractions 0, 1/(n-1), ..., 1: linear between the sorted
// values (numpy's and R's default, type 7).
std::vector<double> quantiles_of(std::vector<double> values, int n) {
  std::sort(values.begin(), values.end());
  std::vector<double> out;
  for (int k = 0; k < n; ++k) {
    const double at = static_cast<double>(values.size() - 1) * k / (n - 1);
    const auto below = static_cast<std::size_t>(std::floor(at));
    const std::size_t above = std::min(below + 1, values.size() - 1);
    out.push_back(values[below] + (at - static_cast<double>(below)) * (values[above] - values[below]));
  }
  return out;
}

// Each piece's travel, their mean and quantiles (MotionResults::pieces).
void piece_travels(const Simulation& sim, const std::vector<MassPoint>& points, const Vec3& up, MotionResults& m) {
  const std::vector<int> label = sim.fragments();
  struct Piece {
    double mass = 0;
    Vec3 start = Vec3::Zero(), end = Vec3::Zero();
  };
  std::map<std::int64_t, Piece> pieces;  // without bonds a loose sphere's label is 0: it is its own piece
  for (const MassPoint& point : points) {
    const int i = point.particle;
    Piece& piece = pieces[label[i] > 0 ? label[i] : -1 - static_cast<std::int64_t>(i)];
    piece.mass += point.mass;
    piece.start += point.mass * point.start;
    piece.end += point.mass * point.end;
  }
  std::vector<double> travel;
  for (const auto& [key, piece] : pieces)
    if (piece.mass > 0) travel.push_back(horizontal((piece.end - piece.start) / piece.mass, up).norm());
  m.pieces = static_cast<int>(travel.size());
  if (travel.empty()) return;
  m.piece_travel_mean = mean_of(travel);
  m.piece_travel = quantiles_of(std::move(travel), MotionResults::kPieceQuantiles);
}

// What each source inserted, and its particles' heights at the end (RunResults::sources).
std::vector<SourceResults> source_results(const Simulation& sim) {
  const Scene& scene = sim.scene();
  const Particles& p = sim.particles();
  const Vec3 up = up_of(scene);
  std::vector<std::vector<double>> heights(scene.sources.size());
  for (std::size_t j = 0; j < p.size(); ++j) {
    const int source = scene.particles[p.id[j]].source;
    if (source >= 0) heights[source].push_back(p.x[j].dot(up));
  }
  std::vector<SourceResults> out;
  for (std::size_t k = 0; k < scene.sources.size(); ++k) {
    SourceResults s;
    s.name = scene.sources[k].name;
    s.inserted = sim.source_progress()[k].inserted;
    s.mass = sim.source_progress()[k].mass;
    s.crowded_batches = sim.source_progress()[k].crowded_batches;
    s.total_reached = total_reached(scene, scene.sources[k], sim.source_progress()[k]);
    if (!heights[k].empty()) {
      s.height_mean = mean_of(heights[k]);
      s.heights = quantiles_of(std::move(heights[k]), SourceResults::kHeightQuantiles);
    }
    out.push_back(std::move(s));
  }
  return out;
}

int last_stage(const Scene& scene) { return scene.stages.empty() ? 0 : static_cast<int>(scene.stages.size()) - 1; }

std::string number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

ResultsRecorder::ResultsRecorder(const Simulation& sim, const std::string& track, bool append) {
  if (append) read_track(track, sim.step_count(), static_cast<int>(sim.scene().walls.size()), sim.particles().size());
  const bool fresh = !append || !std::ifstream(track).good();
  // a continuation past the reference without it (no track file, or one that never got so far)
  // counts the motion from here; without the file, the load cycles too
  const bool reference_passed = sim.stage() == last_stage(sim.scene()) && sim.step_count() > sim.stage_start_step();
  const bool no_reference = append && reference_passed && !reference_;
  if (append && (fresh || no_reference)) {
    const std::string what = fresh && no_reference ? "the motion and the load cycles"
                             : fresh               ? "the load cycles"
                                                   : "the motion";
    notes_.push_back(std::string(kTrackName) + (fresh ? " was not in the run's folder" : " holds no reference") + ": " +
                     what + " count from the continuation at step " + std::to_string(sim.step_count()) +
                     ", not from the run's start");
  }
  track_ = OutputFile(track, !fresh);
  if (fresh) write_line(kTrackMagic);
  if (no_reference) {
    take_positions(sim);
    complete_reference(sim);
  }
}

void ResultsRecorder::write_line(const std::string& line) {
  std::fputs(line.c_str(), track_.get());
  std::fputc('\n', track_.get());
  track_.flush();
}

// The track file: its magic line, then
//   reference STEP TIME BONDS N STAGE-NAME   and N lines   p ID X Y Z FRAGMENT
//   load WALL STEP START-TIME START-DISPLACEMENT CYCLIC(0/1)
//   cycle WALL START-TIME K END-STEP END-TIME DISPLACEMENT PEAK F-MIN F-MAX
// Lines of steps past `up_to_step` (a run that went on past its saved state) are left out; a later
// line for the same thing wins.
void ResultsRecorder::read_track(const std::string& path, std::int64_t up_to_step, int walls, std::size_t particles) {
  std::ifstream in(path);
  if (!in) return;
  std::string line;
  if (!std::getline(in, line) || line != kTrackMagic)
    throw std::runtime_error(path + " is not a results track file (first line \"" + line.substr(0, 60) + "\")");
  auto bad = [&](const std::string& what) {
    throw std::runtime_error(path + ": " + what + " (line \"" + line.substr(0, 80) + "\")");
  };
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string kind;
    words >> kind;
    // N lines "p ID X Y Z FRAGMENT" after a reference or entered line, each passed to `take`
    auto read_particles = [&](std::size_t n, const char* whose, auto&& take) {
      for (std::size_t k = 0; k < n; ++k) {
        if (!std::getline(in, line)) bad(std::string("the ") + whose + " particles end early");
        std::istringstream pw(line);
        std::string tag;
        int id = 0, fragment = 0;
        Vec3 x;
        if (!(pw >> tag >> id >> x.x() >> x.y() >> x.z() >> fragment) || tag != "p")
          bad(std::string("a particle of the ") + whose + " is not p ID X Y Z FRAGMENT (or there are fewer)");
        if (id < 0 || static_cast<std::size_t>(id) >= particles)
          bad("no particle " + std::to_string(id) + " in the run");
        take(id, x, fragment);
      }
    };
    if (kind == "reference") {
      Reference r;
      std::size_t n = 0;
      if (!(words >> r.step >> r.time >> r.bonds_intact >> n)) bad("a reference line is not STEP TIME BONDS N STAGE");
      if (r.step < 0 || n > particles) bad("a reference at a step below 0, or of more particles than the run has");
      if (reference_) bad("a second reference");
      std::getline(words >> std::ws, r.stage);
      read_particles(n, "reference's", [&](int id, const Vec3& x, int fragment) {
        r.position[id] = x;
        r.fragment[id] = fragment;
      });
      if (r.step <= up_to_step) reference_ = std::move(r);
    } else if (kind == "entered") {
      std::int64_t step = 0;
      std::size_t n = 0;
      if (!(words >> step >> n)) bad("an entered line is not STEP N");
      if (!reference_ && step <= up_to_step) bad("particles entered before the reference");
      if (n > particles) bad("more particles entered than the run has");
      read_particles(n, "entered", [&](int id, const Vec3& x, int fragment) {
        if (step > up_to_step || !reference_) return;
        reference_->position.emplace(id, x);
        reference_->fragment.emplace(id, fragment);
      });
    } else if (kind == "load") {
      int wall = 0;
      std::int64_t step = 0;
      WallTrack w;
      if (!(words >> wall >> step >> w.start_time >> w.start_displacement >> w.cyclic))
        bad("a load line is not WALL STEP T0 X0 CYCLIC");
      if (wall < 0 || wall >= walls) bad("no such wall in the scene");
      if (step <= up_to_step) walls_[wall] = w;
    } else if (kind == "cycle") {
      int wall = 0;
      double start = 0;
      LoadCycle c;
      if (!(words >> wall >> start >> c.cycle >> c.end_step >> c.end_time >> c.displacement >> c.peak_displacement >>
            c.force_min >> c.force_max))
        bad("a cycle line is not WALL T0 K STEP TIME X PEAK F-MIN F-MAX");
      c.resilient = c.peak_displacement - c.displacement;
      auto found = walls_.find(wall);
      if (c.end_step > up_to_step) continue;
      if (found == walls_.end() || found->second.start_time != start) bad("a cycle of a load that never began");
      std::vector<LoadCycle>& cycles = found->second.cycles;
      if (c.cycle < 1 || c.cycle > static_cast<int>(cycles.size()) + 1)  // one after another, or one again
        bad("cycle " + std::to_string(c.cycle) + " after " + std::to_string(cycles.size()) + " cycles");
      cycles.resize(static_cast<std::size_t>(std::max<int>(c.cycle - 1, 0)));  // a later line for cycle K wins
      cycles.push_back(c);
    } else if (!kind.empty()) {
      bad("unknown line");
    }
  }
}

void ResultsRecorder::frame(const Simulation& sim) {
  if (!reference_ && !pending_ && sim.stage() == last_stage(sim.scene())) {
    take_positions(sim);  // the run's start (a run without stages, or with one)
    complete_reference(sim);
  }
}

// The reference is where the particles are when the last stage begins: at the end of the stage
// before it. Its pieces are those after the last stage's first step, whose start glues the bonds a
// stage asks for (the key block's bonds, glued as it is released).
void ResultsRecorder::step(const Simulation& sim) {
  if (!reference_) {
    const int last = last_stage(sim.scene());
    if (pending_) {
      complete_reference(sim);
    } else if (last > 0 && sim.stage() == last - 1 && sim.step_count() == sim.stage_end_step()) {
      take_positions(sim);
    } else if (sim.stage() == last) {  // a run continued inside its last stage without a track file
      take_positions(sim);
      complete_reference(sim);
    }
  } else if (sim.particles().size() > reference_->position.size()) {
    add_entered(sim);
  }
  track_loads(sim);
}

void ResultsRecorder::take_positions(const Simulation& sim) {
  Reference r;
  r.step = sim.step_count();
  r.time = sim.time();
  const Particles& p = sim.particles();
  for (std::size_t i = 0; i < p.size(); ++i) r.position[p.id[i]] = p.x[i];
  pending_ = std::move(r);
}

void ResultsRecorder::complete_reference(const Simulation& sim) {
  Reference r = std::move(*pending_);
  pending_.reset();
  r.stage = sim.stage_name();
  r.bonds_intact = sim.bonds().counts().intact;
  const Particles& p = sim.particles();
  const std::vector<int> fragment = sim.fragments();
  std::string lines;
  for (std::size_t i = 0; i < p.size(); ++i) {
    // a particle that entered in the stage's first step counts from where it is now
    const Vec3 x = r.position.emplace(p.id[i], p.x[i]).first->second;
    r.fragment[p.id[i]] = fragment[i];
    lines += "p " + std::to_string(p.id[i]) + ' ' + number(x.x()) + ' ' + number(x.y()) + ' ' + number(x.z()) + ' ' +
             std::to_string(fragment[i]) + '\n';
  }
  write_line("reference " + std::to_string(r.step) + ' ' + number(r.time) + ' ' + std::to_string(r.bonds_intact) + ' ' +
             std::to_string(p.size()) + ' ' + r.stage + (lines.empty() ? "" : "\n") +
             lines.substr(0, lines.empty() ? 0 : lines.size() - 1));
  reference_ = std::move(r);
}

// Particles a source inserted after the reference count from where they entered (their travel and
// the source's top): a fed scene's centre of mass is the particles', wherever they came from.
void ResultsRecorder::add_entered(const Simulation& sim) {
  const Particles& p = sim.particles();
  const std::vector<int> fragment = sim.fragments();
  std::string lines;
  std::size_t added = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!reference_->position.emplace(p.id[i], p.x[i]).second) continue;
    reference_->fragment[p.id[i]] = fragment[i];
    lines += "\np " + std::to_string(p.id[i]) + ' ' + number(p.x[i].x()) + ' ' + number(p.x[i].y()) + ' ' +
             number(p.x[i].z()) + ' ' + std::to_string(fragment[i]);
    ++added;
  }
  write_line("entered " + std::to_string(sim.step_count()) + ' ' + std::to_string(added) + lines);
}

// Per loaded wall: the cycles of a cyclic load close at each minimum of the load (its clock a whole
// number of periods), taking the displacement there; between them the peak and the force range.
void ResultsRecorder::track_loads(const Simulation& sim) {
  for (int k = 0; k < sim.boundaries().size(); ++k) {
    const WallDriver& d = sim.wall_driver(k);
    if (!d.load_controlled() || !sim.wall_present(k)) continue;
    auto found = walls_.find(k);
    if (found == walls_.end() || found->second.start_time != d.load_start()) {
      WallTrack w;  // a load that begins now (or begins anew: a stage changed it)
      w.start_time = d.load_start();
      w.start_displacement = d.load_displacement();
      w.cyclic = d.load()->kind == LoadControl::Kind::Cyclic;
      write_line("load " + std::to_string(k) + ' ' + std::to_string(sim.step_count()) + ' ' + number(w.start_time) +
                 ' ' + number(w.start_displacement) + (w.cyclic ? " 1" : " 0"));
      found = walls_.insert_or_assign(k, w).first;
    }
    WallTrack& w = found->second;
    const double x = d.load_displacement() - w.start_displacement;
    const double f = d.applied_force();
    w.all_f_min = w.any_force ? std::min(w.all_f_min, f) : f;
    w.all_f_max = w.any_force ? std::max(w.all_f_max, f) : f;
    w.any_force = true;
    const LoadControl& load = *d.load();
    if (load.kind != LoadControl::Kind::Cyclic || load.frequency <= 0 || load.cycles <= 0) continue;
    if (static_cast<int>(w.cycles.size()) >= load.cycles) continue;
    const double clock = sim.time() - d.load_start();
    // cycles completed by now; the step that reaches a minimum closes its cycle
    const int done = std::min(load.cycles, static_cast<int>(std::floor(clock * load.frequency + 1e-9)));
    if (!w.open) {
      w.open = true;
      w.peak = x;
      w.f_min = w.f_max = f;
    }
    w.peak = std::max(w.peak, x);
    w.f_min = std::min(w.f_min, f);
    w.f_max = std::max(w.f_max, f);
    while (static_cast<int>(w.cycles.size()) < done) {
      LoadCycle c;
      c.cycle = static_cast<int>(w.cycles.size()) + 1;
      c.end_step = sim.step_count();
      c.end_time = sim.time();
      c.displacement = x;
      c.peak_displacement = w.peak;
      c.resilient = w.peak - x;
      c.force_min = w.f_min;
      c.force_max = w.f_max;
      w.cycles.push_back(c);
      write_line("cycle " + std::to_string(k) + ' ' + number(w.start_time) + ' ' + std::to_string(c.cycle) + ' ' +
                 std::to_string(c.end_step) + ' ' + number(c.end_time) + ' ' + number(c.displacement) + ' ' +
                 number(c.peak_displacement) + ' ' + number(c.force_min) + ' ' + number(c.force_max));
      w.peak = x;  // the next cycle starts here
      w.f_min = w.f_max = f;
    }
  }
}

MotionResults ResultsRecorder::motion(const Simulation& sim) const {
  const Reference& ref = *reference_;
  const Particles& p = sim.particles();
  const Vec3 up = up_of(sim.scene());
  MotionResults m;
  m.reference_step = ref.step;
  m.reference_time = ref.time;
  m.reference_stage = ref.stage;

  // the centre of mass of the moving particles there at both instants
  const std::vector<MassPoint> points = mass_points(sim, ref.position);
  double mass = 0;
  Vec3 start = Vec3::Zero(), end = Vec3::Zero();
  for (const MassPoint& point : points) {
    mass += point.mass;
    start += point.mass * point.start;
    end += point.mass * point.end;
  }
  if (mass > 0) {
    m.com_start = start / mass;
    m.com_end = end / mass;
  }
  const Vec3 travel = horizontal(m.com_end - m.com_start, up);
  m.com_travel = travel.norm();
  m.com_drop = (m.com_start - m.com_end).dot(up);
  m.com_travel_angle = std::atan2(m.com_drop, m.com_travel) * 180 / std::numbers::pi;
  const Vec3 x_axis = horizontal(Vec3::UnitX(), up);
  m.direction = m.com_travel > 1e-12    ? Vec3(travel / m.com_travel)
                : x_axis.norm() > 1e-12 ? Vec3(x_axis.normalized())
                                        : Vec3(horizontal(Vec3::UnitY(), up).normalized());
  const Vec3 across = up.cross(m.direction);

  // the source's top (its highest particle at the reference) and its front then
  bool any_start = false;
  Vec3 crown = Vec3::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto then = ref.position.find(p.id[i]);
    if (!moves(p, i) || then == ref.position.end()) continue;
    const Vec3 top = then->second + p.radius[i] * up;
    const double front = then->second.dot(m.direction) + p.radius[i];
    if (!any_start || top.dot(up) > crown.dot(up)) crown = top;
    m.front_start = any_start ? std::max(m.front_start, front) : front;
    any_start = true;
  }

  piece_travels(sim, points, up, m);

  // the deposit at the end: its front (the toe), extent and covered area
  const bool planar = sim.scene().plane.has_value();
  double diameters = 0;
  int count = 0;
  double along_min = 0, along_max = 0, across_min = 0, across_max = 0;
  Vec3 toe = Vec3::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!moves(p, i)) continue;
    const double a = p.x[i].dot(m.direction), c = p.x[i].dot(across), r = p.radius[i];
    if (count == 0 || a + r > along_max) toe = p.x[i] + r * m.direction - r * up;
    along_min = count == 0 ? a - r : std::min(along_min, a - r);
    along_max = count == 0 ? a + r : std::max(along_max, a + r);
    across_min = count == 0 ? c - r : std::min(across_min, c - r);
    across_max = count == 0 ? c + r : std::max(across_max, c + r);
    diameters += 2 * r;
    ++count;
  }
  if (count == 0) return m;
  m.front_end = along_max;
  m.deposit_length = along_max - along_min;
  m.deposit_width = planar ? 0 : across_max - across_min;
  m.runout_length = (toe - crown).dot(m.direction);
  m.fall_height = (crown - toe).dot(up);
  m.h_over_l = m.runout_length > 0 ? m.fall_height / m.runout_length : 0;
  m.deposit_cell = diameters / count;
  if (!planar) {
    // footprints on cells of one mean diameter: a cell counts when its centre lies under a particle
    // (or it holds a particle's centre)
    const double cell = m.deposit_cell;
    std::unordered_set<std::uint64_t> covered;
    auto key = [](std::int64_t i, std::int64_t j) {
      return (static_cast<std::uint64_t>(i) << 32) ^ (static_cast<std::uint64_t>(j) & 0xffffffffU);
    };
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (!moves(p, i)) continue;
      const double a = p.x[i].dot(m.direction) / cell, c = p.x[i].dot(across) / cell, r = p.radius[i] / cell;
      const auto ia = static_cast<std::int64_t>(std::floor(a)), ic = static_cast<std::int64_t>(std::floor(c));
      covered.insert(key(ia, ic));
      for (auto u = static_cast<std::int64_t>(std::floor(a - r)); u <= static_cast<std::int64_t>(std::floor(a + r));
           ++u)
        for (auto v = static_cast<std::int64_t>(std::floor(c - r)); v <= static_cast<std::int64_t>(std::floor(c + r));
             ++v) {
          const double du = static_cast<double>(u) + 0.5 - a, dv = static_cast<double>(v) + 0.5 - c;
          if (du * du + dv * dv <= r * r) covered.insert(key(u, v));
        }
    }
    m.deposit_area = static_cast<double>(covered.size()) * cell * cell;
  }
  return m;
}

FragmentResults ResultsRecorder::fragment_results(const Simulation& sim) const {
  const Particles& p = sim.particles();
  const std::vector<int> label = sim.fragments();
  const std::vector<double> share = mass_shares(sim);
  FragmentResults r;
  std::map<int, std::pair<int, double>> pieces;  // label: particles, mass
  double total = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    auto& [n, mass] = pieces[label[i]];
    ++n;
    mass += share[i];
    total += share[i];
  }
  r.count = static_cast<int>(pieces.size());
  double largest = 0;
  for (const auto& [l, piece] : pieces) {
    largest = std::max(largest, piece.second);
    int bin = 0;
    while ((2 << bin) <= piece.first) ++bin;  // sizes 2^bin .. 2^(bin+1) - 1
    if (static_cast<int>(r.sizes.size()) <= bin) r.sizes.resize(bin + 1);
    FragmentBin& b = r.sizes[bin];
    b.min_particles = 1 << bin;
    b.max_particles = (2 << bin) - 1;
    ++b.fragments;
    b.mass += piece.second;
  }
  std::erase_if(r.sizes, [](const FragmentBin& b) { return b.fragments == 0; });
  r.largest_mass_fraction = total > 0 ? largest / total : 0;

  const BondCounts bonds = sim.bonds().counts();
  r.bonds_intact = bonds.intact;
  r.bonds_broken_tension = bonds.tension;
  r.bonds_broken_shear = bonds.shear;
  if (!reference_) return r;
  r.bonds_initial = reference_->bonds_intact;
  // each reference piece of more than one particle: its mass now, and its largest part now
  std::map<int, int> size_then;
  for (const auto& [id, piece] : reference_->fragment) ++size_then[piece];
  r.initial_count = static_cast<int>(size_then.size());
  std::map<int, std::map<int, double>> parts;  // reference piece: label now -> mass
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto then = reference_->fragment.find(p.id[i]);
    if (then == reference_->fragment.end() || size_then[then->second] < 2) continue;
    parts[then->second][label[i]] += share[i];
  }
  double pieced = 0;
  for (const auto& [piece, now] : parts) {
    double mass = 0, biggest = 0;
    for (const auto& [l, m] : now) {
      mass += m;
      biggest = std::max(biggest, m);
    }
    pieced += mass;
    r.crushed_mass += mass - biggest;
  }
  r.crushed_mass_fraction = pieced > 0 ? r.crushed_mass / pieced : 0;
  return r;
}

void ResultsRecorder::finish(const Simulation& sim, const RunOutcome& outcome) {
  RunResults& r = results_;
  r.notes = notes_;
  r.ok = outcome.ok;
  r.error = outcome.error;
  r.particles = sim.particles().size();
  r.steps = sim.step_count();
  r.simulated_time = sim.time();
  r.run_seconds = outcome.loop_seconds;
  r.time_step = sim.dt();
  const EnergyLedger& ledger = sim.energy_input();
  r.energy_start = ledger.initial_energy;
  r.energy_end = sim.mechanical_energy();
  r.energy_input = ledger.total();
  r.energy_dissipated = r.energy_start + r.energy_input - r.energy_end;
  r.kinetic_end = sim.kinetic_energy();
  if (reference_) r.motion = motion(sim);
  if (!sim.bonds().empty()) r.fragments = fragment_results(sim);
  r.sources = source_results(sim);
  r.loaded_walls.clear();
  for (const auto& [k, w] : walls_) {
    LoadedWallResults l;
    l.wall = sim.scene().walls[k].name;
    l.index = k;
    l.cyclic = w.cyclic;
    l.start_time = w.start_time;
    l.start_displacement = w.start_displacement;
    l.end_displacement = sim.wall_driver(k).load_displacement() - w.start_displacement;
    // the range since the load began: this run's, and the cycles' (of the run before a restart)
    l.force_min = w.all_f_min;
    l.force_max = w.all_f_max;
    bool any = w.any_force;
    for (const LoadCycle& c : w.cycles) {
      l.force_min = any ? std::min(l.force_min, c.force_min) : c.force_min;
      l.force_max = any ? std::max(l.force_max, c.force_max) : c.force_max;
      any = true;
    }
    l.cycles = w.cycles;
    r.loaded_walls.push_back(std::move(l));
  }
}

}  // namespace dem
