#include "stages/stability_probe.hpp"

#include <algorithm>

#include "forces/force_field.hpp"
#include "integrate/leapfrog.hpp"
#include "physics/shell_failure.hpp"

namespace tidalcrust {

ProbeResult run_stability_probe(const Checkpoint& relaxed, const Config& config, double failure_strain,
                                const StepLoopOptions& options) {
  Checkpoint probe = relaxed;
  probe.state.perturber = Perturber{};
  probe.observables = Observables{};
  const std::int64_t first = probe.state.step;
  probe.stage.clock = StepClock{probe.state.time, first, relaxed.stage.clock.dt};
  probe.stage.end_step = first + steps_for_duration(config.relax.probe_duration, probe.stage.clock.dt);

  ForceField forces(probe.body, force_options(config, config.relax.probe_damping));
  Leapfrog leapfrog(forces, probe.stage.clock);
  ProbeResult result;
  result.max_shell_tension = max_shell_tension(probe.body, probe.state);
  const FailureRule rule = make_failure_rule(config, std::nullopt, probe.body, probe.state, probe.stage.clock.dt);
  const FailureThreshold threshold{failure_strain, config.shell.failed_stiffness_factor};
  auto after_step = [&](Checkpoint& c) {
    result.max_shell_tension = std::max(result.max_shell_tension, max_shell_tension(c.body, c.state));
    result.failures += static_cast<std::int64_t>(apply_failure_rule(rule, threshold, c.body, c.state, first, c.observables.failures));
  };
  StepLoopOptions probe_options = options;
  probe_options.label = options.label.empty() ? "stability probe" : options.label + " stability probe";
  probe_options.mid_checkpoint.clear();
  probe_options.checkpoint_interval = 0;
  result.interrupted =
      run_step_loop(probe, [&](State& s) { leapfrog.step(s); }, after_step, probe_options) == LoopOutcome::interrupted;
  return result;
}

}  // namespace tidalcrust
