// A running simulation: the state, the time stepping, and read access for observers.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/scene.hpp"
#include "sim/force_kernel.hpp"
#include "sim/state.hpp"
#include "sim/time_step.hpp"

namespace dem {

struct PairContact {
  int i;      // particle index (not id)
  int j;
  double fn;  // normal force, N
  double ft;  // tangential force magnitude, N
};

class Simulation {
 public:
  // Builds the state from a checked scene; throws SceneError for what cannot run (e.g. dt too large).
  explicit Simulation(Scene scene);

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

  // Per-contact forces (pair_contacts, contact_counts) are kept only for steps that ask for them:
  // on by default; a runner turns it on just before the steps whose frames it writes.
  void record_contacts(bool on) { state_.record_contacts = on; }
  bool contacts_recorded() const { return contacts_recorded_; }

  double kinetic_energy() const;        // translational + rotational, J
  double gravitational_energy() const;  // -sum m g.x, J
  ContactSummary contact_summary() const { return kernel_->summarize(state_); }
  // Both throw std::logic_error when the last step did not record contacts.
  std::vector<int> contact_counts() const;  // per particle index: touching pairs and walls
  std::vector<PairContact> pair_contacts() const;

 private:
  double half_kick_and_drift();  // returns the largest squared displacement since the last build
  void build_neighbors();
  void build_wall_contacts(const WallContacts& previous, const std::vector<int>& new_to_old);
  void plan_blocks();

  Scene scene_;
  SimState state_;
  TimeStepReport time_step_;
  std::unique_ptr<ForceKernel> kernel_;
  std::vector<Vec3> x_at_build_;
  double skin_ = 0;
  std::int64_t step_ = 0;
  std::int64_t total_steps_ = 0;
  int builds_ = 0;
  bool contacts_recorded_ = true;
  std::int64_t last_build_step_ = 0;
};

}  // namespace dem
