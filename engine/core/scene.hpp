// The typed, checked description of a simulation, in SI units. Front ends (the spec loader, later the
// legacy INPT importer) build it; the engine only reads it.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/model_parameters.hpp"
#include "core/particles.hpp"
#include "core/size_distribution.hpp"
#include "core/vec.hpp"

namespace dem {

struct Material {
  std::string name;
  double density = 0;         // kg/m^3
  double youngs_modulus = 0;  // Pa
  double poisson_ratio = 0;
  double normal_stiffness = 0;  // N/m, linear model
  bool rigid = false;           // infinitely stiff: contributes nothing to the compliance
};

struct Interaction {
  double restitution = 1;
  double friction = 0;
  double rolling_friction = 0;
};

// The contact models by their schema names (contact/models.hpp lists them) and their parameters.
struct ContactSettings {
  std::string normal = "LINEAR";
  std::string rolling = "NONE";  // used only where a pair has rolling friction
  // A contact never pulls: impact theory's assumption, and the one under which friction's impulse is
  // mu times the normal impulse (with tension, the pull at parting has no friction: docs/physics.md).
  bool no_tensile_force = true;
  ModelParameters parameters;  // by field name; a model's default where absent
};

struct ParticleInit {
  Vec3 position = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();
  double radius = 0;
  int material = 0;
  bool fixed = false;
  Vec3 force = Vec3::Zero();  // constant external force, N
  int clump = -1;             // index in Scene::clumps of the rigid clump it belongs to, -1: free
  int stone = -1;             // the breakable stone it belongs to: bonds glue only spheres of one stone (-1: none)
  int source = -1;            // the source (Scene::sources) that inserted it during the run (-1: given)
};

// A rigid clump: overlapping member spheres (Scene::particles first .. first + count - 1) moving as
// one body. The body frame has its origin at the centroid and its axes along the principal axes.
struct ClumpInit {
  int first = 0;
  int count = 0;
  double mass = 0;
  Vec3 moments = Vec3::Zero();                                      // principal moments of inertia, kg m^2
  Vec3 position = Vec3::Zero();                                     // of the centroid
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // body frame -> space
  Vec3 velocity = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();
};

struct PlaneShape {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  // unit, points to the particles' side
};

struct PlateShape {
  std::array<Vec3, 4> corners;  // planar, in order around the edge
};

// A triangle mesh, already read and placed in the scene's frame (metres).
struct MeshShape {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;  // 0-based
  std::string source;                         // the file it came from, for messages and outputs
};

// Prescribed motion of a wall: its reference point moves with
// v(t) = velocity + amplitude sin(2 pi frequency t + phase), and the wall turns about that point
// with a constant angular velocity.
struct PrescribedMotion {
  Vec3 velocity = Vec3::Zero();
  Vec3 amplitude = Vec3::Zero();
  double frequency = 0;                  // Hz
  double phase = 0;                      // rad
  Vec3 angular_velocity = Vec3::Zero();  // rad/s
  std::optional<Vec3> center;            // rotation centre at t = 0; default the wall's centroid
};

// A wall driven by a force along `direction` (the direction it pushes the particles), free to
// move only along it. Cyclic: F(t) = F_min + (F_max - F_min) (1 - cos 2 pi f t) / 2 for `cycles`
// cycles, then F_min (the ballast test: 1.5 kN to 51.84 kN at 3 Hz, 15 cycles); the wall has a
// mass and moves under F(t), its weight and the particles' reaction. Servo: the wall moves at
// v = gain (target - F_contact), at most max_speed, until the particles push back with `target`.
struct LoadControl {
  enum class Kind { Cyclic, Servo };
  Kind kind = Kind::Cyclic;
  int cycles = 0;                   // (cyclic); beside `kind`, so that no padding lies between them (saved states)
  Vec3 direction = -Vec3::UnitZ();  // unit
  double mass = 0;                  // kg (cyclic)
  double f_min = 0, f_max = 0;      // N (cyclic)
  double frequency = 0;             // Hz (cyclic)
  double target = 0;                // N (servo)
  double gain = 0;                  // m/s per N (servo)
  double max_speed = 0;             // m/s (servo)

