#include "stages/step_loop.hpp"

#include <fmt/format.h>

#include <cmath>

#include "base/errors.hpp"
#include "io/progress.hpp"
#include "io/stop_signal.hpp"
#include "io/test_points.hpp"
#include "io/checkpoint_names.hpp"
#include "io/checkpoint_file.hpp"

namespace tidalcrust {

std::int64_t steps_for_duration(double duration, double dt) {
  return static_cast<std::int64_t>(std::llround(duration / dt));
}

StepLoopOptions stage_loop_options(const std::filesystem::path& final_file, std::string label,
                                   std::int64_t checkpoint_interval) {
  StepLoopOptions loop;
  loop.label = std::move(label);
  loop.mid_checkpoint = sibling_checkpoint(final_file, "mid");
  loop.diagnostic_checkpoint = sibling_checkpoint(final_file, "diagnostic");
  loop.checkpoint_interval = checkpoint_interval;
  return loop;
}

LoopOutcome run_step_loop(Checkpoint& checkpoint, const std::function<void(State&)>& advance,
                          const std::function<void(Checkpoint&)>& after_step, const StepLoopOptions& options) {
  State& state = checkpoint.state;
  const std::int64_t end = checkpoint.stage.end_step;
  std::optional<ProgressReporter> progress;
  if (!options.quiet) progress.emplace(options.label, checkpoint.stage.clock.start_step, state.step, end, options.status_file);
  install_stop_handlers();

  auto write_mid = [&] {
    if (options.mid_checkpoint.empty()) return;
    checkpoint.stage.complete = false;
    write_checkpoint(options.mid_checkpoint, checkpoint);
  };

  while (state.step < end) {
    try {
      advance(state);
      after_step(checkpoint);
    } catch (const SimulationError& err) {
      std::string where;
      if (!options.diagnostic_checkpoint.empty()) {
        checkpoint.stage.complete = false;
        checkpoint.stage.diagnostic = err.what();
        write_checkpoint(options.diagnostic_checkpoint, checkpoint);
        where = fmt::format(" (diagnostic checkpoint: {})", options.diagnostic_checkpoint.string());
      }
      if (progress) progress->finish(state.step, "failed");
      throw SimulationError(std::string(err.what()) + where);
    }
    if (progress) progress->update(state.step);
    test_point_after_step();  // testing aid: kill or hold here when the environment asks
    const bool stop = stop_requested() || state.step == options.stop_after_step;
    if (stop && state.step < end) {
      write_mid();
      if (progress) progress->finish(state.step, "interrupted");
      return LoopOutcome::interrupted;
    }
    const std::int64_t done = state.step - checkpoint.stage.clock.start_step;
    if (options.checkpoint_interval > 0 && done % options.checkpoint_interval == 0 && state.step < end) write_mid();
  }
  checkpoint.stage.complete = true;
  if (progress) progress->finish(state.step);
  return LoopOutcome::finished;
}

}  // namespace tidalcrust
