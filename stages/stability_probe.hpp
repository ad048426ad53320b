#pragma once
// The stability check of paper section 2.8: the relaxed body, alone (no perturber), run at a
// low damping with the crust failure rule switched on. A well relaxed body loses no spring.
#include <cstdint>

#include "model/checkpoint.hpp"
#include "model/config.hpp"
#include "stages/step_loop.hpp"

namespace tidalcrust {

struct ProbeResult {
  std::int64_t failures = 0;       ///< shell springs that failed during the probe
  double max_shell_tension = 0;    ///< largest tensile shell strain at any step of the probe
  bool interrupted = false;        ///< stopped by SIGINT/SIGTERM (or options.stop_after_step)
};

/// Runs a COPY of `relaxed` for relax.probe_duration at damping relax.probe_damping (all
/// springs), no perturber, and every encounter.fail_interval steps (counted from the probe's
/// first step) applies fail_most_strained_shell_spring with eps_S = failure_strain and
/// F_Sk = shell.failed_stiffness_factor. `relaxed` is not changed. The probe is short and
/// deterministic, so it writes no mid-stage checkpoints: an interrupted probe is rerun whole.
ProbeResult run_stability_probe(const Checkpoint& relaxed, const Config& config, double failure_strain,
                                const StepLoopOptions& options);

}  // namespace tidalcrust
