#include "stages/workflow.hpp"

#include <fmt/format.h>

#include <chrono>
#include <thread>

#include "analysis/fracture_analysis.hpp"
#include "base/errors.hpp"
#include "io/checkpoint_file.hpp"
#include "io/checkpoint_names.hpp"
#include "io/json.hpp"
#include "io/progress.hpp"
#include "io/stage_lock.hpp"
#include "io/state_hash.hpp"
#include "io/stop_signal.hpp"
#include "model/stage_fingerprint.hpp"
#include "stages/analysis_stage.hpp"
#include "stages/build_stage.hpp"
#include "stages/encounter_stage.hpp"
#include "stages/gravity_kernel_check.hpp"
#include "stages/relax_stage.hpp"
#include "stages/stretch_stage.hpp"
#include "stages/time_step.hpp"

namespace tidalcrust {
namespace {

namespace fs = std::filesystem;

struct RunContext {
  fs::path status_file;
  bool quiet = false;
  bool allow_kernel_change = false;
};

void say(const RunContext& ctx, const std::string& text) {
  if (!ctx.quiet) fmt::print("{}\n", text);
}

/// How often a process waiting for another one's stage looks again.
constexpr auto lock_poll_interval = std::chrono::milliseconds(100);

/// Locks the stage `file` for computing the version `identity`: at once when it is free (taking
/// over, and saying so, the lock of a process that died); after waiting when another process
/// computes the same version (one line says whom it waits for) or briefly checks the folder (empty
/// identity: remove_superseded_encounters); InputError naming the holder when another process
/// computes another version. Nothing when SIGINT/SIGTERM arrive while waiting.
std::optional<StageLock> lock_stage(const RunContext& ctx, const std::string& name, const fs::path& file,
                                    const std::string& identity) {
  for (bool waiting = false;; std::this_thread::sleep_for(lock_poll_interval)) {
    LockAttempt attempt = try_lock_stage(file, identity);
    if (attempt.lock) {
      if (attempt.lock->taken_over_from()) fmt::print(stderr, "tidalcrust: {}\n", attempt.lock->takeover_note());
      return std::move(attempt.lock);
    }
    const LockHolder& holder = *attempt.holder;
    // An empty identity is another process's check for superseded encounters (it holds the lock
    // for a moment, never computes): wait for it like for the same version.
    if (holder.pid > 0 && holder.identity != identity && !holder.identity.empty())
      throw InputError(fmt::format(
          "{}: {} is being computed with other values by {} (lock {}); wait for it to finish or use another --out",
          file.string(), name, holder.describe(), lock_path(file).string()));
    if (!waiting && holder.pid > 0) {
      say(ctx, fmt::format("{}: waiting for {}, which is computing the same {}", name, holder.describe(), name));
      waiting = true;
    }
    if (stop_requested()) return std::nullopt;
  }
}

/// A finished checkpoint that can be reused as it is, or nothing.
std::optional<Checkpoint> reusable(const fs::path& file, const std::string& fingerprint,
                                   const std::string& parent_hash) {
  if (!fs::exists(file)) return std::nullopt;
  Checkpoint existing = read_checkpoint(file);  // corrupt final file: exit 2, never guessed over
  if (existing.stage.complete && existing.stage.fingerprint == fingerprint && existing.stage.parent_hash == parent_hash)
    return existing;
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
  if (existing.stage.fingerprint != fingerprint || existing.stage.parent_hash != parent_hash || existing.stage.complete)
    return std::nullopt;
  return existing;
}

/// A stage without time steps (build, stretch), under its lock (lock_stage): its final file
/// when that is current, else made anew and written. Nothing when interrupted while waiting.
template <typename Make>
std::optional<Checkpoint> instant_stage(const RunContext& ctx, const char* name, const fs::path& file,
                                        const std::string& fingerprint, const std::string& parent_hash,
                                        const char* doing, Make make) {
  const auto lock = lock_stage(ctx, name, file, stage_lock_identity(fingerprint, parent_hash));
  if (!lock) return std::nullopt;
  if (auto existing = reusable(file, fingerprint, parent_hash)) {
    say(ctx, fmt::format("{}: up to date ({})", name, file.string()));
    return existing;
  }
  say(ctx, fmt::format("{}: {}", name, doing));
  remove_stage_outputs(file, false);
  Checkpoint made = make();
  made.stage.fingerprint = fingerprint;
  write_checkpoint(file, made);
  return made;
}

/// A time-stepping stage (relax, encounter), under its lock (lock_stage): its final file when
/// that is current; else resumed from a matching mid-stage checkpoint or begun anew, run,
/// written; then `finish` (the encounter's analysis) still under the lock. Nothing when
/// interrupted.
/// A stage begun here runs with `config`; a resumed one with the configuration it started with
/// (values outside its fingerprint may have changed since).
/// Outputs of a superseded run (final file, diagnostic; when begun anew also the mid-stage
/// checkpoint and snapshots; and `derived`, e.g. the analysis folder) are removed before the
/// stage writes anything.
/// Stepping on under another gravity kernel than the checkpoint's (the parent's, `parent_file`,
/// or the mid-stage one's) is refused before anything is removed, unless allowed.
template <typename Begin, typename Run, typename Finish>
std::optional<Checkpoint> stepping_stage(const RunContext& ctx, const std::string& name, const fs::path& file,
                                         const std::string& fingerprint, const std::string& parent_hash,
                                         const Config& config, std::int64_t checkpoint_interval,
                                         const fs::path& parent_file, Begin begin, Run run,
                                         const fs::path& derived, Finish finish) {
  const auto lock = lock_stage(ctx, name, file, stage_lock_identity(fingerprint, parent_hash));
  if (!lock) return std::nullopt;
  if (auto existing = reusable(file, fingerprint, parent_hash)) {
    say(ctx, fmt::format("{}: up to date ({})", name, file.string()));
    finish(*existing);
    return existing;
  }
  StepLoopOptions loop = stage_loop_options(file, name, checkpoint_interval);
  loop.status_file = ctx.status_file;
  loop.quiet = ctx.quiet;
  std::optional<Checkpoint> checkpoint = resumable(loop.mid_checkpoint, fingerprint, parent_hash);
  const bool resuming = checkpoint.has_value();
  std::optional<Config> stored;
  if (resuming) {
    stored = parse_config(checkpoint->config_toml, loop.mid_checkpoint.string() + ":/parameters/config");
    stored->gravity.kernel = config.gravity.kernel;  // the kernel is this run's choice, checked next
  } else {
    checkpoint = begin();
    checkpoint->stage.fingerprint = fingerprint;
  }
  continue_under_gravity_kernel(*checkpoint, stored ? *stored : config, ctx.allow_kernel_change,
                                (resuming ? loop.mid_checkpoint : parent_file).string());
  remove_stage_outputs(file, resuming);
  if (!derived.empty()) fs::remove_all(derived);
  if (resuming)
    say(ctx, fmt::format("{}: resuming from {} (step {})", name, loop.mid_checkpoint.string(), checkpoint->state.step));
  if (run(*checkpoint, stored ? *stored : config, loop, file) == LoopOutcome::interrupted) return std::nullopt;
  write_checkpoint(file, *checkpoint);
  remove_checkpoint_files(loop.mid_checkpoint);
  finish(*checkpoint);
  return checkpoint;
}

}  // namespace

void check_same_body(const fs::path& build_file, const Config& config) {
  if (!fs::exists(build_file)) return;
  const Checkpoint existing = read_checkpoint(build_file);
  const std::string wanted = build_fingerprint(config);
  if (existing.stage.fingerprint != wanted)
    throw InputError(fmt::format(
        "{}: the output folder holds checkpoints of a different body ({}); use --out DIR or remove the folder",
        build_file.string(),
        existing.stage.fingerprint.empty() ? "no fingerprint" : first_difference(existing.stage.fingerprint, wanted)));
}

namespace {

void analyze_if_stale(const RunContext& ctx, const fs::path& file, const Checkpoint& encounter, const fs::path& out,
                      const std::string& name) {
  if (analysis_is_current(out, encounter)) {
    say(ctx, fmt::format("analyze {}: up to date ({})", name, out.string()));
    return;
  }
  analyze_encounter(file, encounter, out);
  say(ctx, fmt::format("analyze {}: figures and summary.json in {}", name, out.string()));
}

/// Encounter folders below `root` (also in dt<factor>/) whose encounter branched from another
/// relaxed body (the body chain changed) are superseded: their checkpoints, snapshots and
/// analysis are removed, unless another process holds the encounter's lock. Unreadable ones are
/// left alone (run reports them when it reaches them).
void remove_superseded_encounters(const RunContext& ctx, const fs::path& root, const std::string& relaxed_hash) {
  std::vector<fs::path> folders;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(root, ec)) {
    if (!entry.is_directory(ec)) continue;
    folders.push_back(entry.path());
    if (entry.path().filename().string().starts_with("dt"))
      for (const auto& inner : fs::directory_iterator(entry.path(), ec))
        if (inner.is_directory(ec)) folders.push_back(inner.path());
  }
  for (const auto& dir : folders) {
    const fs::path file = dir / "encounter.h5";
    const fs::path found = fs::exists(file) ? file : sibling_checkpoint(file, "mid");
    if (!fs::exists(found)) continue;
    try {
      const LockAttempt attempt = try_lock_stage(file, "");
      if (!attempt.lock || read_checkpoint(found).stage.parent_hash == relaxed_hash) continue;
      remove_stage_outputs(file, false);
      fs::remove_all(dir / "analysis", ec);
      say(ctx, fmt::format("{}: removed the encounter, which branched from another relaxed body", dir.string()));
    } catch (const InputError&) {
      continue;
    }
  }
}

WorkflowResult interrupted(WorkflowResult& result) {
  result.interrupted = true;
  return std::move(result);
}

}  // namespace

