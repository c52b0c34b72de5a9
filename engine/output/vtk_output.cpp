#include "output/vtk_output.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <numeric>
#include <optional>
#include <regex>
#include <vector>

namespace dem {
namespace {

namespace fs = std::filesystem;
constexpr std::uint8_t kVtkVertex = 1;  // VTK's cell type of a single point

// The particles in the order of their ids (the order of the legacy files), not of the engine's
// spatial sort: a particle keeps its place from frame to frame.
std::vector<int> by_id(const Particles& p) {
  std::vector<int> order(p.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return p.id[a] < p.id[b]; });
  return order;
}

// Line cells 0-1, 2-3, ... over `count` lines of two points each.
std::vector<vtk::DataArray> two_point_lines(std::int64_t count) {
  std::vector<std::int64_t> connectivity(2 * count), offsets(count);
  std::iota(connectivity.begin(), connectivity.end(), 0);
  for (std::int64_t k = 0; k < count; ++k) offsets[k] = 2 * (k + 1);
  return {vtk::int64("connectivity", connectivity), vtk::int64("offsets", offsets)};
}

vtk::Dataset particles_of(const Simulation& sim) {
  const Particles& p = sim.particles();
  const std::vector<int> order = by_id(p);
  const std::size_t n = order.size();
  std::vector<Vec3> x(n), v(n), w(n), displacement(n), force(n);
  std::vector<std::int64_t> id(n);
  std::vector<double> radius(n), mass(n);
  std::vector<int> material(n);
  for (std::size_t k = 0; k < n; ++k) {
    const int i = order[k];
    x[k] = p.x[i];
    v[k] = p.v[i];
    w[k] = p.w[i];
    displacement[k] = p.x[i] - sim.scene().particles[p.id[i]].position;
    force[k] = p.f[i];
    id[k] = p.id[i] + 1;  // from 1, as in the legacy files
    radius[k] = p.radius[i];
    mass[k] = p.mass[i];
    material[k] = p.material[i];
  }
  vtk::Dataset d;
  d.type = "UnstructuredGrid";
  d.counts = {{"NumberOfPoints", static_cast<std::int64_t>(n)}, {"NumberOfCells", static_cast<std::int64_t>(n)}};
  d.points = vtk::vectors("Points", x);
  d.point_data = {vtk::int64("id", id),
                  vtk::float64("radius", radius),
                  vtk::float64("mass", mass),
                  vtk::int32("material", material),
                  vtk::vectors("velocity", v),
                  vtk::vectors("angularVelocity", w),
                  vtk::vectors("displacement", displacement),
                  vtk::vectors("force", force)};
  auto per_particle = [&](const std::vector<int>& by_index) {
    std::vector<int> out(n);
    for (std::size_t k = 0; k < n; ++k) out[k] = by_index[order[k]];
    return out;
  };
  if (sim.contacts_recorded()) d.point_data.push_back(vtk::int32("contacts", per_particle(sim.contact_counts())));
  if (!p.body.empty()) {
    std::vector<int> clump = per_particle(p.body);
    for (int& c : clump) ++c;  // from 1; 0 for a free sphere
    d.point_data.push_back(vtk::int32("clump", clump));
  }
  if (!sim.bonds().empty()) d.point_data.push_back(vtk::int32("fragment", per_particle(sim.fragments())));
  std::vector<std::int64_t> connectivity(n), offsets(n);
  std::iota(connectivity.begin(), connectivity.end(), 0);
  std::iota(offsets.begin(), offsets.end(), 1);
  d.topology = {{"Cells",
                 {vtk::int64("connectivity", connectivity), vtk::int64("offsets", offsets),
                  vtk::uint8("types", std::vector<std::uint8_t>(n, kVtkVertex))}}};
  return d;
}

vtk::Dataset lines(std::vector<Vec3> ends, std::vector<vtk::DataArray> cell_data) {
  const auto count = static_cast<std::int64_t>(ends.size() / 2);
  vtk::Dataset d;
  d.type = "PolyData";
  d.counts = {{"NumberOfPoints", 2 * count},
              {"NumberOfVerts", 0},
              {"NumberOfLines", count},
              {"NumberOfStrips", 0},
              {"NumberOfPolys", 0}};
  d.points = vtk::vectors("Points", ends);
  d.cell_data = std::move(cell_data);
  d.topology = {{"Lines", two_point_lines(count)}};
  return d;
}

vtk::Dataset contacts_of(const Simulation& sim) {
  const Particles& p = sim.particles();
  std::vector<PairContact> pairs = sim.pair_contacts();
  // in the order of the ids, as the legacy ForceChain_3D.dat
  for (PairContact& c : pairs)
    if (p.id[c.j] < p.id[c.i]) std::swap(c.i, c.j);
  std::sort(pairs.begin(), pairs.end(), [&](const PairContact& a, const PairContact& b) {
    return p.id[a.i] != p.id[b.i] ? p.id[a.i] < p.id[b.i] : p.id[a.j] < p.id[b.j];
  });
  std::vector<Vec3> ends;
  std::vector<double> fn, ft;
  for (const PairContact& c : pairs) {
    ends.push_back(p.x[c.i]);
    ends.push_back(p.x[c.j]);
    fn.push_back(c.fn);
    ft.push_back(c.ft);
  }
  return lines(std::move(ends), {vtk::float64("normalForce", fn), vtk::float64("tangentialForce", ft)});
}

vtk::Dataset bonds_of(const Simulation& sim) {
  const Particles& p = sim.particles();
  std::vector<Vec3> ends;
  std::vector<std::uint8_t> state;
  std::vector<double> fn, fs;
  for (const Bond& b : sim.bonds().bonds()) {  // in the order they were glued
    ends.push_back(p.x[b.i]);
    ends.push_back(p.x[b.j]);
    state.push_back(static_cast<std::uint8_t>(b.state));
    const bool intact = b.state == BondBreak::Intact;
    fn.push_back(intact ? b.normal_force : 0.0);
    fs.push_back(intact ? b.shear_force.norm() : 0.0);
  }
  return lines(std::move(ends),
               {vtk::uint8("state", state), vtk::float64("normalForce", fn), vtk::float64("shearForce", fs)});
}

// The walls of `scene_walls` (scene indices) present now. A mesh's triangles share its vertices.
vtk::Dataset walls_of(const Simulation& sim, const std::vector<int>& scene_walls) {
  std::vector<bool> wanted(sim.scene().walls.size(), false);
  for (int k : scene_walls) wanted[k] = true;
  const Particles& p = sim.particles();
  // An infinite plane is drawn as a square about the particles, 1.5 times their extent across (2 m
  // without particles).
  Vec3 lo = Vec3::Constant(-1), hi = Vec3::Constant(1);
  if (p.size() > 0) {
    lo = hi = p.x[0];
    for (std::size_t i = 0; i < p.size(); ++i) {
      lo = lo.cwiseMin(p.x[i] - Vec3::Constant(p.radius[i]));
      hi = hi.cwiseMax(p.x[i] + Vec3::Constant(p.radius[i]));
    }
  }
  const Vec3 centre = 0.5 * (lo + hi);
  const double half = 0.75 * (hi - lo).maxCoeff();
  std::vector<Vec3> points;
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<int> wall;
  auto polygon = [&](std::initializer_list<Vec3> corners, int scene_wall) {
    for (const Vec3& c : corners) {
      connectivity.push_back(static_cast<std::int64_t>(points.size()));
      points.push_back(c);
    }
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    wall.push_back(scene_wall + 1);  // from 1, as in Wall_ForceChain_3D.dat
  };
  for (int k = 0; k < static_cast<int>(sim.walls().size()); ++k) {
    const int scene_wall = sim.boundary_of_plane(k);
    if (!wanted[scene_wall] || !sim.wall_present(scene_wall)) continue;
    const Wall& w = sim.walls()[k];
    if (w.kind == Wall::Kind::Plate) {
      polygon({w.corners[0], w.corners[1], w.corners[2], w.corners[3]}, scene_wall);
      continue;
    }
    const Vec3 n = w.normal;
    const Vec3 on_plane = centre - n.dot(centre - w.point) * n;
    const Vec3 u = n.unitOrthogonal() * half, v = n.cross(n.unitOrthogonal()) * half;
    polygon({on_plane - u - v, on_plane + u - v, on_plane + u + v, on_plane - u + v}, scene_wall);
  }
  for (const MeshWall& m : sim.meshes()) {
    if (!wanted[m.boundary] || !sim.wall_present(m.boundary)) continue;
    const auto first = static_cast<std::int64_t>(points.size());
    points.insert(points.end(), m.vertices.begin(), m.vertices.end());
    for (const auto& t : m.triangles) {
      for (int c : t) connectivity.push_back(first + c);
      offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
      wall.push_back(m.boundary + 1);
    }
  }
  vtk::Dataset d;
  d.type = "PolyData";
  d.counts = {{"NumberOfPoints", static_cast<std::int64_t>(points.size())},
              {"NumberOfVerts", 0},
              {"NumberOfLines", 0},
              {"NumberOfStrips", 0},
              {"NumberOfPolys", static_cast<std::int64_t>(offsets.size())}};
  d.points = vtk::vectors("Points", points);
  d.cell_data = {vtk::int32("wall", wall)};
  d.topology = {{"Polys", {vtk::int64("connectivity", connectivity), vtk::int64("offsets", offsets)}}};
  return d;
}

}  // namespace

