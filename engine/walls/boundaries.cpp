#include "walls/boundaries.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mesh/triangle_mesh.hpp"

namespace dem {

void Boundaries::build(const Scene& scene, const std::vector<ParticleInit>& reach, std::vector<Wall>& walls,
                       std::vector<MeshWall>& meshes) {
  const int n = static_cast<int>(scene.walls.size());
  plane_index_.assign(n, -1);
  mesh_index_.assign(n, -1);
  extent_.assign(n, 0.0);
  for (int k = 0; k < n; ++k) {
    const WallInit& w = scene.walls[k];
    Vec3 centroid;
    if (std::holds_alternative<MeshShape>(w.shape)) {
      mesh_index_[k] = static_cast<int>(meshes.size());
      meshes.push_back(MeshWall::from(w, k));
      centroid = meshes.back().centroid();
    } else {
      plane_index_[k] = static_cast<int>(walls.size());
      walls.push_back(Wall::from(w));
      centroid = walls.back().centroid();
    }
    drivers_.emplace_back(w, centroid, scene.gravity);
    const Vec3 c0 = drivers_.back().pose().center0;
    if (mesh_index_[k] >= 0) {
      for (const Vec3& v : meshes.back().vertices0) extent_[k] = std::max(extent_[k], (v - c0).norm());
    } else if (walls.back().kind == Wall::Kind::Plate) {
      for (const Vec3& v : walls.back().corners) extent_[k] = std::max(extent_[k], (v - c0).norm());
    } else {  // a plane is as wide as the particles' reach from its centre
      for (const ParticleInit& p : reach) extent_[k] = std::max(extent_[k], (p.position - c0).norm() + p.radius);
    }
  }
  present_.assign(n, 1);
  varies_.assign(n, 0);
  of_plane_.assign(walls.size(), 0);
  for (int k = 0; k < n; ++k)
    if (plane_index_[k] >= 0) of_plane_[plane_index_[k]] = k;
}

void Boundaries::note_variation(const Scene& scene) {
  for (int k = 0; k < size(); ++k)
    varies_[k] = drivers_[k].moves() || scene.walls[k].first_stage > 0 ||
                 scene.walls[k].last_stage != std::numeric_limits<int>::max();
  for (const Stage& stage : scene.stages)
    for (const WallChange& c : stage.wall_changes) varies_[c.wall] = 1;
}

bool Boundaries::any_varies() const {
  return std::any_of(varies_.begin(), varies_.end(), [](std::uint8_t v) { return v != 0; });
}

bool Boundaries::any_moving() const {
  for (int k = 0; k < size(); ++k)
    if (present_[k] && drivers_[k].moves()) return true;
  return false;
}

std::vector<WallPose> Boundaries::poses() const {
  std::vector<WallPose> out;
  out.reserve(drivers_.size());
  for (const WallDriver& d : drivers_) out.push_back(d.pose());
  return out;
}

void Boundaries::place(int k, std::vector<Wall>& walls, std::vector<MeshWall>& meshes) const {
  if (plane_index_[k] >= 0)
    walls[plane_index_[k]].move_to(drivers_[k].pose());
  else
    meshes[mesh_index_[k]].move_to(drivers_[k].pose());
}

void Boundaries::begin_step(double t_new, double dt, std::vector<Wall>& walls, std::vector<MeshWall>& meshes) {
  for (int k = 0; k < size(); ++k) {
    if (!present_[k] || !drivers_[k].moves()) continue;
    drivers_[k].begin_step(t_new, dt);
    place(k, walls, meshes);
  }
}

void Boundaries::end_step(double t_new, double dt, const std::vector<BoundaryLoad>& loads, std::vector<Wall>& walls,
                          std::vector<MeshWall>& meshes) {
  for (int k = 0; k < size(); ++k) {
    if (!present_[k] || !drivers_[k].load_controlled()) continue;
    drivers_[k].end_step(t_new, dt, loads[k].force, loads[k].response);
    place(k, walls, meshes);
  }
}

double Boundaries::moved_since(int k, const WallPose& then) const {
  const WallPose& now = drivers_[k].pose();
  const Eigen::Matrix3d turn = then.rotation.transpose() * now.rotation;
  const double angle = std::acos(std::clamp((turn.trace() - 1) / 2, -1.0, 1.0));
  return (now.displacement - then.displacement).norm() + angle * extent_[k];
}

double Boundaries::shift_since_build() const {
  double shift = 0;
  for (int k = 0; k < size(); ++k)
    if (present_[k] && drivers_[k].moves()) shift = std::max(shift, moved_since(k, pose_at_build_[k]));
  return shift;
}

void Boundaries::mark_build() { pose_at_build_ = poses(); }

std::optional<std::pair<int, double>> Boundaries::moved_past(const std::vector<WallPose>& before, double reach) const {
  for (int k = 0; k < size(); ++k) {
    if (!present_[k] || !drivers_[k].moves()) continue;
    const double moved = moved_since(k, before[k]);
    if (moved > reach) return std::pair{k, moved};
  }
  return std::nullopt;
}

std::vector<std::array<Vec3, 3>> Boundaries::faces(int k, const std::vector<Wall>& walls,
                                                   const std::vector<MeshWall>& meshes) const {
  std::vector<std::array<Vec3, 3>> out;
  if (!present_[k]) return out;
  if (plane_index_[k] >= 0) {
    const std::array<Vec3, 4>& c = walls[plane_index_[k]].corners;
    out.push_back({c[0], c[1], c[2]});
    out.push_back({c[0], c[2], c[3]});
    return out;
  }
  const MeshWall& mesh = meshes[mesh_index_[k]];
  for (const auto& t : mesh.triangles) out.push_back({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]});
  return out;
}

bool Boundaries::touches(const Vec3& x, double r, const std::vector<Wall>& walls,
                         const std::vector<MeshWall>& meshes) const {
  for (std::size_t w = 0; w < walls.size(); ++w)
    if (present_[of_plane_[w]] && walls[w].distance(x) < r) return true;
  const Vec3 lo = x - Vec3::Constant(r), hi = x + Vec3::Constant(r);
  for (const MeshWall& mesh : meshes) {
    if (!present_[mesh.boundary]) continue;
    bool touching = false;
    auto test = [&](int t) {
      const auto& tri = mesh.triangles[t];
      const Vec3 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]], &c = mesh.vertices[tri[2]];
      if ((a.cwiseMin(b).cwiseMin(c).array() > hi.array()).any() ||
          (a.cwiseMax(b).cwiseMax(c).array() < lo.array()).any())
        return;
      touching = touching || (closest_on_triangle(x, a, b, c).point - x).squaredNorm() < r * r;
    };
    if (!mesh.grid_stale)  // binned where the mesh is now
      mesh.grid.for_each_in_box(lo, hi, test);
    else
      for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) test(t);
    if (touching) return true;
  }
  return false;
}

}  // namespace dem
