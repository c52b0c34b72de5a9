// Where a run's time goes, phase by phase (`dem run --profile`): wall-clock seconds per phase of
// the step, summed over the run. Off unless asked for: a run without a profile pays one pointer
// test per phase.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <string>

namespace dem {

enum class Phase {
  drift,        // the first half kick and the drift of the particles
  clumps,       // the rigid clumps' drift and kick (their members follow their bodies)
  growth,       // radius growth (Scene::growth, a stage's)
  sources,      // the particle sources' insertions
  sort,         // the spatial reorder of the particles before a neighbour build
  rebuild,      // the neighbour list, its block plan, and the wall and mesh contacts' lists
  pairs,        // the force loop over the listed pairs
  bonds,        // the bonds' forces and breakage
  walls,        // the spheres' contacts with planes and plates
  meshes,       // the spheres' contacts with triangle meshes
  kick,         // the pairs' sums, gravity, damping and the second half kick
  wall_motion,  // moving and loaded walls: their motion, loads and work
  guard,        // the stability guard's checks
  outputs,      // the observers: frames, files, results, checkpoints
  other,        // the rest of the loop: stages, progress, the timer itself
};
inline constexpr int kPhaseCount = static_cast<int>(Phase::other) + 1;

const char* phase_name(Phase phase);

struct PhaseProfile {
  using Clock = std::chrono::steady_clock;
  std::array<double, kPhaseCount> seconds{};
  double loop_seconds = 0;  // the whole loop (runner), which `other` completes
  std::int64_t steps = 0;
  std::int64_t particle_steps = 0;  // sum over the steps of the particles then

  void add(Phase phase, double s) { seconds[static_cast<int>(phase)] += s; }
  // `other` = the loop's time that no phase took (set once the loop is over)
  void close(double loop);
  // A table: phase, seconds, share of the loop, microseconds per step, nanoseconds per particle-step
  std::string table() const;
};

// Adds the time from its making to its end to `phase` of `profile` (nothing when it is null).
class PhaseTimer {
 public:
  PhaseTimer(PhaseProfile* profile, Phase phase) : profile_(profile), phase_(phase) {
    if (profile_) start_ = PhaseProfile::Clock::now();
  }
  ~PhaseTimer() {
    if (profile_) profile_->add(phase_, std::chrono::duration<double>(PhaseProfile::Clock::now() - start_).count());
  }
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;

 private:
  PhaseProfile* profile_;
  Phase phase_;
  PhaseProfile::Clock::time_point start_;
};

}  // namespace dem
