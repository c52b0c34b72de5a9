// Where a run's time goes, phase by phase (`dem run --profile`): wall-clock seconds per phase of
// the step, summed over the run. Off unless asked for: a run without a profile pays one pointer
// test per phase.
#pragma once

#include <algorithm>
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

// The cost of one read of the profile's clock, s (measured once per process).
double clock_read_seconds();

// What the threads measured inside one gather (the second half kick, with the walls' and meshes'
// contacts per particle): their seconds in their ranges, in walls and in meshes, and how many walls'
// and meshes' intervals they timed (each costs two clock reads, which the profile takes back out).
struct GatherTimes {
  double range = 0, walls = 0, meshes = 0;
  std::int64_t wall_intervals = 0, mesh_intervals = 0;
};

struct PhaseProfile {
  using Clock = std::chrono::steady_clock;
  std::array<double, kPhaseCount> seconds{};
  double loop_seconds = 0;  // the whole loop (runner), which `other` completes
  std::int64_t steps = 0;
  std::int64_t particle_steps = 0;  // sum over the steps of the particles then
  // a timed interval holds about one clock read, which is the timer's, not the phase's (the rest of
  // the reads are left to `other`)
  double clock_read = clock_read_seconds();
  std::int64_t gathers = 0;
  double unsampled_gather = 0;                   // s, of the gathers not timed inside
  double sampled_walls = 0, sampled_meshes = 0;  // s, in the sampled gathers
  double sampled_kick = 0;

  void add(Phase phase, double s) { seconds[static_cast<int>(phase)] += s; }
  // The gathers: one in kGatherSample is timed inside (its walls and meshes per particle), the first
  // among them; the others' time is shared as theirs was, at close().
  static constexpr int kGatherSample = 16;
  bool sample_gather() { return gathers++ % kGatherSample == 0; }
  // A sampled gather of `elapsed` wall-clock seconds: shared among walls, meshes and kick as the
  // threads' own times are, less the clock reads (left to `other`).
  void add_gather(double elapsed, const GatherTimes& times);
  void add_unsampled_gather(double elapsed) { unsampled_gather += elapsed; }
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
    if (profile_) {
      const double elapsed = std::chrono::duration<double>(PhaseProfile::Clock::now() - start_).count();
      profile_->add(phase_, std::max(0.0, elapsed - profile_->clock_read));
    }
  }
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;

 private:
  PhaseProfile* profile_;
  Phase phase_;
  PhaseProfile::Clock::time_point start_;
};

}  // namespace dem
