#pragma once
// The loop every time-stepping stage (relax, stability probe, encounter) runs: advance one
// step, run the stage's per-step hook, write periodic mid-stage checkpoints, stop cleanly on
// SIGINT/SIGTERM, report progress. Everything the next step depends on is in the Checkpoint,
// so resuming from any checkpoint it writes continues bit for bit.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "model/checkpoint.hpp"

namespace tidalcrust {

struct StepLoopOptions {
  std::string label;                          ///< for progress lines, e.g. "encounter T5"
  std::filesystem::path mid_checkpoint;       ///< periodic/SIGINT checkpoint file ("" = none)
  std::int64_t checkpoint_interval = 0;       ///< steps between periodic checkpoints (0 = none)
  std::optional<std::filesystem::path> status_file;
  std::filesystem::path diagnostic_checkpoint;  ///< written on a numerical blow-up ("" = none)
  /// Testing aid: behave as if SIGINT arrived right after this global step (-1 = never).
  std::int64_t stop_after_step = -1;
  bool quiet = false;                         ///< no progress lines (tests)
};

enum class LoopOutcome { finished, interrupted };

/// Advances `checkpoint.state` from its current step to checkpoint.stage.end_step.
/// `advance` performs one integration step; `after_step` runs the stage's schedules (failures,
/// rest-length updates, sampling) with the state at the new step boundary.
/// On interruption the checkpoint is marked incomplete, written to mid_checkpoint, and
/// `interrupted` is returned. On SimulationError a diagnostic checkpoint is written and the
/// error is rethrown with its path in the message.
LoopOutcome run_step_loop(Checkpoint& checkpoint, const std::function<void(State&)>& advance,
                          const std::function<void(Checkpoint&)>& after_step, const StepLoopOptions& options);

/// The loop options of a stage whose final checkpoint is `final_file`: its mid-stage and
/// diagnostic checkpoints beside it (io/checkpoint_names.hpp), progress labelled `label`.
StepLoopOptions stage_loop_options(const std::filesystem::path& final_file, std::string label,
                                   std::int64_t checkpoint_interval);

/// Steps of a stage lasting `duration` (t_grav) at time step dt: a count, never a float compare.
std::int64_t steps_for_duration(double duration, double dt);

}  // namespace tidalcrust
