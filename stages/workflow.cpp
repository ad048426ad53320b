#include "stages/workflow.hpp"

#include <fmt/format.h>

#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <unordered_map>

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
  std::string config_file;
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
  options.config_source = ctx.config_file;
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

fs::path superseded_check_file(const fs::path& body_dir) { return body_dir / "encounters-checked"; }

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
                      const std::string& name, bool figures) {
  if (analysis_is_current(out, encounter, figures)) {
    say(ctx, fmt::format("analyze {}: up to date ({})", name, out.string()));
    return;
  }
  analyze_encounter(file, encounter, out, figures);
  say(ctx, fmt::format("analyze {}: {}summary.json in {}", name, figures ? "figures and " : "", out.string()));
}

/// The relaxed body's state_hash against which the encounter folders of the body in `body_dir` were
/// last checked (remove_superseded_encounters), or "" when they were not.
std::string checked_against(const fs::path& body_dir) {
  std::ifstream in(superseded_check_file(body_dir));
  std::string hash;
  if (in) std::getline(in, hash);
  return hash;
}

/// Encounter folders below `root` (also in dt<factor>/) of the body of seed `seed` in `body_dir`
/// (`seed_of_folder` of the folder's name; for a name the workflow does not know, the seed its
/// checkpoint was computed with, so that a member dropped from a body-seed ensemble is not taken
/// for the workflow's body's) whose first per-encounter stage (`files`: the per-encounter stages' file
/// names, in chain order) branched from another relaxed body (that body chain changed) are
/// superseded: their checkpoints, snapshots and analysis are removed, unless another process holds
/// the first stage's lock. Unreadable ones are left alone (run reports them when it reaches them).
/// Once every folder was checked (none locked by another process), superseded_check_file records
/// `relaxed_hash`, and later runs on the same relaxed body skip the scan: each task of a sweep then
/// reads no other encounter's files (O(1), not O(N)).
void remove_superseded_encounters(const RunContext& ctx, const fs::path& root, const fs::path& body_dir,
                                  std::uint64_t seed,
                                  const std::function<std::optional<std::uint64_t>(const std::string&)>& seed_of_folder,
                                  const std::vector<fs::path>& files, const std::string& relaxed_hash) {
  if (checked_against(body_dir) == relaxed_hash) return;
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
  // First every encounter that began from a relaxed body: superseded when that is another one.
  // Then the encounters of histories (`after`), each once the one it comes after is settled:
  // superseded when that one's final checkpoint is gone or holds another state than it began from.
  const auto remove_encounter = [&](const fs::path& dir, const std::string& why) {
    for (const auto& name : files) remove_stage_outputs(dir / name, false);
    fs::remove_all(dir / "analysis", ec);
    say(ctx, fmt::format("{}: removed the encounter, which {}", dir.string(), why));
  };
  // The first stage's checkpoint of `dir`, read under its lock (held by `lock`); nullopt when
  // absent, locked by another process, unreadable, or of another body.
  const auto read_first = [&](const fs::path& dir, std::optional<StageLock>& lock) -> std::optional<Checkpoint> {
    const std::optional<std::uint64_t> known = seed_of_folder(dir.filename().string());
    if (known && *known != seed) return std::nullopt;
    const fs::path file = dir / files.front();
    const fs::path found = fs::exists(file) ? file : sibling_checkpoint(file, "mid");
    if (!fs::exists(found)) return std::nullopt;
    try {
      LockAttempt attempt = try_lock_stage(file, "");
      if (!attempt.lock) every_folder_checked = false;
      if (!attempt.lock) return std::nullopt;
      lock = std::move(attempt.lock);
      Checkpoint first = read_checkpoint(found);
      if (!known && parse_config(first.config_toml, found.string()).workflow.seed != seed) return std::nullopt;
      return first;
    } catch (const InputError&) {
      return std::nullopt;
    }
  };
  const auto after_of = [](const Checkpoint& c) -> std::optional<std::string> {
    const auto* record = std::get_if<EncounterRecord>(&c.stage.record);
    return record ? record->encounter.after : std::nullopt;
  };
  std::map<fs::path, fs::path> history;  // encounter folder -> the folder of the one it comes after
  for (const auto& dir : folders) {
    std::optional<StageLock> lock;
    const std::optional<Checkpoint> first = read_first(dir, lock);
    if (!first) continue;
    if (const auto after = after_of(*first)) history.emplace(dir, dir.parent_path() / *after);
    else if (first->stage.parent_hash != relaxed_hash) remove_encounter(dir, "branched from another relaxed body");
  }
  std::set<fs::path> settled;
  for (bool progress = true; progress && settled.size() < history.size();) {
    progress = false;
    for (const auto& [dir, before] : history) {
      if (settled.contains(dir) || (history.contains(before) && !settled.contains(before))) continue;
      settled.insert(dir);
      progress = true;
      std::optional<StageLock> lock;
      const std::optional<Checkpoint> first = read_first(dir, lock);  // again, under its lock
      if (!first || !after_of(*first)) continue;
      const fs::path before_final = before / files.back();
      try {
        if (fs::exists(before_final) && state_hash(read_checkpoint(before_final).state) == first->stage.parent_hash)
          continue;
      } catch (const InputError&) {
        continue;  // unreadable: run reports it when it reaches it
      }
      remove_encounter(dir, fmt::format("began from another state of {}", before.filename().string()));
    }
  }
  if (every_folder_checked) write_file_atomically(superseded_check_file(body_dir), relaxed_hash + "\n");
}

