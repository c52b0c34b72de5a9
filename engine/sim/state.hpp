// Everything the force loop reads and writes, in one place.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "clumps/clump_bodies.hpp"
#include "bonds/bond_set.hpp"
#include "core/lanes.hpp"
#include "core/parallel.hpp"
#include "core/particles.hpp"
#include "neighbor/neighbor_list.hpp"
#include "mesh/mesh_wall.hpp"
#include "sim/phase_profile.hpp"
#include "walls/wall.hpp"

namespace dem {

// Particle-wall candidates of each particle (compressed rows), rebuilt with the neighbour list.
struct WallContacts {
  std::vector<int> row_start;            // size n + 1
  std::vector<int> wall;                 // wall index of each entry
  std::vector<Vec3> shear;               // tangential spring per entry
  std::vector<Vec3> roll;                // rolling spring per entry (EPSD only)
  std::vector<PairConstants> constants;  // computed at the build, like the pairs'
  std::vector<double> fn;                // normal force of the last step (0 when apart)
  std::vector<double> ft;                // tangential force magnitude of the last step
  std::vector<std::uint8_t> touching;
  std::vector<Vec3> force;  // on the particle, last step (zero when apart)
  std::vector<Vec3> point;  // contact point (the middle of the overlap), last step
  // The contact's dF_n/d(delta) and normal dashpot coefficient, last step (0 when apart): a servo
  // wall's loop gain. Set by every step's force pass before it is read; not saved.
  std::vector<double> kn, cn;
};

// A particle's contact with a mesh, kept from step to step: the spring history follows the contact
// as it moves from triangle to triangle (matched by its normal), not the triangle.
struct MeshSlot {
  int mesh = -1;    // -1: empty
  int padding = 0;  // saved with the state: its bytes are set, not whatever the memory held
  Vec3 normal = Vec3::Zero();
  Vec3 shear = Vec3::Zero();
  Vec3 roll = Vec3::Zero();
  Vec3 force = Vec3::Zero();  // on the particle
  Vec3 point = Vec3::Zero();  // the contact point (the middle of the overlap)
  Vec3 pull = Vec3::Zero();   // the part of `force` that acts through the particle's centre (a valley weight's pull)
  double fn = 0, ft = 0, delta = 0;
  double kn = 0, cn = 0;  // dF_n/d(delta) and the normal dashpot's coefficient (WallContacts::kn)
  double weight = 1;      // the face's share at a valley (mesh/mesh_wall.hpp): fn and force include it
};

// The spring's push on a particle on the step after it parted from a mesh's face (the impulse the
// last sample missed): kept for that step's wall load, so that the mesh's work counts it too.
struct MeshParting {
  int mesh = -1;              // -1: none this step
  Vec3 force = Vec3::Zero();  // on the particle
  Vec3 point = Vec3::Zero();
};

// Particle-mesh candidates (triangles within reach, rebuilt with the neighbour list, grouped by
// mesh) and each particle's contact slots.
struct MeshContacts {
  static constexpr int kSlots = 4;       // contacts with history per particle; more still push, fresh each step
  std::vector<int> row_start;            // size n + 1
  std::vector<int> mesh;                 // per candidate
  std::vector<int> triangle;             // per candidate
  std::vector<MeshSlot> slots;           // n * kSlots; in use first, then (if room) one with mesh = -1
  std::vector<std::uint8_t> used;        // per particle: any slot in use (the slots are not read otherwise)
  std::vector<PairConstants> constants;  // per particle, against any wall (computed at the build)
  // per particle: written by the force loop, read and cleared by the walls' loads of the same step
  // (so never saved: a saved state holds the loads themselves)
  std::vector<MeshParting> parted;

  // No particle has a face within reach: the steps skip the meshes' per-particle work (a mesh far
  // from every particle costs nothing; the build empties the slots still in use).
  bool none_near() const { return mesh.empty(); }

  // The slots of particle i in use.
  int count(int i) const {
    if (used.empty() || !used[i]) return 0;
    int k = 0;
    while (k < kSlots && slots[static_cast<std::size_t>(i) * kSlots + k].mesh >= 0) ++k;
    return k;
  }
  const MeshSlot& slot(int i, int k) const { return slots[static_cast<std::size_t>(i) * kSlots + k]; }
  MeshSlot& slot(int i, int k) { return slots[static_cast<std::size_t>(i) * kSlots + k]; }
};

// Results of the last force evaluation per listed pair, for observers (force chains, contact counts).
struct PairResults {
  std::vector<double> fn;          // normal force
  std::vector<double> ft_squared;  // squared tangential force
  std::vector<std::uint8_t> touching;
};

// Force and torque summed on one body (or one deferred share) during the pair loop, each padded to
// four doubles (the fourth stays zero): the four-lane loop adds a lane's share with one 32-byte load,
// add and store each, and the pair fits one cache line.
struct alignas(64) BodySums {
  Lanes4 f{}, t{};
};

// The force loop works on fixed blocks of consecutive (spatially sorted) particles. A pair whose
// partner j lies in the same block as i is added to both bodies at once; a pair that crosses to a
// later block leaves j's share here, to be added by j's block after all blocks are done. The blocks
// do not depend on the number of threads, so neither does any sum: results are bit-identical.
struct BlockPlan {
  int block_size = kParticleBlock;  // core/parallel.hpp
  std::vector<int> deferred_start;  // per particle p: its slots as j of crossing pairs (size n + 1)
  std::vector<int> owner;           // per pair: its i (the row it belongs to)
  std::vector<int> target;          // per pair: where j's share goes in sums, j or n + its slot
  // n particles, then the deferred slots (of each p in ascending pair order). All are zero whenever
  // the pair loop starts: the kick that adds them clears them.
  std::vector<BodySums> sums;
};

struct SimState {
  Particles particles;
  NeighborList neighbors;
  PairResults pairs;
  BlockPlan blocks;
  // bond forces of this step (the pairs' are summed in blocks.sums, the last step's total is particles.f)
  std::vector<Vec3> f_next;
  std::vector<Vec3> half_kick;  // velocity change of this step's first half kick, dt/2 f/m
  std::vector<Vec3> spin_kick;  // spin change of the same half kick, dt/2 t/I (made anew every drift)
  std::vector<Wall> walls;      // planes and plates
  WallContacts wall_contacts;
  std::vector<MeshWall> meshes;
  MeshContacts mesh_contacts;
  BondSet bonds;
  ClumpBodies bodies;  // rigid clumps; their members are particles
  double time = 0;     // of the forces being computed
  double local_damping = 0;
  Vec3 gravity = Vec3::Zero();
  double dt = 0;
  bool record_contacts = true;  // keep per-contact forces in `pairs` (observers need them)
  bool non_finite = false;      // some particle's position or velocity may have stopped being finite this step
  // Some contact of this step overlaps by more than overlap_limit times the smaller radius (the
  // stability guard's limit), found in the force loop at the cost of a comparison per contact.
  double overlap_limit = 0.25;
  std::atomic<bool> deep_overlap{false};
  PhaseProfile* profile = nullptr;  // where the steps' phases add their time (`dem run --profile`), or none
};

}  // namespace dem
