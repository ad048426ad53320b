#pragma once
// Stage 4 (paper sections 2.6, 2.9): a point-mass perturber on the two-body orbit with
// pericenter q and speed V_q passes the body; every t_fail steps the most strained shell
// spring beyond eps_S fails (k -> F_Sk k). Many encounters branch from one relaxed body.
#include <filesystem>

#include "model/checkpoint.hpp"
#include "model/config.hpp"
#include "stages/step_loop.hpp"

namespace tidalcrust {

/// Fewest time steps per pericenter passage time q/V_q, and in the whole encounter. The tide of
/// the perturber rises and falls within a few q/V_q around pericenter while the direction to it
/// turns by ~2 rad; the leapfrog follows the orbit with a phase error per step of about
/// (omega dt)^2 / 24 for omega = V_q/q and samples the tidal forcing once a step. With 20 steps
/// per q/V_q the turn per step is <= 0.05 rad, the phase error per step ~1e-4 and the forcing is
/// sampled smoothly; with fewer the perturber jumps past pericenter (below 1 step it is never
/// near it). The paper's encounters (paper-T.toml, quick.toml) have ~290 to ~580 steps per q/V_q.
inline constexpr double min_steps_per_pericenter_passage = 20;

/// InputError unless `spec` is valid (model/config validate) and resolved by
/// config.integrator.dt: q/V_q and the whole encounter (start_distance in to pericenter, out to
/// end_distance) span at least min_steps_per_pericenter_passage steps. The message names the
/// encounter and dt, after "<source>: " when `source` (the file that gives the encounter or the
/// time step: the workflow, the input checkpoint) is not empty. begin_encounter calls it; `run`,
/// `submit` and the `encounter` command call it for every encounter before writing anything.
void check_encounter(const Config& config, const Encounter& spec, const std::string& source = "");

/// A fresh "encounter" checkpoint from a complete "relax" or "encounter" checkpoint: places
/// the perturber and records the encounter, its failure rule and schedules in an EncounterRecord.
Checkpoint begin_encounter(const Checkpoint& parent, const Config& config, const Encounter& spec);

/// Runs (or resumes) the encounter in place until complete. `checkpoint` is what
/// begin_encounter returned or a mid-stage "encounter" checkpoint. `output` is the encounter's
/// final checkpoint file: the snapshot checkpoints are written beside it
/// (io/checkpoint_names.hpp); empty = no snapshot files.
LoopOutcome run_encounter(Checkpoint& checkpoint, const Config& config, const StepLoopOptions& options,
                          const std::filesystem::path& output = {});

}  // namespace tidalcrust
