// `tidalcrust stretch`
#include <fmt/format.h>

#include <filesystem>

#include "io/checkpoint_file.hpp"
#include "cli/cli_options.hpp"
#include "cli/commands.hpp"
#include "base/errors.hpp"
#include "cli/stage_command.hpp"
#include "stages/stretch_stage.hpp"

namespace tidalcrust {

int command_stretch(int argc, char** argv) {
  cxxopts::Options options("tidalcrust stretch", "Stretch and strengthen a built body (paper section 2.3).");
  auto in = read_stage_input(options, argc, argv, "input build checkpoint", false, {"build"}, "stretch");
  if (!in) return exit_ok;
  const auto& [parsed, common, from, out, input] = *in;
  Config config = stage_config(input, from, common, false);
  apply_thread_count(common.threads);
  const StageLock lock = lock_output(out, from, false);
  Checkpoint stretched = stretch_stage(input, config);
  write_checkpoint(out, stretched);
  fmt::print("{}: stretch written (factor {}, residual surface acceleration {:.3g})\n", out.string(),
             stretched.stage.as<StretchRecord>().stretch_factor,
             stretched.stage.as<StretchRecord>().residual_surface_acceleration);
  return exit_ok;
}

}  // namespace tidalcrust
