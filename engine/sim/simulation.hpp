// A running simulation: the state, the time stepping, and read access for observers.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/scene.hpp"
#include "sim/force_kernel.hpp"
#include "sim/kernel_select.hpp"
#include "sim/particle_sources.hpp"
#include "sim/state.hpp"
#include "sim/time_step.hpp"
#include "walls/boundaries.hpp"

namespace dem {

// A particle touching a wall, for the wall force-chain file.
struct WallContact {
  int i;      // particle index (not id)
  int wall;   // index in Scene::walls
  double fn;  // normal force, N
  double ft;  // tangential force magnitude, N
};

struct PairContact {
  int i;  // particle index (not id)
  int j;
  double fn;  // normal force, N
  double ft;  // tangential force magnitude, N
};

// Where a run first stopped being finite: the step and time, and the particle (its scene id) with
// the lowest id among those that went bad in that step.
struct NonFinite {
  std::int64_t step = 0;
  double time = 0;
  int particle_id = 0;
  int particles = 0;  // how many went bad in that step
};

// Where a particle first moved so far in one step that it could pass through another, or past a
// contact's overlap limit, between two force evaluations: farther than half the overlap limit
// (numerics.maxOverlapFraction) times its radius.
struct TooFast {
  std::int64_t step = 0;
  double time = 0;
  int particle_id = 0;
  double distance = 0;  // moved in that step, m
  double radius = 0;    // the particle's; for a wall, the smallest particle's
  int wall = -1;        // a wall (its index in Scene::walls) that moved so far, instead of a particle
};

// The work done on the particles since the start by what feeds energy in, J: moving and loaded
// walls, constant external forces, radius growth, and the changes at a stage's start (larger overlaps, and masses and
// weights that grow at their speeds and heights). The mechanical energy minus this work, against its start, is what
// damping, friction and integration took out (or put in).
struct EnergyLedger {
  double walls = 0;
  double external = 0;
  double growth = 0;
  double stages = 0;   // what a stage's changes (gravity, friction, walls gone) did to the mechanical energy
  double sources = 0;  // the kinetic and gravitational energy of the particles the sources inserted
  double total() const { return walls + external + growth + stages + sources; }
  double magnitude = 0;       // sum of the sizes of every step's contributions (for the guard's slack)
  double initial_energy = 0;  // the mechanical energy at t = 0 (kinetic, elastic, gravitational)
};

class Simulation {
 public:
  // Builds the state from a checked scene; throws SceneError for what cannot run (e.g. dt too large).
  // `select` makes the force loop of the scene's contact models (the engine's own by default).
  explicit Simulation(Scene scene, KernelSelector select = select_kernel);

  // One velocity-Verlet step: half kick, drift, (re)build neighbours if needed, forces, half kick.
  void step();

  const Scene& scene() const { return scene_; }
  const SimState& state() const { return state_; }
  const Particles& particles() const { return state_.particles; }
  const TimeStepReport& time_step() const { return time_step_; }
  double dt() const { return state_.dt; }
  double time() const { return static_cast<double>(step_) * state_.dt; }
  std::int64_t step_count() const { return step_; }
  std::int64_t total_steps() const { return total_steps_; }
  int neighbor_builds() const { return builds_; }
  double skin() const { return skin_; }

  // Where the steps add each phase's time (`dem run --profile`; the runner adds the guard's and the
  // outputs'), or nullptr for none, the default. The profile must outlive the steps it times.
  void set_profile(PhaseProfile* profile) { state_.profile = profile; }
  PhaseProfile* profile() const { return state_.profile; }

  // Per-contact forces (pair_contacts, contact_counts) are kept only for steps that ask for them:
  // on by default; a runner turns it on just before the steps whose frames it writes.
  void record_contacts(bool on) { state_.record_contacts = on; }
  bool contacts_recorded() const { return contacts_recorded_; }

