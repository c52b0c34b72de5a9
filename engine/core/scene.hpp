// The typed, checked description of a simulation, in SI units. Front ends (the spec loader, later the
// legacy INPT importer) build it; the engine only reads it.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/vec.hpp"

namespace dem {

enum class NormalModel { Linear, Hertz };
enum class RollingModel { None, Cdt, Epsd };

struct Material {
  std::string name;
  double density = 0;           // kg/m^3
  double youngs_modulus = 0;    // Pa
  double poisson_ratio = 0;
  double normal_stiffness = 0;  // N/m, linear model
  bool rigid = false;           // infinitely stiff: contributes nothing to the compliance
};

struct Interaction {
  double restitution = 1;
  double friction = 0;
  double rolling_friction = 0;
};

struct ContactSettings {
  NormalModel normal = NormalModel::Linear;
  RollingModel rolling = RollingModel::None;
  bool no_tensile_force = false;
  double tangential_stiffness_ratio = 0.5;  // the seeds' rns
  double tangential_damping_ratio = 0.0;    // the seeds' rzs
  double rolling_damping_ratio = 0.3;       // eta_r of Ai et al. (2011)
};

struct ParticleInit {
  Vec3 position = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();
  double radius = 0;
  int material = 0;
  bool fixed = false;
};

struct PlaneShape {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  // unit, points to the particles' side
};

struct PlateShape {
  std::array<Vec3, 4> corners;  // planar, in order around the edge
};

struct WallInit {
  std::string name;
  int material = 0;
  std::variant<PlaneShape, PlateShape> shape;
};

struct Box {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
};

enum class FileNumberFormat { Scientific, LegacyFixed };

struct OutputSettings {
  std::int64_t every_steps = 0;  // 0: only the first and last frame (unless interval_seconds)
  double interval_seconds = 0;   // turned into every_steps once the time step is known
  bool animation = true;
  bool force_chains = false;
  double length_unit = 1.0;      // metres per file length unit (1e-3 for mm)
  std::string length_unit_name = "m";
  FileNumberFormat number_format = FileNumberFormat::Scientific;
};

struct NumericsSettings {
  double skin_fraction = 0.1;       // of the mean diameter
  int search_interval = 0;          // 0: rebuild only when needed
  int threads = 0;                  // 0: all cores
  double max_overlap_fraction = 0.25;
  int check_interval = 100;
  int reorder_interval = 10;
};

struct TimeSettings {
  double dt = 0;                    // 0: automatic
  double dt_fraction = 1.0 / 50.0;  // of the shortest contact time (the seeds' 1/50)
  double duration = 0;
  std::int64_t steps = 0;           // derived from duration when 0
  bool allow_unstable_dt = false;
};

struct Scene {
  std::string name;
  std::vector<Material> materials;
  std::vector<Interaction> interactions;  // materials.size()^2, symmetric, index a * n + b
  ContactSettings contact;
  std::vector<ParticleInit> particles;
  std::vector<WallInit> walls;
  Vec3 gravity = Vec3::Zero();
  TimeSettings time;
  OutputSettings outputs;
  std::optional<Box> domain;
  NumericsSettings numerics;

  const Interaction& interaction(int a, int b) const {
    return interactions[static_cast<size_t>(a) * materials.size() + b];
  }
};

}  // namespace dem