WorkflowResult run_workflow(const Config& config, const WorkflowOptions& options) {
  RunContext ctx;
  ctx.quiet = options.quiet;
  ctx.allow_kernel_change = options.allow_kernel_change;
  const fs::path body_dir = options.root / "body";
  check_same_body(body_dir / "build.h5", config);
  fs::create_directories(body_dir);
  ctx.status_file = options.root / "status.json";
  WorkflowResult result;

  // Body chain: one process computes each stage, others that need the same version wait.
  const auto built = instant_stage(ctx, "build", body_dir / "build.h5", build_fingerprint(config), "",
                                   "building the body", [&] { return build_stage(config); });
  if (!built) return interrupted(result);
  const auto stretched =
      instant_stage(ctx, "stretch", body_dir / "stretch.h5", stretch_fingerprint(config), state_hash(built->state),
                    config.stretch.hydrostatic_support == HydrostaticSupport::compress ? "stretching (interior compressed to its pressure)"
                                                                     : "stretching and strengthening",
                    [&] { return stretch_stage(*built, config); });
  if (!stretched) return interrupted(result);
  // dt checked against (or, for a [material] body without one, chosen from) the stability bound.
  Config body_config = config;
  const std::string dt_note = settle_time_step(body_config, *stretched, (body_dir / "stretch.h5").string());
  if (!dt_note.empty()) {
    if (dt_note.starts_with("warning")) fmt::print(stderr, "tidalcrust: {}\n", dt_note);
    else say(ctx, dt_note);
  }
  const auto relaxed = stepping_stage(
      ctx, "relax", body_dir / "relax.h5", relax_fingerprint(body_config), state_hash(stretched->state), body_config,
      body_config.relax.checkpoint_interval, body_dir / "stretch.h5", [&] { return begin_relax(*stretched, body_config); },
      [&](Checkpoint& c, const Config& run_config, const StepLoopOptions& loop, const fs::path&) {
        return run_relax(c, run_config, loop);
      },
      fs::path(), [](const Checkpoint&) {});
  if (!relaxed) return interrupted(result);
  result.relaxed = relaxed->stage.as<RelaxRecord>();

  // Encounters, each branching from the relaxed body, at dt * dt_factor; each encounter's lock
  // also covers its analysis, so processes running different encounters run side by side.
  Config encounter_config = body_config;
  if (options.dt_factor != 1.0) scale_time_step(encounter_config, options.dt_factor);
  const fs::path encounter_root =
      options.dt_factor == 1.0 ? options.root : options.root / fmt::format("dt{}", options.dt_factor);
  const std::string relaxed_hash = state_hash(relaxed->state);
  remove_superseded_encounters(ctx, options.root, relaxed_hash);
  for (const auto& spec : options.encounters) {
    const fs::path dir = encounter_root / spec.name;
    fs::create_directories(dir);
    const fs::path file = dir / "encounter.h5";
    const auto encounter = stepping_stage(
        ctx, "encounter " + spec.name, file, encounter_fingerprint(encounter_config, spec), relaxed_hash,
        encounter_config, encounter_config.encounter.checkpoint_interval, body_dir / "relax.h5",
        [&] { return begin_encounter(*relaxed, encounter_config, spec); },
        [&](Checkpoint& c, const Config& run_config, const StepLoopOptions& loop, const fs::path& out) {
          return run_encounter(c, run_config, loop, out);
        },
        dir / "analysis",
        [&](const Checkpoint& done) { analyze_if_stale(ctx, file, done, dir / "analysis", spec.name); });
    if (!encounter) return interrupted(result);
    result.encounters.push_back({spec.name, file, dir / "analysis",
                                 fracture_summary_line(spec.name, analyze_fractures(encounter->body, encounter->state))});
  }

  Json status = {{"stage", "workflow " + config.workflow.name},
                 {"state", "done"},
                 {"dt_factor", options.dt_factor},
                 {"encounters", Json::array()}};
  for (const auto& e : result.encounters) status["encounters"].push_back(e.name);
  write_status_file(ctx.status_file, status);
  return result;
}

}  // namespace tidalcrust