  // A staged run (Scene::stages; a run without stages is one stage, 0): the stage the last step
  // belonged to, where it started and where it ends (moved earlier when its end condition holds).
  int stage() const { return stage_; }
  std::int64_t stage_start_step() const { return stage_start_step_; }
  std::int64_t stage_end_step() const { return stage_end_step_; }
  const std::string& stage_name() const;  // "" without stages
  // Enters the next stage when this one is over, and makes the coming step this stage's last when
  // its end condition holds now. step() calls it first; a runner calls it before it decides
  // whether the coming step is a frame (the last step of a run is one).
  void update_stage();
  // Whether scene wall k is there in this stage (a stage may add or remove walls).
  bool wall_present(int k) const { return boundaries_.present(k); }
  // Whether scene wall k may move, come or go at some point of the run (its own motion or load, a
  // stage's change, a stage adding or removing it): outputs draw such a wall in every frame.
  bool wall_varies(int k) const { return boundaries_.varies(k); }
  bool any_wall_varies() const { return boundaries_.any_varies(); }

  double kinetic_energy() const;        // translational + rotational, J
  double rotational_energy() const;     // the rotational part, J
  double translational_energy() const;  // the translational part, J, summed on its own
  double gravitational_energy() const;  // -sum m g.x, J
  // Particle i's kinetic energy as a free sphere (a clump member's by its own motion), J.
  double particle_kinetic_energy(std::size_t i) const;
  const EnergyLedger& energy_input() const { return ledger_; }
  // Kinetic, gravitational, and elastic energy of the contacts and the bonds, J.
  double mechanical_energy() const;
  // Of the moving bodies (free particles and clumps; held particles excluded): sum m v, and
  // sum x x m v + I w about the origin.
  Vec3 linear_momentum() const;
  Vec3 angular_momentum() const;
  ContactSummary contact_summary() const { return kernel_->summarize(state_); }
  // Both throw std::logic_error when the last step did not record contacts.
  std::vector<int> contact_counts() const;  // per particle index: touching pairs and walls
  std::vector<PairContact> pair_contacts() const;
  std::vector<WallContact> wall_contacts() const;  // touching ones, by particle then wall
  // Per particle index: its fragment (particles held together by intact bonds, a rigid clump's
  // members one piece among them), numbered from 1 by lowest id. Without bonds: a clump member's
  // clump number from 1, a free sphere 0.
  std::vector<int> fragments() const;
  const BondSet& bonds() const { return state_.bonds; }
  // Particles entering during the run (Scene::sources): the scene's own come first (ids below
  // given_particles()), each inserted one gets the next id.
  std::size_t given_particles() const { return given_particles_; }
  const std::vector<SourceProgress>& source_progress() const { return source_progress_; }

  // Per wall of the scene, updated every step.
  const std::vector<BoundaryLoad>& boundary_loads() const { return boundary_loads_; }
  const WallDriver& wall_driver(int wall) const { return boundaries_.driver(wall); }
  const Boundaries& boundaries() const { return boundaries_; }
  const std::vector<Wall>& walls() const { return state_.walls; }  // planes and plates
  const std::vector<MeshWall>& meshes() const { return state_.meshes; }
  // Index in walls() or meshes() of scene wall k (-1 when it is the other kind).
  int plane_index(int k) const { return boundaries_.plane_index(k); }
  int mesh_index(int k) const { return boundaries_.mesh_index(k); }
  int boundary_of_plane(int p) const { return boundaries_.of_plane(p); }  // scene wall of walls()[p]
  bool has_moving_walls() const { return boundaries_.any_moving(); }

  // Set by the first step that left a particle's position, velocity or spin non-finite (every step
  // is checked, at the cost of one comparison per particle).
  const std::optional<NonFinite>& first_non_finite() const { return first_non_finite_; }
  // Set by the first step in which a particle moved too far (TooFast; a comparison per particle).
  const std::optional<TooFast>& first_too_fast() const { return first_too_fast_; }
  // The last step had a contact past numerics.maxOverlapFraction (a comparison per contact).
  bool deep_overlap() const { return state_.deep_overlap.load(std::memory_order_relaxed); }

 private:
  friend class StateIO;  // saves and restores everything below (sim/state_io.hpp)