WorkflowResult interrupted(WorkflowResult& result) {
  result.interrupted = true;
  return std::move(result);
}

}  // namespace

Config body_chain_config(const Config& config, const fs::path& root, const Encounter* encounter) {
  Config prepared = encounter ? body_config_of(config, *encounter) : config;
  const fs::path body_dir = body_folder(root, config, encounter);
  fs::path parent_file;
  for (const StageKind& kind : stage_kinds()) {
    if (kind.per_encounter) continue;
    if (kind.prepare && !parent_file.empty()) {
      if (!fs::exists(parent_file)) return prepared;  // nothing run yet: the caller says so
      kind.prepare(prepared, read_checkpoint(parent_file), parent_file.string());
    }
    parent_file = stage_file(body_dir, kind);
  }
  return prepared;
}

namespace {

/// A finished body chain: the configuration its prepare steps left (the relax's time step) and
/// its last checkpoint, the relaxed body the encounters branch from; `encounter_config` is
/// `config` at the run's dt * dt_factor, what its encounters run with.
struct BodyChain {
  Config config;
  Checkpoint relaxed;
  fs::path file;
  Config encounter_config;
};

/// Runs (or reuses) the body chain of `config` (the stages that are not per encounter, in table
/// order, each beginning from the one before) in `body_dir`; nothing when interrupted. One process
/// computes each stage, others that need the same version wait.
std::optional<BodyChain> run_body_chain(const RunContext& ctx, const Config& config, const fs::path& body_dir) {
  // Checked before anything is written, and again under the first stage's lock (a process with
  // another body may have written it since: one folder, one body chain, decided under that lock).
  const fs::path first_file = stage_file(body_dir, stage_kinds().front());
  check_same_body(first_file, config);
  test_point_after_body_check();
  fs::create_directories(body_dir);
  BodyChain chain{config, {}, {}, {}};
  std::optional<Checkpoint> body;
  for (const StageKind& kind : stage_kinds()) {
    if (kind.per_encounter) continue;
    if (body) prepare_stage(ctx, kind, chain.config, *body, chain.file);
    const StageJob job{&kind, kind.name(), stage_file(body_dir, kind), body ? &*body : nullptr, chain.file, nullptr};
    StageRunOptions stage_options = workflow_stage_options(ctx);
    if (job.file == first_file) stage_options.check_locked = [&] { check_same_body(first_file, config); };
    StageResult done = run_stage(job, chain.config, std::move(stage_options));
    if (done.outcome == LoopOutcome::interrupted) return std::nullopt;
    body = std::move(done.checkpoint);
    chain.file = job.file;
  }
  chain.relaxed = std::move(*body);
  return chain;
}

}  // namespace