std::string VtkWriter::frame_name(const std::string& kind, std::int64_t step) {
  char digits[24];
  std::snprintf(digits, sizeof digits, "%010lld", static_cast<long long>(step));
  return kind + "_" + digits + (kind == "particles" ? ".vtu" : ".vtp");
}

namespace {

// particles_0000012000.vtu and its kin: the kind and the step, or nothing for another name.
std::optional<std::pair<std::string, std::int64_t>> frame_file(const std::string& name) {
  static const std::regex pattern(R"((particles|contacts|bonds|walls)_(\d{10})\.vt[up])");
  std::smatch m;
  if (!std::regex_match(name, m, pattern)) return std::nullopt;
  const std::int64_t step = std::stoll(m[2]);
  if (name != VtkWriter::frame_name(m[1], step)) return std::nullopt;  // a .vtp of particles, ...
  return std::make_pair(m[1].str(), step);
}

// the files of a run that are not frames: its series and its walls that stay
constexpr const char* kRunFiles[] = {"particles.pvd", "contacts.pvd", "bonds.pvd", "walls.pvd", "walls.vtp"};

}  // namespace

void VtkWriter::remove_earlier(const std::string& folder) {
  std::error_code ec;
  std::vector<fs::path> earlier;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
    const std::string name = e.path().filename().string();
    bool ours = frame_file(name).has_value();
    for (const char* file : kRunFiles) ours = ours || name == file || name == std::string(file) + ".tmp";
    if (ours && e.is_regular_file(ec)) earlier.push_back(e.path());
  }
  for (const fs::path& p : earlier) fs::remove(p, ec);
}

