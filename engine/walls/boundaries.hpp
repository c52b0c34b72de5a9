// The scene's walls as one list, in Scene::walls order, whatever their kind. Planes and plates keep their
// geometry in SimState::walls and meshes in SimState::meshes (the force loop reads those two); Boundaries
// keeps, for every scene wall, its driver (a prescribed motion or a load), where its geometry is, whether
// the stage has it, how far its points reach from its centre and its pose at the last neighbour build, and
// moves each wall's geometry with its driver. A stage adds or removes a wall of any kind the same way.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/scene.hpp"
#include "mesh/mesh_wall.hpp"
#include "walls/wall.hpp"
#include "walls/wall_motion.hpp"

namespace dem {

// What the particles do to one wall (in Scene::walls order) this step: the force on the wall and
// its torque about the wall's centre (the rotation centre of its motion).
struct BoundaryLoad {
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();
  int contacts = 0;
  int padding = 0;           // saved with the state: its bytes are set, not whatever the memory held
  ContactResponse response;  // how that force answers the wall's motion (a servo's loop gain)
};

class Boundaries {
 public:
  // Every scene wall's geometry, appended to `walls` (planes, plates) or `meshes`, and its driver. `reach`: the
  // particles a plane must be wide enough for (those given, and the sources' extremes).
  void build(const Scene& scene, const std::vector<ParticleInit>& reach, std::vector<Wall>& walls,
             std::vector<MeshWall>& meshes);
  // Which walls may move, come or go during the run (their own motion or load, a stage's change, a stage
  // adding or removing them), once the first stage's settings are in the drivers.
  void note_variation(const Scene& scene);

  int size() const { return static_cast<int>(drivers_.size()); }
  WallDriver& driver(int k) { return drivers_[k]; }
  const WallDriver& driver(int k) const { return drivers_[k]; }
  int plane_index(int k) const { return plane_index_[k]; }  // in SimState::walls, or -1 (a mesh)
  int mesh_index(int k) const { return mesh_index_[k]; }    // in SimState::meshes, or -1
  int of_plane(int p) const { return of_plane_[p]; }        // the scene wall of SimState::walls[p]
  bool present(int k) const { return present_[k] != 0; }
  void set_present(int k, bool there) { present_[k] = there ? 1 : 0; }
  bool varies(int k) const { return varies_[k] != 0; }
  bool any_varies() const;
  bool any_moving() const;  // present and moving now
  std::vector<WallPose> poses() const;

  // The first half of a step for the walls that move: their drivers' motion, their geometry moved.
  void begin_step(double t_new, double dt, std::vector<Wall>& walls, std::vector<MeshWall>& meshes);
  // The loaded walls' second half, under `loads` (per scene wall), their geometry moved.
  void end_step(double t_new, double dt, const std::vector<BoundaryLoad>& loads, std::vector<Wall>& walls,
                std::vector<MeshWall>& meshes);
  // Moves wall k's geometry to where its driver has it.
  void place(int k, std::vector<Wall>& walls, std::vector<MeshWall>& meshes) const;

  // How far any wall point may have moved since the last neighbour build (mark_build): the shift of its
  // centre plus the arc its farthest point has turned through.
  double shift_since_build() const;
  void mark_build();
  // The first present moving wall whose points moved more than `reach` since `before` (per scene wall), and
  // how far: a wall that could pass through a particle unseen.
  std::optional<std::pair<int, double>> moved_past(const std::vector<WallPose>& before, double reach) const;

  // Wall k's faces where it is now (a plate's two triangles, a mesh's triangles; none when absent).
  std::vector<std::array<Vec3, 3>> faces(int k, const std::vector<Wall>& walls,
                                         const std::vector<MeshWall>& meshes) const;
  // Whether a sphere at x of radius r touches a wall there now.
  bool touches(const Vec3& x, double r, const std::vector<Wall>& walls, const std::vector<MeshWall>& meshes) const;

 private:
  friend class StateIO;  // saves the drivers' records and the poses at the last build
  double moved_since(int k, const WallPose& then) const;

  std::vector<WallDriver> drivers_;
  std::vector<int> plane_index_, mesh_index_;
  std::vector<int> of_plane_;
  std::vector<std::uint8_t> present_;  // in this stage
  std::vector<std::uint8_t> varies_;
  std::vector<double> extent_;  // largest distance of a wall's points from its centre
  std::vector<WallPose> pose_at_build_;
};

}  // namespace dem
