#include "cli/stage_command.hpp"

#include "io/checkpoint_names.hpp"

#include <fmt/format.h>

#include "base/errors.hpp"
#include "io/checkpoint_file.hpp"

namespace tidalcrust {

namespace fs = std::filesystem;

std::string required_option(const cxxopts::ParseResult& parsed, const char* name) {
  if (!parsed.count(name)) throw InputError(fmt::format("missing required option --{}", name));
  return parsed[name].as<std::string>();
}

void check_output_path(const fs::path& out) {
  fs::path folder = out.parent_path().empty() ? fs::path(".") : out.parent_path();
  if (!fs::is_directory(folder))
    throw InputError(fmt::format("{}: output folder does not exist", folder.string()));
  if (out.extension() != ".h5") throw InputError(fmt::format("{}: output file must end in .h5", out.string()));
}

StageLock lock_output(const fs::path& out, const fs::path& from, bool resuming) {
  LockAttempt attempt = try_lock_stage(out, "");
  if (!attempt.lock)
    throw InputError(fmt::format("{}: is being computed by {} (lock {}); wait for it to finish or use another --out",
                                 out.string(), attempt.holder->describe(), lock_path(out).string()));
  if (attempt.lock->taken_over_from()) fmt::print(stderr, "tidalcrust: {}\n", attempt.lock->takeover_note());
  remove_stage_outputs(out, resuming, {out, from});
  return std::move(*attempt.lock);
}

void add_loop_options(cxxopts::Options& options) {
  options.add_options("stepping")
      ("checkpoint-every", "steps between mid-stage checkpoints (default: from the configuration)",
       cxxopts::value<std::int64_t>())
      ("stop-after-step", "testing aid: stop as if interrupted right after this global step",
       cxxopts::value<std::int64_t>()->default_value("-1"))
      ("quiet", "no progress lines");
}

StepLoopOptions loop_options_for(const cxxopts::ParseResult& parsed, const fs::path& out, std::string label,
                                 std::int64_t default_interval) {
  const std::int64_t interval =
      parsed.count("checkpoint-every") ? parsed["checkpoint-every"].as<std::int64_t>() : default_interval;
  if (interval < 0) throw InputError("--checkpoint-every must be >= 0");
  StepLoopOptions loop = stage_loop_options(out, std::move(label), interval);
  loop.stop_after_step = parsed["stop-after-step"].as<std::int64_t>();
  loop.quiet = parsed.count("quiet") > 0;
  return loop;
}

int finish_stage(LoopOutcome outcome, const Checkpoint& checkpoint, const fs::path& out, const StepLoopOptions& loop) {
  if (outcome == LoopOutcome::interrupted) {
    fmt::print(stderr, "stopped at step {}; resume with --from {}\n", checkpoint.state.step,
               loop.mid_checkpoint.string());
    return exit_interrupted;
  }
  write_checkpoint(out, checkpoint);
  remove_checkpoint_files(loop.mid_checkpoint);
  fmt::print("{}: {} written (step {}, time {})\n", out.string(), checkpoint.stage.name(), checkpoint.state.step,
             checkpoint.state.time);
  return exit_ok;
}

Config stage_config(const Checkpoint& input, const fs::path& from, const CommonOptions& common, bool resuming) {
  if (resuming) {
    if (common.config_file || !common.overrides.empty() || common.dt_factor != 1.0)
      throw InputError(fmt::format("{}: is a mid-stage checkpoint; it resumes with its own configuration "
                                   "(drop --config, --set and --dt-factor)", from.string()));
    Config stored = parse_config(input.config_toml, from.string() + ":/parameters/config");
    common.kernel.apply(stored);  // checked against the recorded kernel by continue_under_gravity_kernel
    return stored;
  }
  return resolve_config(input.config_toml, from.string() + ":/parameters/config", common);
}

void require_stage(const Checkpoint& input, const fs::path& from, std::initializer_list<const char*> allowed,
                   const char* command) {
  for (const char* stage : allowed)
    if (std::string_view(input.stage.name()) == stage) return;
  std::string names;
  for (const char* stage : allowed) names += (names.empty() ? "" : " or ") + std::string(stage);
  throw InputError(fmt::format("{}: is a '{}' checkpoint; {} needs a {} checkpoint", from.string(),
                               input.stage.name(), command, names));
}

std::optional<StageInput> read_stage_input(cxxopts::Options& options, int argc, char** argv, const char* from_help,
                                           bool time_stepping, std::initializer_list<const char*> allowed,
                                           const char* command) {
  add_common_options(options);
  if (time_stepping) add_loop_options(options);
  options.add_options()("from", from_help, cxxopts::value<std::string>())("out", "output checkpoint",
                                                                           cxxopts::value<std::string>());
  auto parsed = parse_arguments(options, argc, argv);
  if (parsed.count("help")) {
    fmt::print("{}\n", options.help());
    return std::nullopt;
  }
  StageInput in{parsed, read_common_options(parsed), required_option(parsed, "from"), required_option(parsed, "out"),
                {}};
  check_output_path(in.out);
  in.input = read_checkpoint(in.from);
  require_stage(in.input, in.from, allowed, command);
  return in;
}

}  // namespace tidalcrust