VtkWriter::VtkWriter(const std::string& folder, const Simulation& sim, bool append) : folder_(folder) {
  for (int k = 0; k < static_cast<int>(sim.scene().walls.size()); ++k)
    (sim.wall_varies(k) ? moving_walls_ : fixed_walls_).push_back(k);
  // Where they are at the start is where they stay (a continued run keeps the file, whose planes
  // are drawn about where the particles were then).
  const fs::path fixed = fs::path(folder_) / "walls.vtp";
  if (!fixed_walls_.empty() && !(append && fs::is_regular_file(fixed)))
    vtk::write(fixed.string(), walls_of(sim, fixed_walls_), sim.time());
  if (!append) return;
  // The frames a continued run finds (a resumed server job: those up to its checkpoint, the later
  // ones removed) are the start of its series, with their times (step x dt: the step is fixed).
  std::map<std::string, std::map<std::int64_t, vtk::SeriesEntry>> found;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(folder_, ec)) {
    const std::string name = e.path().filename().string();
    const auto frame = frame_file(name);
    if (frame && e.is_regular_file(ec) && frame->second <= sim.step_count())
      found[frame->first][frame->second] = {static_cast<double>(frame->second) * sim.dt(), name};
  }
  for (const auto& [kind, frames] : found) {
    std::vector<vtk::SeriesEntry> entries;
    for (const auto& [step, entry] : frames) entries.push_back(entry);
    series_[kind].file = std::make_unique<vtk::SeriesFile>((fs::path(folder_) / (kind + ".pvd")).string(), entries);
    series_[kind].last_step = frames.rbegin()->first;
  }
}

void VtkWriter::add_to_series(const std::string& kind, std::int64_t step, double time) {
  Series& series = series_[kind];
  if (step <= series.last_step) return;  // a continued run writing again the frame it began at
  const vtk::SeriesEntry entry{time, frame_name(kind, step)};
  if (series.file)
    series.file->add(entry);
  else
    series.file = std::make_unique<vtk::SeriesFile>((fs::path(folder_) / (kind + ".pvd")).string(),
                                                    std::vector<vtk::SeriesEntry>{entry});
  series.last_step = step;
}

void VtkWriter::frame(const Simulation& sim) {
  const std::int64_t step = sim.step_count();
  const double time = sim.time();
  auto put = [&](const std::string& kind, const vtk::Dataset& data) {
    vtk::write((fs::path(folder_) / frame_name(kind, step)).string(), data, time);
    add_to_series(kind, step, time);
  };
  put("particles", particles_of(sim));
  if (sim.contacts_recorded()) put("contacts", contacts_of(sim));
  if (!sim.bonds().empty()) put("bonds", bonds_of(sim));
  if (!moving_walls_.empty()) put("walls", walls_of(sim, moving_walls_));
}

}  // namespace dem
