#pragma once
// Stage 3 (paper section 2.8): damped relaxation without perturber (gamma = 50, T = 3, no
// failures) during which shell rest lengths move toward their current lengths and hinge rest
// angles are reset on step schedules; then the stability probe (encounter damping, failures
// on, no perturber) whose results are stored in the relaxed checkpoint.
#include "model/checkpoint.hpp"
#include "model/config.hpp"
#include "stages/step_loop.hpp"

namespace tidalcrust {

/// A fresh "relax" checkpoint (incomplete, at its first step) from a complete "stretch"
/// checkpoint; InputError for any other input.
Checkpoint begin_relax(const Checkpoint& stretched, const Config& config);

/// Runs (or resumes) the relaxation in place until it is complete, then the stability probe.
/// `checkpoint` is what begin_relax returned or a mid-stage "relax" checkpoint (InputError if
/// `config` differs from its stored configuration). Creep phase (shell rest-length creep,
/// hinge resets), exact crust reset at creep_end_step, settle phase (relax.settle_duration).
/// Fills the RelaxRecord (model/stage_records.hpp): the relaxed body's strains, kinetic energy
/// and radius, and the stability probe's failures at eps_S and at 0.002 and every encounter
/// override. `relaxed` is set once the relaxation is done: a mid-stage checkpoint with it set
/// resumes with the probe alone.
LoopOutcome run_relax(Checkpoint& checkpoint, const Config& config, const StepLoopOptions& options);

}  // namespace tidalcrust
