// `tidalcrust relax`
#include <fmt/format.h>

#include <filesystem>

#include "io/checkpoint_file.hpp"
#include "cli/cli_options.hpp"
#include "cli/commands.hpp"
#include "base/errors.hpp"
#include "stages/relax_stage.hpp"
#include "stages/time_step.hpp"
#include "cli/stage_command.hpp"
#include "stages/gravity_kernel_check.hpp"

namespace tidalcrust {

int command_relax(int argc, char** argv) {
  cxxopts::Options options("tidalcrust relax", "Damped relaxation and stability probe (paper section 2.8).");
  auto in = read_stage_input(options, argc, argv,
                             "input stretch checkpoint (or a mid-stage relax checkpoint to resume)", true,
                             {"stretch", "relax"}, "relax");
  if (!in) return exit_ok;
  auto& [parsed, common, from, out, input] = *in;
  const bool resuming = std::holds_alternative<RelaxRecord>(input.stage.record);
  if (resuming && input.stage.complete)
    throw InputError(fmt::format("{}: relaxation is already complete", from.string()));
  Config config = stage_config(input, from, common, resuming);
  if (!resuming) {  // dt checked against (or chosen from) the stretched body's stability bound
    const std::string note = settle_time_step(config, input, from.string());
    if (!note.empty()) fmt::print(stderr, "tidalcrust: {}\n", note);
  }
  apply_thread_count(common.threads);
  Checkpoint checkpoint = resuming ? std::move(input) : begin_relax(input, config);
  continue_under_gravity_kernel(checkpoint, config, common.kernel.allow_change, from.string());
  const StageLock lock = lock_output(out, from, resuming);
  StepLoopOptions loop = loop_options_for(parsed, out, "relax", config.relax.checkpoint_interval);
  return finish_stage(run_relax(checkpoint, config, loop), checkpoint, out, loop);
}

}  // namespace tidalcrust