  double half_kick_and_drift();  // returns the largest squared displacement since the last build
  void add_wall_work(const std::vector<WallPose>& before, const std::vector<BoundaryLoad>& loads_before);
  void check_wall_moves(const std::vector<WallPose>& before);
  void refuse_coincident_particles() const;
  void refuse_positions_past_precision() const;
  void refuse_motion_off_the_plane() const;  // a 2D run (Scene::plane)
  void hold_in_plane();                      // a 2D run: after each force evaluation
  // The forces, the second half kick (state_.dt; 0: the forces alone), the plane's reaction and the bodies' kick.
  void compute_forces_and_kick();
  void add_work(double& account, double work);
  void build_neighbors();
  void build_wall_contacts(const WallContacts& previous, const std::vector<int>& new_to_old);
  void plan_blocks();
  void build_mesh_contacts(const std::vector<int>& new_to_old);
  void move_walls(double t_new, double dt);    // the walls' first half of the step
  void settle_walls(double t_new, double dt);  // loads from this step's forces, then their second half
  // The growth of this step (Scene::growth), given its work on the contacts at the step's start
  // positions; returns how much the largest radius grew since the last build.
  double grow(double contacts_work_at_start);
  bool growing() const;                     // this step grows the radii
  double grown_scale() const;               // the radii's scale after this step's growth
  std::vector<double> grown_radii() const;  // the radii after this step's growth
  // What this step's growth adds to the contacts' stored energy at the particles' positions now.
  double growth_energy_at_positions_now() const;
  // The contacts' reduced masses, radii and rolling inertias from the particles' radii and masses
  // now (they are computed at each build; growth changes them in between).
  void refresh_contact_constants();
  // Stages (Scene::stages).
  std::int64_t stage_steps(int k) const;  // its longest length in steps
  void enter_stage(int k);                // at its first step: its changes, glued bonds, forces anew
  // The settings stage k runs with (gravity, damping, friction, walls there, growth), from the
  // scene's and the changes of stages 0..k; with `restore`, also every wall's motion and load as
  // stage k has them (a saved state is read into a simulation made at step 0).
  void apply_stage_settings(int k, bool restore);
  bool stage_end_condition_holds() const;
  void recount_total_steps();
  void plan_stage_growth(int k);
  double growth_scale_at(std::int64_t step) const;  // the radii's scale the spec gives after `step` steps
  void restore_stage(int k, std::int64_t start, std::int64_t end, bool ended_early);  // StateIO
  void glue_bonds();
  void drop_slots_of_absent_meshes();
  // Sources (Scene::sources): inserts this step's due particles; true when it inserted any.
  bool feed_sources();
  bool source_active(int k) const;
  double source_active_time(int k) const;  // since the source's start, after this step
  // Adds one particle to the run (a source's, or one a saved state holds) with an empty history.
  void append_particle(const ParticleInit& init);

  Scene scene_;
  KernelSelector select_;
  SimState state_;
  TimeStepReport time_step_;
  std::unique_ptr<ForceKernel> kernel_;
  std::vector<Vec3> x_at_build_;
  std::vector<double> external_work_of_block_;  // the drift's, per particle block (half_kick_and_drift)
  double skin_ = 0;
  std::int64_t step_ = 0;
  std::int64_t total_steps_ = 0;
  int builds_ = 0;
  bool contacts_recorded_ = true;
  std::int64_t last_build_step_ = 0;
  Boundaries boundaries_;  // every scene wall, whatever its kind: its driver, where it is, whether it is there
  std::vector<BoundaryLoad> boundary_loads_;
  double largest_given_radius_ = 0;   // of the scene's particles (growth scales it)
  double smallest_given_radius_ = 0;  // of the scene's particles
  double growth_scale_ = 1;           // radii now over their given sizes (Scene::growth)
  double growth_at_build_ = 1;        // the same at the last build
  // The growth under way (Scene::growth, or a stage's): the scale goes from `from` to `to` over
  // `steps` steps from `start`.
  struct GrowthPlan {
    double from = 1, to = 1;
    std::int64_t start = 0, steps = 0;
  };
  std::optional<GrowthPlan> growth_plan_;
  int stage_ = 0;
  std::int64_t stage_start_step_ = 0;
  std::int64_t stage_end_step_ = 0;
  bool stage_ended_early_ = false;  // its end condition ended it (at stage_end_step_)
  std::optional<NonFinite> first_non_finite_;
  std::optional<TooFast> first_too_fast_;
  bool moved_too_far_ = false;  // set by the last drift
  EnergyLedger ledger_;
  std::size_t given_particles_ = 0;
  std::vector<SourceProgress> source_progress_;  // per source
  // per source: the index and radius of the next particle it would insert (not saved: drawn again)
  std::vector<std::pair<std::int64_t, double>> next_source_radius_;
};

}  // namespace dem
