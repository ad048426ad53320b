// `tidalcrust build|stretch|relax|encounter`: one stage of the table (stages/stage_kinds.hpp) run by
// hand, from a checkpoint (or, for a stage without parents, from --config) into --out, computed by
// run_stage (stages/run_stage.hpp) as `run` computes it, but never waiting for or reusing another
// process's work: the output's lock is refused while anyone holds it, and --out is replaced. The
// same command run again after an interruption resumes from --out's matching mid-stage checkpoint
// (a killed run's progress is never thrown away by repeating the command that started it).
#include <fmt/format.h>

#include <filesystem>
#include <optional>
#include <string>

#include "base/errors.hpp"
#include "cli/cli_options.hpp"
#include "cli/commands.hpp"
#include "io/checkpoint_file.hpp"
#include "stages/encounter_stage.hpp"
#include "stages/run_stage.hpp"
#include "stages/stage_kinds.hpp"

namespace tidalcrust {
namespace {

namespace fs = std::filesystem;

std::string required_option(const cxxopts::ParseResult& parsed, const char* name) {
  if (!parsed.count(name)) throw InputError(fmt::format("missing required option --{}", name));
  return parsed[name].as<std::string>();
}

/// The output folder must exist and the name end in .h5 (checked before any work).
void check_output_path(const fs::path& out) {
  fs::path folder = out.parent_path().empty() ? fs::path(".") : out.parent_path();
  if (!fs::is_directory(folder)) throw InputError(fmt::format("{}: output folder does not exist", folder.string()));
  if (out.extension() != ".h5") throw InputError(fmt::format("{}: output file must end in .h5", out.string()));
}

/// The stages a command of `kind` continues: its parents and, for a stepping stage, itself (a
/// mid-stage checkpoint to resume).
StageSet accepted_inputs(const StageKind& kind) {
  return kind.stepping() ? kind.parents | StageSet{kind.id} : kind.parents;
}

/// InputError unless `input` can be continued by the command of `kind`; true when it resumes it.
bool check_input(const StageKind& kind, const Checkpoint& input, const fs::path& from) {
  const StageId stage = stage_id(input.stage.record);
  if (!accepted_inputs(kind).contains(stage))
    throw InputError(fmt::format("{}: is a '{}' checkpoint; {} needs a {} checkpoint", from.string(), input.stage.name(),
                                 kind.name(), stage_list(accepted_inputs(kind), " or ")));
  if (!input.stage.complete) {
    if (stage == kind.id) return true;
    throw InputError(fmt::format("{}: is a mid-stage {} checkpoint; finish it with 'tidalcrust {}'", from.string(),
                                 input.stage.name(), input.stage.name()));
  }
  if (!kind.parents.contains(stage))
    throw InputError(fmt::format("{}: the {} stage is already complete", from.string(), kind.name()));
  return false;
}

/// The configuration for a stage: from the input checkpoint, --config and --set. A mid-stage
/// checkpoint resumes with exactly the configuration it started with, except the gravity kernel
/// (--gravity-kernel, refused by continue_under_gravity_kernel unless it gives the same bits).
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

void add_encounter_options(cxxopts::Options& options) {
  options.add_options("encounter")
      ("encounter", "name of an encounter of the configuration", cxxopts::value<std::string>())
      ("m2", "perturber mass M2 (M)", cxxopts::value<double>())
      ("q", "pericenter distance (R)", cxxopts::value<double>())
      ("vq", "speed at pericenter (sqrt(GM/R); default parabolic, sqrt(2 (1 + M2) / q))", cxxopts::value<double>())
      ("failure-strain", "eps_S for this encounter", cxxopts::value<double>());
}

/// The encounter of a per-encounter stage begun anew: --encounter NAME of the configuration, or
/// --m2, --q and --vq ("custom"), with --failure-strain; InputError for a missing, doubled or
/// invalid one.
Encounter encounter_of(const cxxopts::ParseResult& parsed, const Config& config) {
  const bool by_name = parsed.count("encounter") > 0;
  const bool by_values = parsed.count("m2") || parsed.count("q") || parsed.count("vq");
  if (by_name == by_values) throw InputError("give either --encounter NAME or --m2 M --q Q [--vq V]");
  Encounter spec;
  if (by_name) {
    spec = config.find_encounter(parsed["encounter"].as<std::string>());
  } else {
    if (!(parsed.count("m2") && parsed.count("q")))
      throw InputError("--m2 and --q must be given together (--vq: default parabolic)");
    spec.name = "custom";
    spec.perturber_mass = parsed["m2"].as<double>();
    spec.pericenter = parsed["q"].as<double>();
    spec.pericenter_speed =
        parsed.count("vq") ? parsed["vq"].as<double>() : parabolic_speed(spec.perturber_mass, spec.pericenter);
  }
  if (parsed.count("failure-strain")) spec.failure_strain = parsed["failure-strain"].as<double>();
  Config checked = config;
  checked.encounters = {spec};
  validate(checked, "encounter options");  // NaN, negative mass, q inside the body -> exit 2
  return spec;
}

}  // namespace

int command_stage(const StageKind& kind, int argc, char** argv) {
  cxxopts::Options options = command_options(kind.name());
  add_common_options(options);
  const bool from_configuration = kind.parents.empty();
  if (kind.stepping())
    options.add_options("stepping")
        ("checkpoint-every", fmt::format("steps between mid-stage checkpoints (default: {})", kind.checkpoint_interval_key),
         cxxopts::value<std::int64_t>())
        ("stop-after-step", "testing aid: stop as if interrupted right after this global step",
         cxxopts::value<std::int64_t>()->default_value("-1"))
        ("quiet", "no progress lines");
  if (kind.per_encounter) add_encounter_options(options);
  if (!from_configuration)
    options.add_options()("from",
                          fmt::format("input {} checkpoint{}", stage_list(kind.parents, " or "),
                                      kind.stepping() ? fmt::format(" (or a mid-stage {} checkpoint to resume)", kind.name())
                                                      : ""),
                          cxxopts::value<std::string>());
  options.add_options()("out", "output checkpoint", cxxopts::value<std::string>());
  const auto parsed = parse_arguments(options, argc, argv);
  if (parsed.count("help")) return fmt::print("{}\n", options.help()), exit_ok;
  const CommonOptions common = read_common_options(parsed);

  // Everything is checked before anything is computed or written.
  if (from_configuration && !common.config_file) throw InputError("missing required option --config WORKFLOW.toml");
  const fs::path from = from_configuration ? fs::path() : fs::path(required_option(parsed, "from"));
  const fs::path out = required_option(parsed, "out");
  check_output_path(out);
  std::optional<Checkpoint> input;
  bool resuming = false;
  Config config;
  if (from_configuration) {
    // --config, each --set, then --dt-factor: the time step is stored in the build checkpoint and
    // every later stage continues with it (no common option is ignored).
    config = resolve_config("", "", common);
  } else {
    input = read_checkpoint(from);
    resuming = check_input(kind, *input, from);
    config = stage_config(*input, from, common, resuming);
  }
  std::optional<Encounter> spec;
  if (kind.per_encounter && resuming && (parsed.count("encounter") || parsed.count("m2") || parsed.count("q") ||
                                         parsed.count("vq")))
    throw InputError(fmt::format("{}: is a mid-stage {}; it resumes its own encounter "
                                 "(drop --encounter/--m2/--q/--vq)", from.string(), kind.name()));
  if (kind.per_encounter && !resuming) {
    spec = encounter_of(parsed, config);
    check_encounter(config, *spec, from.string());  // its time step is the input checkpoint's
  }
  if (!resuming && kind.prepare) {
    const std::string note = kind.prepare(config, *input, from.string());
    if (!note.empty()) fmt::print(stderr, "tidalcrust: {}\n", note);
  }
  apply_thread_count(common.threads);

  const Encounter* encounter = spec ? &*spec : (input ? record_encounter(input->stage.record) : nullptr);
  StageJob job{&kind, kind.per_encounter ? fmt::format("{} {}", kind.name(), encounter->name) : kind.name(), out,
               resuming ? nullptr : (input ? &*input : nullptr), from, spec ? &*spec : nullptr};
  StageRunOptions run;
  run.keep = {out, from};  // `out` is replaced when the stage is done
  run.allow_kernel_change = common.kernel.allow_change;
  run.config_source = common.config_file ? common.config_file->string() : from.string();
  if (kind.stepping()) {
    if (parsed.count("checkpoint-every")) run.checkpoint_interval = parsed["checkpoint-every"].as<std::int64_t>();
    if (run.checkpoint_interval && *run.checkpoint_interval < 0) throw InputError("--checkpoint-every must be >= 0");
    run.stop_after_step = parsed["stop-after-step"].as<std::int64_t>();
    run.quiet = parsed.count("quiet") > 0;
    run.find_resume = true;  // --out's matching mid-stage checkpoint (none needed when --from is one)
    run.say = [](const std::string& text) { fmt::print(stderr, "tidalcrust: {}\n", text); };  // "resuming from"
  }
  if (resuming) {
    run.resume = std::move(input);
    run.resume_file = from;
  }
  const StageResult done = run_stage(job, config, std::move(run));
  if (done.outcome == LoopOutcome::interrupted) {
    fmt::print(stderr, "stopped at step {}; resume with --from {} (or the same command again)\n",
               done.checkpoint.state.step, done.mid_checkpoint.string());
    return exit_interrupted;
  }
  fmt::print("{}: {} written ({})\n", out.string(), kind.name(),
             kind.written ? kind.written(done.checkpoint)
                          : fmt::format("step {}, time {}", done.checkpoint.state.step, done.checkpoint.state.time));
  return exit_ok;
}

}  // namespace tidalcrust
