#include "stages/workflow.hpp"

#include <fmt/format.h>

#include <fstream>

#include "analysis/fracture_analysis.hpp"
#include "base/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/checkpoint_file.hpp"
#include "io/checkpoint_names.hpp"
#include "io/json.hpp"
#include "io/progress.hpp"
#include "io/stage_lock.hpp"
#include "io/test_points.hpp"
#include "io/state_hash.hpp"
#include "model/stage_fingerprint.hpp"
#include "stages/analysis_stage.hpp"
#include "stages/run_stage.hpp"
#include "stages/stage_kinds.hpp"

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

/// How `run` computes a stage (stages/run_stage.hpp): waiting for a process computing the same
/// version, reusing a current file, resuming a matching mid-stage checkpoint.
StageRunOptions workflow_stage_options(const RunContext& ctx) {
  StageRunOptions options;
  options.wait_for_same_version = true;
  options.reuse_current = true;
  options.find_resume = true;
  options.allow_kernel_change = ctx.allow_kernel_change;
  options.quiet = ctx.quiet;
  options.status_file = ctx.status_file;
  options.say = [&ctx](const std::string& text) { say(ctx, text); };
  return options;
}

/// The file of stage `kind` in `dir`: body/build.h5, ..., <encounter>/encounter.h5.
fs::path stage_file(const fs::path& dir, const StageKind& kind) { return dir / (std::string(kind.name()) + ".h5"); }

/// Runs StageKind::prepare, if any, on `config` before `kind` begins from `parent`, printing its line.
void prepare_stage(const RunContext& ctx, const StageKind& kind, Config& config, const Checkpoint& parent,
                   const fs::path& parent_file) {
  if (!kind.prepare) return;
  const std::string note = kind.prepare(config, parent, parent_file.string());
  if (note.starts_with("warning")) fmt::print(stderr, "tidalcrust: {}\n", note);
  else if (!note.empty()) say(ctx, note);
}

}  // namespace

fs::path superseded_check_file(const fs::path& root) { return root / "body" / "encounters-checked"; }

void check_same_body(const fs::path& build_file, const Config& config) {
  if (!fs::exists(build_file)) return;
  const Checkpoint existing = read_checkpoint(build_file);
  const std::string wanted = stage_fingerprint(config, stage_kinds().front().id);
  if (same_fingerprint(existing.stage.fingerprint, wanted)) return;
  std::string existing_workflow = "?";  // the name in its stored configuration, to say whose body it is
  try {
    existing_workflow = parse_config(existing.config_toml, build_file.string()).workflow.name;
  } catch (const InputError&) {
  }
  throw InputError(fmt::format(
      "{}: the output folder holds checkpoints of a different body: the body of workflow '{}' (build state {}), not "
      "the body of workflow '{}' this run builds ({}); use --out DIR or remove the folder",
      build_file.string(), existing_workflow, state_hash(existing.state), config.workflow.name,
      existing.stage.fingerprint.empty() ? "no fingerprint"
                                         : "first difference " + first_difference(existing.stage.fingerprint, wanted)));
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

/// The relaxed body's state_hash against which every encounter folder of `root` was last checked
/// (remove_superseded_encounters), or "" when none was.
std::string checked_against(const fs::path& root) {
  std::ifstream in(superseded_check_file(root));
  std::string hash;
  if (in) std::getline(in, hash);
  return hash;
}

/// Encounter folders below `root` (also in dt<factor>/) whose first per-encounter stage (`files`:
/// the per-encounter stages' file names, in chain order) branched from another relaxed body (the
/// body chain changed) are superseded: their checkpoints, snapshots and analysis are removed,
/// unless another process holds the first stage's lock. Unreadable ones are left alone (run
/// reports them when it reaches them). Once every folder was checked (none locked by another
/// process), superseded_check_file records `relaxed_hash`, and later runs on the same relaxed body
/// skip the scan: each task of a sweep then reads no other encounter's files (O(1), not O(N)).
void remove_superseded_encounters(const RunContext& ctx, const fs::path& root, const std::vector<fs::path>& files,
                                  const std::string& relaxed_hash) {
  if (checked_against(root) == relaxed_hash) return;
  bool every_folder_checked = true;
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
    const fs::path file = dir / files.front();
    const fs::path found = fs::exists(file) ? file : sibling_checkpoint(file, "mid");
    if (!fs::exists(found)) continue;
    try {
      const LockAttempt attempt = try_lock_stage(file, "");
      if (!attempt.lock) every_folder_checked = false;
      if (!attempt.lock || read_checkpoint(found).stage.parent_hash == relaxed_hash) continue;
      for (const auto& name : files) remove_stage_outputs(dir / name, false);
      fs::remove_all(dir / "analysis", ec);
      say(ctx, fmt::format("{}: removed the encounter, which branched from another relaxed body", dir.string()));
    } catch (const InputError&) {
      continue;
    }
  }
  if (every_folder_checked) write_file_atomically(superseded_check_file(root), relaxed_hash + "\n");
}

