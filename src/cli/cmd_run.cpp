// `tidalcrust run WORKFLOW.toml`: the restart-driven workflow. One body chain (build, stretch,
// relax) shared by all encounters; each encounter and its analysis in its own folder. Rerunning
// after an interruption continues from the newest valid checkpoint; finished stages whose
// fingerprint and parent match are skipped; a changed value reruns exactly what it affects.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include "stages/analysis_stage.hpp"
#include "analysis/fracture_analysis.hpp"
#include "io/progress.hpp"
#include "stages/build_stage.hpp"
#include "io/checkpoint_file.hpp"
#include "cli/cli_options.hpp"
#include "cli/commands.hpp"
#include "stages/encounter_stage.hpp"
#include "base/errors.hpp"
#include "stages/relax_stage.hpp"
#include "cli/stage_command.hpp"
#include "model/stage_fingerprint.hpp"
#include "io/state_hash.hpp"
#include "stages/stretch_stage.hpp"

namespace tidalcrust {
namespace {

namespace fs = std::filesystem;

struct RunContext {
  fs::path root;
  fs::path status_file;
  bool quiet = false;
};

/// A finished checkpoint that can be reused as it is, or nothing.
std::optional<Checkpoint> reusable(const fs::path& file, const std::string& fingerprint,
                                   const std::string& parent_hash) {
  if (!fs::exists(file)) return std::nullopt;
  Checkpoint existing = read_checkpoint(file);  // corrupt final file: exit 2, never guessed over
  auto it = existing.stage.labels.find(fingerprint_label);
  const bool same_config = it != existing.stage.labels.end() && it->second == fingerprint;
  if (existing.stage.complete && same_config && existing.stage.parent_hash == parent_hash) return existing;
  return std::nullopt;
}

/// A mid-stage checkpoint to resume from, or nothing (stale or corrupt ones are ignored:
/// they are only a shortcut, and the stage can always start again from its parent).
std::optional<Checkpoint> resumable(const fs::path& mid, const std::string& fingerprint,
                                    const std::string& parent_hash) {
  if (!fs::exists(mid)) return std::nullopt;
  Checkpoint existing;
  try {
    existing = read_checkpoint(mid);
  } catch (const InputError&) {
    return std::nullopt;
  }
  auto it = existing.stage.labels.find(fingerprint_label);
  if (it == existing.stage.labels.end() || it->second != fingerprint || existing.stage.parent_hash != parent_hash ||
      existing.stage.complete)
    return std::nullopt;
  return existing;
}

StepLoopOptions loop_options(const RunContext& ctx, const fs::path& final_file, std::string label,
                             std::int64_t interval) {
  StepLoopOptions loop;
  loop.label = std::move(label);
  loop.mid_checkpoint = sibling_checkpoint(final_file, "mid");
  loop.diagnostic_checkpoint = sibling_checkpoint(final_file, "diagnostic");
  loop.checkpoint_interval = interval;
  loop.status_file = ctx.status_file;
  loop.quiet = ctx.quiet;
  return loop;
}

void say(const RunContext& ctx, const std::string& text) {
  if (!ctx.quiet) fmt::print("{}\n", text);
}

void analyze_if_stale(const RunContext& ctx, const fs::path& file, const Checkpoint& encounter, const fs::path& out,
                      const std::string& name) {
  if (analysis_is_current(out, encounter)) {
    say(ctx, fmt::format("analyze {}: up to date ({})", name, out.string()));
    return;
  }
  analyze_encounter(file, encounter, out);
  say(ctx, fmt::format("analyze {}: figures and summary.json in {}", name, out.string()));
}

/// The configuration a stage started with. A resumed stage keeps it even if values that do not
/// affect it (they are not in its fingerprint) changed since.
Config stored_config(const Checkpoint& checkpoint) {
  return parse_config(checkpoint.config_toml, "/parameters/config");
}

/// A stage without time steps (build, stretch): its final file when that is current, else
/// made anew and written.
template <typename Make>
Checkpoint instant_stage(const RunContext& ctx, const char* name, const fs::path& file, const std::string& fingerprint,
                         const std::string& parent_hash, const char* doing, Make make) {
  if (auto existing = reusable(file, fingerprint, parent_hash)) {
    say(ctx, fmt::format("{}: up to date ({})", name, file.string()));
    return std::move(*existing);
  }
  say(ctx, fmt::format("{}: {}", name, doing));
  Checkpoint made = make();
  made.stage.labels[fingerprint_label] = fingerprint;
  write_checkpoint(file, made);
  return made;
}

/// A time-stepping stage (relax, encounter): its final file when that is current; else resumed
/// from a matching mid-stage checkpoint or begun anew, run, written. Nothing when interrupted.
template <typename Begin, typename Run>
std::optional<Checkpoint> stepping_stage(const RunContext& ctx, const std::string& name, const fs::path& file,
                                         const std::string& fingerprint, const std::string& parent_hash,
                                         std::int64_t checkpoint_interval, Begin begin, Run run) {
  if (auto existing = reusable(file, fingerprint, parent_hash)) {
    say(ctx, fmt::format("{}: up to date ({})", name, file.string()));
    return existing;
  }
  const StepLoopOptions loop = loop_options(ctx, file, name, checkpoint_interval);
  std::optional<Checkpoint> checkpoint = resumable(loop.mid_checkpoint, fingerprint, parent_hash);
  if (checkpoint) {
    say(ctx, fmt::format("{}: resuming from {} (step {})", name, loop.mid_checkpoint.string(), checkpoint->state.step));
  } else {
    checkpoint = begin();
    checkpoint->stage.labels[fingerprint_label] = fingerprint;
  }
  if (run(*checkpoint, loop, file) == LoopOutcome::interrupted) return std::nullopt;
  write_checkpoint(file, *checkpoint);
  remove_checkpoint_files(loop.mid_checkpoint);
  return checkpoint;
}

/// Refuses an output folder that holds another body, before anything is written.
void check_same_body(const fs::path& build_file, const Config& config) {
  if (!fs::exists(build_file)) return;
  Checkpoint existing = read_checkpoint(build_file);
  auto it = existing.stage.labels.find(fingerprint_label);
  const std::string wanted = build_fingerprint(config);
  if (it == existing.stage.labels.end() || it->second != wanted)
    throw InputError(fmt::format(
        "{}: the output folder holds checkpoints of a different body ({}); use --out DIR or remove the folder",
        build_file.string(),
        it == existing.stage.labels.end() ? "no fingerprint" : first_difference(it->second, wanted)));
}

}  // namespace

int command_run(int argc, char** argv) {
  cxxopts::Options options("tidalcrust run", "Run a whole workflow; rerun the same command to resume.");
  options.positional_help("WORKFLOW.toml");
  options.add_options()("workflow", "workflow TOML file", cxxopts::value<std::string>())(
      "out", "output root (default checkpoints/<workflow name>)", cxxopts::value<std::string>())(
      "threads", "number of threads (results do not depend on it)", cxxopts::value<int>()->default_value("0"))(
      "dt-factor", "run the encounters at dt times this factor, into a separate folder",
      cxxopts::value<double>()->default_value("1.0"))(
      "only", "run only this encounter (repeatable)", cxxopts::value<std::vector<std::string>>())(
      "set", "override one value: section.key=value (repeatable)", cxxopts::value<std::vector<std::string>>())(
      "quiet", "no progress lines")("h,help", "show this help");
  options.parse_positional({"workflow"});
  auto parsed = parse_arguments(options, argc, argv);
  if (parsed.count("help")) return fmt::print("{}\n", options.help()), exit_ok;
  if (!parsed.count("workflow")) throw InputError("missing WORKFLOW.toml (see --help)");

  // Everything is checked before anything is written.
  const fs::path workflow = parsed["workflow"].as<std::string>();
  Config config = load_config(workflow);
  if (parsed.count("set"))
    for (const auto& assignment : parsed["set"].as<std::vector<std::string>>()) apply_override(config, assignment);
  validate(config, "--set");
  const double dt_factor = parsed["dt-factor"].as<double>();
  if (!std::isfinite(dt_factor) || dt_factor <= 0)
    throw InputError(fmt::format("--dt-factor must be a number > 0, got {}", dt_factor));
  const int threads = parsed["threads"].as<int>();
  if (threads < 0) throw InputError(fmt::format("--threads must be >= 0, got {}", threads));
  std::vector<EncounterSpec> encounters = config.encounters;
  if (parsed.count("only")) {
    encounters.clear();
    for (const auto& name : parsed["only"].as<std::vector<std::string>>())
      encounters.push_back(config.find_encounter(name));
  }
  RunContext ctx;
  ctx.root = parsed.count("out") ? fs::path(parsed["out"].as<std::string>())
                                 : fs::path("checkpoints") / config.workflow.name;
  ctx.quiet = parsed.count("quiet") > 0;
  const fs::path body_dir = ctx.root / "body";
  check_same_body(body_dir / "build.h5", config);
  apply_thread_count(threads);
  fs::create_directories(body_dir);
  ctx.status_file = ctx.root / "status.json";

  // Body chain.
  const Checkpoint built = instant_stage(ctx, "build", body_dir / "build.h5", build_fingerprint(config), "",
                                         "building the body", [&] { return build_stage(config); });
  const std::string built_hash = state_hash(built.state);
  const Checkpoint stretched =
      instant_stage(ctx, "stretch", body_dir / "stretch.h5", stretch_fingerprint(config), built_hash,
                    "stretching and strengthening", [&] { return stretch_stage(built, config); });

  const std::string stretched_hash = state_hash(stretched.state);
  const auto relaxed = stepping_stage(
      ctx, "relax", body_dir / "relax.h5", relax_fingerprint(config), stretched_hash,
      config.relax.checkpoint_interval, [&] { return begin_relax(stretched, config); },
      [&](Checkpoint& c, const StepLoopOptions& loop, const fs::path&) {
        return run_relax(c, stored_config(c), loop);
      });
  if (!relaxed) return exit_interrupted;

  // Encounters, each branching from the relaxed body, at dt * dt_factor.
  Config encounter_config = config;
  if (dt_factor != 1.0) scale_time_step(encounter_config, dt_factor);
  const fs::path encounter_root = dt_factor == 1.0 ? ctx.root : ctx.root / fmt::format("dt{}", dt_factor);
  const std::string relaxed_hash = state_hash(relaxed->state);
  std::vector<std::string> summary_lines;
  for (const auto& spec : encounters) {
    const fs::path dir = encounter_root / spec.name;
    fs::create_directories(dir);
    const fs::path file = dir / "encounter.h5";
    const auto encounter = stepping_stage(
        ctx, "encounter " + spec.name, file, encounter_fingerprint(encounter_config, spec), relaxed_hash,
        encounter_config.encounter.checkpoint_interval,
        [&] { return begin_encounter(*relaxed, encounter_config, spec); },
        [&](Checkpoint& c, const StepLoopOptions& loop, const fs::path& out) {
          return run_encounter(c, stored_config(c), loop, out);
        });
    if (!encounter) return exit_interrupted;
    analyze_if_stale(ctx, file, *encounter, dir / "analysis", spec.name);
    summary_lines.push_back(fracture_summary_line(spec.name, analyze_fractures(encounter->body, encounter->state)) +
                            fmt::format("\n    figures: {}", (dir / "analysis").string()));
  }

  Json status = {
      {"stage", "workflow " + config.workflow.name}, {"state", "done"}, {"dt_factor", dt_factor}, {"encounters", Json::array()}};
  for (const auto& spec : encounters) status["encounters"].push_back(spec.name);
  write_status_file(ctx.status_file, status);
  fmt::print("\nworkflow {} finished: checkpoints in {}\n", config.workflow.name, ctx.root.string());
  const auto& probe = relaxed->stage.scalars;
  if (probe.count("stability_failures"))
    fmt::print("relaxed body: stability probe {} failures, largest shell strain {:.2e}\n",
               probe.at("stability_failures"), probe.count("stability_max_shell_strain") ? probe.at("stability_max_shell_strain") : NAN);
  for (const auto& line : summary_lines) fmt::print("  {}\n", line);
  return exit_ok;
}

}  // namespace tidalcrust
