// `tidalcrust build`
#include <fmt/format.h>

#include <filesystem>

#include "stages/build_stage.hpp"
#include "io/checkpoint_file.hpp"
#include "cli/cli_options.hpp"
#include "cli/commands.hpp"
#include "base/errors.hpp"
#include "cli/stage_command.hpp"

namespace tidalcrust {

namespace fs = std::filesystem;

int command_build(int argc, char** argv) {
  cxxopts::Options options("tidalcrust build", "Build the body of a workflow (random interior, shell, springs).");
  add_common_options(options);
  options.add_options()("out", "output checkpoint BODY.h5", cxxopts::value<std::string>());
  auto parsed = parse_arguments(options, argc, argv);
  if (parsed.count("help")) return fmt::print("{}\n", options.help()), exit_ok;
  CommonOptions common = read_common_options(parsed);
  if (!common.config_file) throw InputError("missing required option --config WORKFLOW.toml");
  fs::path out = required_option(parsed, "out");
  check_output_path(out);
  // --config, each --set, then --dt-factor: the time step is stored in the build checkpoint and
  // every later stage continues with it (no common option is ignored).
  const Config config = resolve_config("", "", common);
  apply_thread_count(common.threads);
  const StageLock lock = lock_output(out, {}, false);
  Checkpoint body = build_stage(config);
  write_checkpoint(out, body);
  fmt::print("{}: build written ({} particles, {} springs, {} hinges)\n", out.string(), body.body.particle_count(),
             body.body.spring_count(), body.body.hinge_count());
  return exit_ok;
}

}  // namespace tidalcrust
