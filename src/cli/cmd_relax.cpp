// `tidalcrust relax`
#include <fmt/format.h>

#include <filesystem>

#include "io/checkpoint_file.hpp"
#include "cli/cli_options.hpp"
#include "cli/commands.hpp"
#include "base/errors.hpp"
#include "stages/relax_stage.hpp"
#include "cli/stage_command.hpp"

namespace tidalcrust {

namespace fs = std::filesystem;

int command_relax(int argc, char** argv) {
  cxxopts::Options options("tidalcrust relax", "Damped relaxation and stability probe (paper section 2.8).");
  add_common_options(options);
  add_loop_options(options);
  options.add_options()("from", "input stretch checkpoint (or a mid-stage relax checkpoint to resume)",
                        cxxopts::value<std::string>())("out", "output checkpoint", cxxopts::value<std::string>());
  auto parsed = parse_arguments(options, argc, argv);
  if (parsed.count("help")) return fmt::print("{}\n", options.help()), exit_ok;
  CommonOptions common = read_common_options(parsed);
  fs::path from = required_option(parsed, "from"), out = required_option(parsed, "out");
  check_output_path(out);
  Checkpoint input = read_checkpoint(from);
  require_stage(input, from, {"stretch", "relax"}, "relax");
  const bool resuming = std::holds_alternative<RelaxRecord>(input.stage.record);
  if (resuming && input.stage.complete)
    throw InputError(fmt::format("{}: relaxation is already complete", from.string()));
  Config config = stage_config(input, from, common, resuming);
  apply_thread_count(common.threads);
  Checkpoint checkpoint = resuming ? std::move(input) : begin_relax(input, config);
  StepLoopOptions loop = loop_options_for(parsed, out, "relax", config.relax.checkpoint_interval);
  return finish_stage(run_relax(checkpoint, config, loop), checkpoint, out, loop);
}

}  // namespace tidalcrust
