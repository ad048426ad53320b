#pragma once
// Stage 4 (paper sections 2.6, 2.9): a point-mass perturber on the two-body orbit with
// pericenter q and speed V_q passes the body; every t_fail steps the most strained shell
// spring beyond eps_S fails (k -> F_Sk k). Many encounters branch from one relaxed body.
#include <filesystem>

#include "model/checkpoint.hpp"
#include "model/config.hpp"
#include "stages/step_loop.hpp"

namespace tidalcrust {

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
