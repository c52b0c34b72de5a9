#include "sim/phase_profile.hpp"

#include <algorithm>
#include <cstdio>

namespace dem {

const char* phase_name(Phase phase) {
  switch (phase) {
    case Phase::drift:
      return "drift";
    case Phase::clumps:
      return "clumps";
    case Phase::growth:
      return "growth";
    case Phase::sources:
      return "sources";
    case Phase::sort:
      return "sort";
    case Phase::rebuild:
      return "rebuild";
    case Phase::pairs:
      return "pairs";
    case Phase::bonds:
      return "bonds";
    case Phase::walls:
      return "walls";
    case Phase::meshes:
      return "meshes";
    case Phase::kick:
      return "kick";
    case Phase::wall_motion:
      return "wall motion";
    case Phase::guard:
      return "guard";
    case Phase::outputs:
      return "outputs";
    case Phase::other:
      return "other";
  }
  return "?";
}

// The least of 20 batches of 100 reads (a vDSO call of some tens of nanoseconds): per particle
// against a wall, two reads were a third of the dense scene's "walls" before they were taken out.
double clock_read_seconds() {
  static const double cost = [] {
    double best = 1;
    for (int batch = 0; batch < 20; ++batch) {
      const auto start = PhaseProfile::Clock::now();
      for (int k = 0; k < 100; ++k) (void)PhaseProfile::Clock::now();
      best = std::min(best, std::chrono::duration<double>(PhaseProfile::Clock::now() - start).count() / 101);
    }
    return best;
  }();
  return cost;
}

void PhaseProfile::add_gather(double elapsed, const GatherTimes& times) {
  const double read = clock_read;
  // an interval holds about one read (the end of its first and the start of its second)
  const double walls = std::max(0.0, times.walls - read * static_cast<double>(times.wall_intervals));
  const double meshes = std::max(0.0, times.meshes - read * static_cast<double>(times.mesh_intervals));
  const double reads = 2 * read * static_cast<double>(times.wall_intervals + times.mesh_intervals);
  const double share = times.range > 0 ? elapsed / times.range : 0;
  const double kick = std::max(0.0, elapsed - (walls + meshes + reads) * share);
  sampled_walls += walls * share;
  sampled_meshes += meshes * share;
  sampled_kick += kick;
  add(Phase::walls, walls * share);
  add(Phase::meshes, meshes * share);
  add(Phase::kick, kick);
}

void PhaseProfile::close(double loop) {
  loop_seconds = loop;
  const double sampled = sampled_walls + sampled_meshes + sampled_kick;
  if (sampled > 0) {
    add(Phase::walls, unsampled_gather * sampled_walls / sampled);
    add(Phase::meshes, unsampled_gather * sampled_meshes / sampled);
    add(Phase::kick, unsampled_gather * sampled_kick / sampled);
  } else {
    add(Phase::kick, unsampled_gather);
  }
  unsampled_gather = 0;
  double timed = 0;
  for (int k = 0; k < kPhaseCount - 1; ++k) timed += seconds[k];
  seconds[static_cast<int>(Phase::other)] = std::max(0.0, loop - timed);
}

std::string PhaseProfile::table() const {
  std::string out = "profile:  phase         seconds   share   us/step  ns/particle-step\n";
  char line[160];
  const double per_step = steps > 0 ? 1e6 / static_cast<double>(steps) : 0;
  const double per_particle_step = particle_steps > 0 ? 1e9 / static_cast<double>(particle_steps) : 0;
  auto row = [&](const char* name, double s) {
    std::snprintf(line, sizeof line, "profile:  %-12s %9.3f  %5.1f%%  %8.3f  %16.2f\n", name, s,
                  loop_seconds > 0 ? 100 * s / loop_seconds : 0.0, s * per_step, s * per_particle_step);
    out += line;
  };
  for (int k = 0; k < kPhaseCount; ++k) row(phase_name(static_cast<Phase>(k)), seconds[k]);
  row("total", loop_seconds);
  return out;
}

}  // namespace dem
