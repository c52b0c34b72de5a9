// The spec loader, one section of the schema (proto/dem.proto) per file: each reads its part of the
// JobSpec into the Scene and reports every problem to the Checker. to_scene (spec_loader.cpp) calls
// them in the order below; what a field stands for when left out is in spec/defaults.hpp.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "core/scene.hpp"
#include "dem.pb.h"
#include "spec/checker.hpp"

namespace dem::spec {

// What the sections share while one spec is loaded.
struct SpecContext {
  SpecContext(Checker& c, std::string dir, Scene& s) : check(c), base_dir(std::move(dir)), scene(s) {}

  Checker& check;
  std::string base_dir;  // mesh and template files are read relative to it
  Scene& scene;
  std::map<std::string, int> material_index;
  std::set<int> particle_materials, wall_materials;  // every pair of them needs an interaction
  std::vector<char> interaction_given;               // per pair of materials, a * n + b

  // The material's index, or -1 (reported at `path`) when there is none of that name.
  int material(const std::string& name, const std::string& path);
  // The same for a particle's material, which must not be rigid.
  int particle_material(const std::string& name, const std::string& path);
};

// materials_section.cpp: the contact models, the materials and their interactions.
void load_materials(const api::JobSpec& spec, SpecContext& ctx);
// One interaction's coefficients and the pair it is for (nullopt: reported).
struct PairInteraction {
  int a = 0, b = 0;
  Interaction value;
};
std::optional<PairInteraction> load_interaction(const api::Interaction& in, const std::string& path, SpecContext& ctx);
// Every pair of materials that can meet has its interaction (after the walls, stages included).
void check_interactions_complete(SpecContext& ctx);

// plane_section.cpp: a 2D run (JobSpec.dimension, .discThickness), read before the particles are made;
// check_plane, after every other section, refuses what would leave the plane, naming the field.
void load_plane(const api::JobSpec& spec, SpecContext& ctx);
void check_plane(const api::JobSpec& spec, SpecContext& ctx);

// particles_section.cpp: listed particles, lattices, packings; then clumps_section.cpp's clumps and stones.
void load_particles(const api::JobSpec& spec, SpecContext& ctx);
void load_clumps(const api::JobSpec& spec, SpecContext& ctx);
void load_stones(const api::JobSpec& spec, SpecContext& ctx);
// Diameters (the manuals' IPATTERN), checked at `path`.
SizeDistribution load_sizes(const api::SizeDistribution& in, const std::string& path, Checker& check);

// walls_section.cpp: planes, plates and meshes, with their motions and loads.
void load_walls(const api::JobSpec& spec, SpecContext& ctx);
WallInit load_wall(const api::Wall& in, const std::string& path, const std::string& default_name, SpecContext& ctx);
PrescribedMotion load_motion(const api::Motion& in, const std::string& path, Checker& check);
LoadControl load_control(const api::Load& in, const std::string& path, Checker& check);
// A mesh read and placed (nullopt: reported).
std::optional<MeshShape> load_mesh(const api::Mesh& in, const std::string& path, SpecContext& ctx);
Eigen::Matrix3d rotation(const api::Vec3& axis, double degrees, const std::string& path, Checker& check);

// bonds_section.cpp: the bonds' model and strengths, and radius growth.
void load_bonds(const api::JobSpec& spec, SpecContext& ctx);
void load_growth(const api::JobSpec& spec, SpecContext& ctx);

// run_section.cpp: gravity, time stepping, outputs, domain, numerics.
void load_run_settings(const api::JobSpec& spec, SpecContext& ctx);

// stages_section.cpp: a staged run's stages (after everything above: they name walls and materials).
void load_stages(const api::JobSpec& spec, SpecContext& ctx);

// sources_section.cpp: particles entering during the run (after the stages and walls they name).
void load_sources(const api::JobSpec& spec, SpecContext& ctx);

}  // namespace dem::spec
