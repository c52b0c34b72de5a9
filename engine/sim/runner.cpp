#include "sim/runner.hpp"

#include <chrono>

#include "core/errors.hpp"
#include "sim/stability_guard.hpp"

namespace dem {

RunOutcome run(Simulation& sim, const std::vector<Observer*>& observers, const RunOptions& options) {
  using Clock = std::chrono::steady_clock;
  RunOutcome outcome;
  const std::int64_t every = sim.scene().outputs.every_steps;
  const int check_every = std::max(1, sim.scene().numerics.check_interval);
  const StabilityGuard guard(sim);
  std::vector<Observer*> step_observers;
  for (Observer* o : observers)
    if (o->wants_steps()) step_observers.push_back(o);
  auto frame = [&] {
    guard.check_writable(sim);  // nothing non-finite is ever written
    for (Observer* o : observers) o->frame(sim);
  };
  PhaseProfile* const profile = sim.profile();
  const auto start = Clock::now();
  auto last_report = start;
  std::int64_t steps_at_report = sim.step_count();
  try {
    {
      const PhaseTimer timer(profile, Phase::guard);
      guard.check(sim);
    }
    const bool staged = !sim.scene().stages.empty();
    if (sim.step_count() == 0) {  // a continued run's first frame is its saved state's last
      const PhaseTimer timer(profile, Phase::outputs);
      frame();
      if (options.after_step) options.after_step(sim, true);
    }
    // a stage that ends early makes the run shorter: the total is asked anew before every step
    while (sim.step_count() < sim.total_steps()) {
      if (options.cancel && options.cancel->load(std::memory_order_relaxed)) {
        outcome.cancelled = true;
        outcome.ok = false;
        outcome.error = "cancelled";
        break;
      }
      sim.update_stage();
      const std::int64_t next = sim.step_count() + 1, total = sim.total_steps();
      // every stage's last step is a frame too: the packing filled, grown, settled
      const bool frame_due =
          (every > 0 && next % every == 0) || next == total || (staged && next == sim.stage_end_step());
      sim.record_contacts(frame_due);
      sim.step();
      const std::int64_t s = sim.step_count();
      if (profile) {  // counted before the guard, which may stop the run at this step
        ++profile->steps;
        profile->particle_steps += static_cast<std::int64_t>(sim.particles().size());
      }
      {
        const PhaseTimer timer(profile, Phase::guard);
        guard.check_finite(sim);
        if (s % check_every == 0 || s == total || sim.deep_overlap()) guard.check(sim);
      }
      {
        const PhaseTimer timer(step_observers.empty() && !frame_due && !options.after_step ? nullptr : profile,
                               Phase::outputs);
        for (Observer* o : step_observers) o->step(sim);
        if (frame_due) frame();
        if (options.after_step) options.after_step(sim, frame_due);
      }
      if (options.on_progress || options.periodically) {
        const auto now = Clock::now();
        const double since = std::chrono::duration<double>(now - last_report).count();
        if (since >= options.progress_seconds || s == total) {
          const double rate = static_cast<double>(s - steps_at_report) / std::max(since, 1e-9);
          if (options.on_progress)
            options.on_progress(
                {s, total, rate, rate > 0 ? static_cast<double>(total - s) / rate : 0, sim.stage_name()});
          if (options.periodically) {
            const PhaseTimer timer(profile, Phase::outputs);
            guard.check_writable(sim);  // the server saves a checkpoint here
            options.periodically(sim);
          }
          last_report = now;
          steps_at_report = s;
        }
      }
    }
  } catch (const InstabilityError& e) {
    outcome.ok = false;
    outcome.error = e.what();
  }
  outcome.steps = sim.step_count();
  outcome.loop_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (profile) profile->close(outcome.loop_seconds);
  for (Observer* o : observers) o->finish(sim, outcome);
  return outcome;
}

}  // namespace dem