WorkflowResult run_workflow(const Config& config, const WorkflowOptions& options) {
  RunContext ctx;
  ctx.quiet = options.quiet;
  ctx.allow_kernel_change = options.allow_kernel_change;
  ctx.config_file = options.config_file.string();
  fs::create_directories(options.root);
  ctx.status_file = options.root / "status.json";
  WorkflowResult result;

  // Per-encounter stages run for each encounter from the end of its body chain, at dt *
  // dt_factor; the lock of an encounter's last stage also covers its analysis, so processes
  // running different encounters run side by side.
  std::vector<const StageKind*> per_encounter;
  std::vector<fs::path> per_encounter_files;
  for (const StageKind& kind : stage_kinds())
    if (kind.per_encounter) {
      per_encounter.push_back(&kind);
      per_encounter_files.push_back(stage_file("", kind));
    }
  const fs::path encounter_root =
      options.dt_factor == 1.0 ? options.root : options.root / fmt::format("dt{}", options.dt_factor);

  // Each body chain once, when its first encounter needs it (the workflow's own body also with
  // no encounter: --body-only); an encounter folder belongs to the body of the workflow's
  // encounter of that name, an unknown one to the body whose seed its checkpoint names.
  std::map<std::uint64_t, BodyChain> chains;
  std::unordered_map<std::string, std::uint64_t> seed_of_encounter;
  for (const Encounter& e : config.encounters) seed_of_encounter.emplace(e.name, body_seed_of(config, e));
  const auto body_seed_of_folder = [&](const std::string& name) -> std::optional<std::uint64_t> {
    const auto found = seed_of_encounter.find(name);
    return found == seed_of_encounter.end() ? std::nullopt : std::optional<std::uint64_t>(found->second);
  };
  const auto chain_for = [&](const Encounter* spec) -> const BodyChain* {
    const std::uint64_t seed = spec ? body_seed_of(config, *spec) : config.workflow.seed;
    if (auto found = chains.find(seed); found != chains.end()) return &found->second;
    const fs::path body_dir = body_folder(options.root, config, spec);
    std::optional<BodyChain> chain = run_body_chain(ctx, spec ? body_config_of(config, *spec) : config, body_dir);
    if (!chain) return nullptr;
    chain->encounter_config = chain->config;
    if (options.dt_factor != 1.0) scale_time_step(chain->encounter_config, options.dt_factor);
    if (chains.empty())
      if (const auto* relaxed = std::get_if<RelaxRecord>(&chain->relaxed.stage.record)) result.relaxed = *relaxed;
    remove_superseded_encounters(ctx, options.root, body_dir, seed, body_seed_of_folder, per_encounter_files,
                                 state_hash(chain->relaxed.state));
    return &chains.emplace(seed, std::move(*chain)).first->second;
  };
  if (options.encounters.empty() && !chain_for(nullptr)) return interrupted(result);

  // An encounter begins from the end of its body chain, or (a history: `after`) from the final
  // checkpoint of the encounter it comes after, which is run first when it is not among
  // options.encounters (`run --only B` runs A too). The final checkpoints that others begin from
  // are kept here, by name.
  std::set<std::string> begun_from;
  for (const Encounter& e : config.encounters)
    if (e.after) begun_from.insert(*e.after);
  struct Finished {
    Checkpoint checkpoint;
    fs::path file;
  };
  std::map<std::string, Finished> finished;
  std::function<const Finished*(const Encounter&)> run_encounter_of = [&](const Encounter& spec) -> const Finished* {
    if (const auto done = finished.find(spec.name); done != finished.end()) return &done->second;
    const BodyChain* chain = chain_for(&spec);
    if (!chain) return nullptr;
    const Checkpoint* start = &chain->relaxed;
    fs::path parent_file = chain->file;
    if (spec.after) {
      const Encounter* before = config.encounter_or_null(*spec.after);  // validate checked that it exists
      const Finished* done = before ? run_encounter_of(*before) : nullptr;
      if (!done) return nullptr;
      start = &done->checkpoint;
      parent_file = done->file;
    }
    const fs::path dir = encounter_root / spec.name;
    fs::create_directories(dir);
    std::optional<Checkpoint> parent;
    for (const StageKind* kind : per_encounter) {
      const StageJob job{kind, fmt::format("{} {}", kind->name(), spec.name), stage_file(dir, *kind),
                         parent ? &*parent : start, parent_file, &spec};
      StageRunOptions stage_options = workflow_stage_options(ctx);
      if (kind == per_encounter.back()) {
        stage_options.derived = dir / "analysis";
        stage_options.finish = [&](const Checkpoint& done) {
          analyze_if_stale(ctx, job.file, done, dir / "analysis", spec.name, config.analysis.figures);
        };
      }
      StageResult done = run_stage(job, chain->encounter_config, std::move(stage_options));
      if (done.outcome == LoopOutcome::interrupted) return nullptr;
      parent = std::move(done.checkpoint);
      parent_file = job.file;
    }
    Finished& out = finished[spec.name];
    out.checkpoint = std::move(*parent);
    out.file = parent_file;
    return &out;
  };

  for (const auto& spec : options.encounters) {
    const Finished* done = run_encounter_of(spec);
    if (!done) return interrupted(result);
    result.encounters.push_back({spec.name, done->file, encounter_root / spec.name / "analysis",
                                 fracture_summary_line(spec.name, analyze_fractures(done->checkpoint)),
                                 failure_trend_line(spec.name, done->checkpoint)});
    // Only the checkpoints others begin from are kept (a sweep's would fill the memory).
    if (!begun_from.contains(spec.name)) finished.erase(spec.name);
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