WorkflowResult interrupted(WorkflowResult& result) {
  result.interrupted = true;
  return std::move(result);
}

}  // namespace

Config body_chain_config(const Config& config, const fs::path& root) {
  Config prepared = config;
  fs::path parent_file;
  for (const StageKind& kind : stage_kinds()) {
    if (kind.per_encounter) continue;
    if (kind.prepare && !parent_file.empty()) {
      if (!fs::exists(parent_file)) return prepared;  // nothing run yet: the caller says so
      kind.prepare(prepared, read_checkpoint(parent_file), parent_file.string());
    }
    parent_file = stage_file(root / "body", kind);
  }
  return prepared;
}

WorkflowResult run_workflow(const Config& config, const WorkflowOptions& options) {
  RunContext ctx;
  ctx.quiet = options.quiet;
  ctx.allow_kernel_change = options.allow_kernel_change;
  const fs::path body_dir = options.root / "body";
  // Checked before anything is written, and again under the first stage's lock (a process with
  // another body may have written it since: one folder, one body chain, decided under that lock).
  const fs::path first_file = stage_file(body_dir, stage_kinds().front());
  check_same_body(first_file, config);
  test_point_after_body_check();
  fs::create_directories(body_dir);
  ctx.status_file = options.root / "status.json";
  WorkflowResult result;

  // Body chain (the stages that are not per encounter, in table order), each beginning from the
  // one before: one process computes each stage, others that need the same version wait.
  Config body_config = config;  // as StageKind::prepare leaves it (the relax's time step)
  std::optional<Checkpoint> body;
  fs::path body_file;
  for (const StageKind& kind : stage_kinds()) {
    if (kind.per_encounter) continue;
    if (body) prepare_stage(ctx, kind, body_config, *body, body_file);
    const StageJob job{&kind, kind.name(), stage_file(body_dir, kind), body ? &*body : nullptr, body_file, nullptr};
    StageRunOptions stage_options = workflow_stage_options(ctx);
    if (job.file == first_file) stage_options.check_locked = [&] { check_same_body(first_file, config); };
    StageResult done = run_stage(job, body_config, std::move(stage_options));
    if (done.outcome == LoopOutcome::interrupted) return interrupted(result);
    body = std::move(done.checkpoint);
    body_file = job.file;
  }
  if (const auto* relaxed = std::get_if<RelaxRecord>(&body->stage.record)) result.relaxed = *relaxed;

  // Per-encounter stages, for each encounter branching from the end of the body chain, at
  // dt * dt_factor; the lock of an encounter's last stage also covers its analysis, so processes
  // running different encounters run side by side.
  Config encounter_config = body_config;
  if (options.dt_factor != 1.0) scale_time_step(encounter_config, options.dt_factor);
  const fs::path encounter_root =
      options.dt_factor == 1.0 ? options.root : options.root / fmt::format("dt{}", options.dt_factor);
  std::vector<const StageKind*> per_encounter;
  std::vector<fs::path> per_encounter_files;
  for (const StageKind& kind : stage_kinds())
    if (kind.per_encounter) {
      per_encounter.push_back(&kind);
      per_encounter_files.push_back(stage_file("", kind));
    }
  remove_superseded_encounters(ctx, options.root, per_encounter_files, state_hash(body->state));
  for (const auto& spec : options.encounters) {
    const fs::path dir = encounter_root / spec.name;
    fs::create_directories(dir);
    std::optional<Checkpoint> parent;
    fs::path parent_file = body_file;
    for (const StageKind* kind : per_encounter) {
      const StageJob job{kind, fmt::format("{} {}", kind->name(), spec.name), stage_file(dir, *kind),
                         parent ? &*parent : &*body, parent_file, &spec};
      StageRunOptions stage_options = workflow_stage_options(ctx);
      if (kind == per_encounter.back()) {
        stage_options.derived = dir / "analysis";
        stage_options.finish = [&](const Checkpoint& done) {
          analyze_if_stale(ctx, job.file, done, dir / "analysis", spec.name);
        };
      }
      StageResult done = run_stage(job, encounter_config, std::move(stage_options));
      if (done.outcome == LoopOutcome::interrupted) return interrupted(result);
      parent = std::move(done.checkpoint);
      parent_file = job.file;
    }
    result.encounters.push_back({spec.name, parent_file, dir / "analysis",
                                 fracture_summary_line(spec.name, analyze_fractures(parent->body, parent->state)),
                                 failure_trend_line(spec.name, *parent)});
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