  // The prescribed force at time t (cyclic).
  double force_at(double t) const;
};

struct WallInit {
  std::string name;
  int material = 0;
  std::variant<PlaneShape, PlateShape, MeshShape> shape;
  std::optional<PrescribedMotion> motion;
  std::optional<LoadControl> load;
  // A staged run's wall is there from the start of stage first_stage to the end of last_stage
  // (Scene::stages); its motion's time counts from the start of first_stage.
  int first_stage = 0;
  int last_stage = std::numeric_limits<int>::max();
  std::string path{};  // where the spec gives it ("walls[2]", "stages[1].addWalls[0]"), for messages; "": walls[index]
  std::string where(std::size_t index) const { return path.empty() ? "walls[" + std::to_string(index) + "]" : path; }
  bool present_at(int stage) const { return stage >= first_stage && stage <= last_stage; }
};

struct Box {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
  bool contains(const Vec3& x) const { return (x.array() >= min.array()).all() && (x.array() <= max.array()).all(); }
};

// Bonds glued at the start (or at a stage's start: Stage::glue_bonds) between neighbours whose gap is at most
// gap_tolerance times the smaller radius (both centres inside `region` when given): parallel bonds (Potyondy & Cundall
// 2004), or contact bonds (forces only). The PDEM-EGD manual's BOND_MODEL, RPBN/RPBS, BSTRENGTH and BRATIO.
struct BondSettings {
  std::string model = "PARALLEL";    // a bond model of bonds/bond_models.hpp: PARALLEL or CONTACT
  double radius_multiplier = 1;      // lambda: Rb = lambda min(RA, RB)
  double youngs_modulus = 0;         // Eb, Pa: normal stiffness per area Eb / (RA + RB)
  double shear_stiffness_ratio = 1;  // ks / kn of the bond
  double tensile_strength = 0;       // Pa
  double shear_strength = 0;         // Pa
  double strength_spread = 0;        // relative standard deviation of each bond's strengths
  std::uint32_t seed = 1;
  double gap_tolerance = 1e-3;
  std::optional<Box> region;
  struct Zone {
    Box box;
    double strength_ratio = 1;  // BRATIO: strengths of bonds with their centre here are scaled
  };
  std::vector<Zone> zones;
};

// A source of particles during the run (the BallastDEM manual's wind-blown sand entering the ballast):
// spheres of `sizes` enter at `mass_rate` or `count_rate`, each at a random place in the region where it
// touches no particle and no wall (a crowded region holds the rest back until there is room), moving at
// `velocity`. Its k-th particle's size depends only on the seed and k, so a continued run inserts the same.
struct ParticleSource {
  std::string name;
  enum class Region { Box, Face };
  Region region = Region::Box;
  Box box;             // Box: each particle wholly inside it
  int face_wall = -1;  // Face: the faces of this plate or mesh (Scene::walls index), and the layer over them
  double depth = 0;    // this deep (m) on the side `velocity` points to (a face's normal side when along it)
  int material = 0;
  SizeDistribution sizes;
  std::uint64_t seed = 1;
  double mass_rate = 0;   // kg/s; or
  double count_rate = 0;  // particles/s
  // The most it inserts in all (a study's sand mass: 0, 2, 4 kg), then it stops: infinity and -1 when
  // not given. A source with a total of 0 inserts nothing (its particles still set the time step).
  double total_mass = std::numeric_limits<double>::infinity();  // kg
  std::int64_t total_count = -1;
  Vec3 velocity = Vec3::Zero();
  // Active from `start` to `end` (s), counted from the run's start, or from its stage's when `stage` >= 0
  // (then only during that stage).
  double start = 0;
  double end = std::numeric_limits<double>::infinity();
  int stage = -1;
  // inserts what has come due at most every this many steps (0 or 1: at every step; a step with
  // nothing due costs one comparison, one with something due a pass over the particles)
  std::int64_t every_steps = 0;
  std::string path{};  // where the spec gives it ("sources[0]"), for messages
};

enum class FileNumberFormat { Scientific, LegacyFixed, Full };

struct OutputSettings {
  std::int64_t every_steps = 0;  // 0: only the first and last frame (unless interval_seconds)
  double interval_seconds = 0;   // turned into every_steps once the time step is known
  bool animation = true;
  bool force_chains = false;
  double length_unit = 1.0;  // metres per file length unit (1e-3 for mm)
  std::string length_unit_name = "m";
  FileNumberFormat number_format = FileNumberFormat::Scientific;
  // The PDEM-EGD manual's NLast: the particles' frame files (animation, force chains) keep only the
  // last this many frames; the time series (energy, statistics, walls) keep every frame. 0: all.
  std::int64_t last_frames = 0;
  bool vtk = true;  // ParaView's files (output/vtk_output.hpp)
  bool csv = true;  // the time series' CSV twins (output/csv_table.hpp)
};

struct NumericsSettings {
  double skin_fraction = 0.1;  // of the mean diameter
  int search_interval = 0;     // 0: rebuild only when needed
  int threads = 0;             // 0: all cores
  double max_overlap_fraction = 0.25;
  int check_interval = 100;
  int reorder_interval = 10;
  // Local damping (Cundall; PFC's "local damping", YADE's NewtonIntegrator damping): each component
  // of a particle's force and torque is reduced by alpha |F| against its velocity. For quasi-static
  // loading (a cantilever, settling); 0 leaves the dynamics alone.
  double local_damping = 0;
};

struct TimeSettings {
  double dt = 0;                    // 0: automatic
  double dt_fraction = 1.0 / 50.0;  // of the shortest contact time (the PDEM-EGD manual's 1/50, section 4.1.1)
  double duration = 0;
  std::int64_t steps = 0;  // derived from duration when 0
  bool allow_unstable_dt = false;
};

// A wall's new motion or load from a stage's start (neither: it stops where it is).
struct WallChange {
  int wall = 0;                            // index in Scene::walls
  std::optional<PrescribedMotion> motion;  // its time counts from the stage's start; it turns about the
                                           // wall's centre where the stage finds it
  std::optional<LoadControl> load;
};

// One stage of a staged run (the PDEM-EGD manual's fill, grow, bond, release; the BallastDEM
// manual's settle, then load): how long it runs, what may end it early, and what changes at its
// first step. Each stage keeps what the one before had, except what it changes.
struct Stage {
  std::string name;
  double duration = 0;  // s, its longest length; or
  std::int64_t steps = 0;
  // Ends it early once min_duration has passed (< 0: a tenth of its length): the particles' kinetic
  // energy below until_kinetic_energy (J; 0: no such end), or the particles' force on wall
  // until_wall (-1: none) at least until_wall_force (N).
  double until_kinetic_energy = 0;
  int until_wall = -1;
  double until_wall_force = 0;
  double min_duration = -1;
  std::optional<Vec3> gravity;
  std::optional<double> local_damping;
  std::optional<std::vector<Interaction>> interactions;  // the whole table from this stage on
  std::vector<WallChange> wall_changes;
  bool glue_bonds = false;   // Scene::bonds between the particles touching at its start (none at t = 0 then)
  double growth_factor = 1;  // the radii grow by this over the stage, linearly in time (the PDEM-EGD manual's GROWTH)
  bool ends_early() const { return until_kinetic_energy > 0 || until_wall >= 0; }
};

struct Scene {
  std::string name;
  std::vector<Material> materials;
  std::vector<Interaction> interactions;  // materials.size()^2, symmetric, index a * n + b
  ContactSettings contact;
  std::vector<ParticleInit> particles;
  std::vector<ClumpInit> clumps;
  std::vector<WallInit> walls;
  Vec3 gravity = Vec3::Zero();
  TimeSettings time;
  OutputSettings outputs;
  std::optional<Box> domain;
  NumericsSettings numerics;
  std::optional<BondSettings> bonds;
  // Radius growth (the PDEM-EGD manual's GROWTH and NGROWTH): every radius grows uniformly from its given
  // size to `factor` times it over the first `steps` steps, packing a loose assembly (a solid
  // fraction cc grows to cc factor^3); masses follow, densities stay.
  struct Growth {
    double factor = 1;
    std::int64_t steps = 0;
  };
  std::optional<Growth> growth;
  // A staged run: the stages one after another (none: one run of `time`'s length).
  std::vector<Stage> stages;
  // Particles entering during the run (none: the particles are those given, from start to end).
  std::vector<ParticleSource> sources;
  // A 2D run (the legacy viewers' 2D data): discs of this thickness (m) in the x-z plane (y = 0), moving in it
  // and turning about y; the contact and bond laws are the engine's own, between the discs' centres in the
  // plane. Absent: a 3D run of spheres.
  struct Plane {
    double thickness = 1;
  };
  std::optional<Plane> plane;

  Grain grain() const { return Grain{plane ? plane->thickness : 0}; }

  // The stage that glues the bonds (Stage::glue_bonds; at most one), or -1: none does.
  int bonding_stage() const {
    for (std::size_t k = 0; k < stages.size(); ++k)
      if (stages[k].glue_bonds) return static_cast<int>(k);
    return -1;
  }

  const Interaction& interaction(int a, int b) const {
    return interactions[static_cast<size_t>(a) * materials.size() + b];
  }
};

}  // namespace dem
