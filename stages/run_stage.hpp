#pragma once
// The one way a stage is computed into its checkpoint file, for `run` (stages/workflow.cpp) and for
// the single-stage commands (cli/stage_command.cpp), in one order:
//   1. lock the file (io/stage_lock.hpp; before anything is read back, removed or begun),
//   2. `run` only: reuse the finished file when its fingerprint and parent match,
//   3. resume a mid-stage checkpoint (the command's --from, or `run`'s matching FILE.mid.h5) or
//      begin anew from the parent (StageKind::begin),
//   4. refuse to step on under another gravity kernel (gravity_kernel_check.hpp),
//   5. remove what a superseded run of the stage left (io/checkpoint_names.hpp),
//   6. run it (a stepping stage; SIGINT/SIGTERM: its mid-stage checkpoint, `interrupted`),
//   7. write it, remove its mid-stage checkpoint, and `finish` (the encounter's analysis), still
//      under the lock.
// Nothing is written or removed before InputError in steps 1-4.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "model/checkpoint.hpp"
#include "model/config.hpp"
#include "stages/stage_kinds.hpp"
#include "stages/step_loop.hpp"

namespace tidalcrust {

/// One stage to compute into `file`.
struct StageJob {
  const StageKind* kind = nullptr;
  std::string label;                     ///< "relax", "encounter T5": messages and progress lines
  std::filesystem::path file;            ///< its final checkpoint
  const Checkpoint* parent = nullptr;    ///< what it begins from (null without parents, or to resume)
  std::filesystem::path parent_file;     ///< the parent's file, for messages
  const Encounter* encounter = nullptr;  ///< a per-encounter stage's encounter (null when resuming)
};

/// How the stage is run: by `run` or by a single-stage command.
struct StageRunOptions {
  /// Another process holding the lock while it computes the same version (same fingerprint and
  /// parent) is waited for (`run`: one line says whom), one computing another version is refused.
  /// Off (the single-stage commands): refused while any other process holds it.
  bool wait_for_same_version = false;
  bool reuse_current = false;  ///< a complete `file` with the same fingerprint and parent is the result
  bool find_resume = false;    ///< resume from `file`'s mid-stage checkpoint when it matches
  /// A mid-stage checkpoint of the stage to resume (read from `resume_file`), with its own
  /// fingerprint and parent.
  std::optional<Checkpoint> resume;
  std::filesystem::path resume_file;
  std::vector<std::filesystem::path> keep;  ///< never removed as superseded outputs
  std::filesystem::path derived;            ///< also removed with superseded outputs (analysis/)
  bool allow_kernel_change = false;         ///< --allow-kernel-change
  std::optional<std::int64_t> checkpoint_interval;  ///< default: StageKind::checkpoint_interval
  std::int64_t stop_after_step = -1;                ///< testing aid (StepLoopOptions)
  bool quiet = false;                               ///< no progress lines
  /// Where the stage's configuration comes from (`run`: the workflow file; a stage command: its
  /// --config file or input checkpoint): an InputError of the stage's begin (a value the stage
  /// finds unusable only once it sees the body, e.g. ocean.bulk_modulus) is given with it first,
  /// unless the message starts with it already. Empty: as thrown.
  std::string config_source;
  std::optional<std::filesystem::path> status_file;
  std::function<void(const std::string&)> say;   ///< stage lines ("relax: up to date (...)"); null: none
  std::function<void(const Checkpoint&)> finish; ///< on the result, still under the lock; null: none
  /// Called as soon as the lock is held, before anything is reused, removed or begun: checks
  /// that must hold under the lock (`run`, first stage: the folder's body, check_same_body), so
  /// that a decision taken before the lock is taken again under it. Null: none.
  std::function<void()> check_locked;
};

struct StageResult {
  /// `interrupted`: stopped by SIGINT/SIGTERM (or stop_after_step) with the mid-stage checkpoint
  /// written, or while waiting for the lock (nothing written, `checkpoint` empty).
  LoopOutcome outcome = LoopOutcome::finished;
  Checkpoint checkpoint;                 ///< the finished stage, or where it stopped
  std::filesystem::path mid_checkpoint;  ///< its mid-stage checkpoint file
};

/// Computes (or reuses, or resumes) the stage of `job` with `config`, in the order above. A stage
/// begun here runs with `config` (prepared by StageKind::prepare by the caller); a resumed one with
/// the configuration it started with (values outside its fingerprint may have changed since) but
/// this run's gravity kernel. InputError for bad input (a lock held by another process, a
/// checkpoint of another kernel, ...); SimulationError on a blow-up (with a diagnostic checkpoint).
StageResult run_stage(const StageJob& job, const Config& config, StageRunOptions options);

/// The fingerprint a stage begun by `job` with `config` records (model/stage_fingerprint.hpp).
std::string job_fingerprint(const StageJob& job, const Config& config);

}  // namespace tidalcrust
