#include "stages/run_stage.hpp"

#include <fmt/format.h>

#include <chrono>
#include <string_view>
#include <thread>

#include "base/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/checkpoint_file.hpp"
#include "io/checkpoint_names.hpp"
#include "io/stage_lock.hpp"
#include "io/state_hash.hpp"
#include "io/stop_signal.hpp"
#include "model/stage_fingerprint.hpp"
#include "stages/gravity_kernel_check.hpp"

namespace tidalcrust {
namespace {

namespace fs = std::filesystem;

/// How often a process waiting for another one's stage looks again.
constexpr auto lock_poll_interval = std::chrono::milliseconds(100);

void say(const StageRunOptions& options, const std::string& text) {
  if (options.say) options.say(text);
}

/// Locks the stage `file` for computing the version `identity`. At once when it is free (taking
/// over, and saying so on stderr, the lock of a process that died). Held by another process: with
/// wait_for_same_version, waits when it computes the same version or briefly checks the folder
/// (empty identity: workflow.cpp, remove_superseded_encounters), one line saying whom it waits for,
/// and refuses (InputError naming the holder) when it computes another version; without, refuses
/// at once. Nothing when SIGINT/SIGTERM arrive while waiting.
std::optional<StageLock> lock_stage(const StageJob& job, const std::string& identity, const StageRunOptions& options) {
  for (bool waiting = false;; std::this_thread::sleep_for(lock_poll_interval)) {
    LockAttempt attempt = try_lock_stage(job.file, identity);
    if (attempt.lock) {
      if (attempt.lock->taken_over_from()) fmt::print(stderr, "tidalcrust: {}\n", attempt.lock->takeover_note());
      return std::move(attempt.lock);
    }
    const LockHolder& holder = *attempt.holder;
    if (!options.wait_for_same_version)
      throw InputError(fmt::format("{}: is being computed by {} (lock {}); wait for it to finish or use another --out",
                                   job.file.string(), holder.describe(), lock_path(job.file).string()));
    if (holder.pid > 0 && holder.identity != identity && !holder.identity.empty())
      throw InputError(fmt::format(
          "{}: {} is being computed with other values by {} (lock {}); wait for it to finish or use another --out",
          job.file.string(), job.label, holder.describe(), lock_path(job.file).string()));
    if (!waiting && holder.pid > 0) {
      say(options, fmt::format("{}: waiting for {}, which is computing the same {}", job.label, holder.describe(),
                               job.label));
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
  if (existing.stage.complete && same_fingerprint(existing.stage.fingerprint, fingerprint) &&
      existing.stage.parent_hash == parent_hash)
    return existing;
  return std::nullopt;
}

/// A mid-stage checkpoint to resume from, or nothing: none there, or one of another version of
/// the stage (stale: the stage begins again and replaces it). One that cannot be read (an I/O
/// error that persists after read_checkpoint's retries, a damaged file, a format this program
/// does not read) is never taken for absent: InputError naming it, and it is kept (overwriting
/// it could throw away a valid run's progress).
std::optional<Checkpoint> resumable(const fs::path& mid, const std::string& label, const std::string& fingerprint,
                                    const std::string& parent_hash) {
  if (!fs::exists(mid)) return std::nullopt;
  Checkpoint existing;
  try {
    existing = read_checkpoint(mid);
  } catch (const InputError& err) {
    throw InputError(fmt::format("{} (the mid-stage checkpoint of {}: kept; remove it to begin {} again)", err.what(),
                                 label, label));
  }
  if (!same_fingerprint(existing.stage.fingerprint, fingerprint) || existing.stage.parent_hash != parent_hash ||
      existing.stage.complete)
    return std::nullopt;
  return existing;
}

/// kind.begin, its InputError with `source` first (StageRunOptions::config_source).
Checkpoint begin_stage(const StageJob& job, const Config& config, const std::string& source) {
  try {
    return job.kind->begin(job.parent, config, job.encounter);
  } catch (const InputError& err) {
    if (source.empty() || std::string_view(err.what()).starts_with(source)) throw;
    throw InputError(fmt::format("{}: {}", source, err.what()));
  }
}

}  // namespace

std::string job_fingerprint(const StageJob& job, const Config& config) {
  return stage_fingerprint(config, job.kind->id, job.kind->per_encounter ? job.encounter : nullptr);
}

StageResult run_stage(const StageJob& job, const Config& config, StageRunOptions options) {
  const StageKind& kind = *job.kind;
  const std::string fingerprint = options.resume ? options.resume->stage.fingerprint : job_fingerprint(job, config);
  const std::string parent_hash =
      options.resume ? options.resume->stage.parent_hash : (job.parent ? state_hash(job.parent->state) : "");
  const auto lock = lock_stage(job, stage_lock_identity(fingerprint, parent_hash), options);
  StageResult result;
  if (!lock) {
    result.outcome = LoopOutcome::interrupted;
    return result;
  }
  if (options.check_locked) options.check_locked();
  // Holding the lock, nobody else writes this stage's files: the temporaries of its files (and of
  // its derived folder) that a killed process left are removed (those of live processes stay).
  remove_stale_temporaries(job.file.parent_path(), job.file.stem().string() + ".");
  if (!options.derived.empty()) remove_stale_temporaries(options.derived, "");
  if (options.reuse_current)
    if (auto existing = reusable(job.file, fingerprint, parent_hash)) {
      say(options, fmt::format("{}: up to date ({})", job.label, job.file.string()));
      if (options.finish) options.finish(*existing);
      result.checkpoint = std::move(*existing);
      return result;
    }

  if (!kind.stepping()) {
    say(options, fmt::format("{}: {}", job.label, kind.doing(config)));
    remove_stage_outputs(job.file, false, options.keep);
    if (!options.derived.empty()) fs::remove_all(options.derived);
    result.checkpoint = begin_stage(job, config, options.config_source);
    result.checkpoint.stage.fingerprint = fingerprint;
    write_checkpoint(job.file, result.checkpoint);
    if (options.finish) options.finish(result.checkpoint);
    return result;
  }

  StepLoopOptions loop =
      stage_loop_options(job.file, job.label, options.checkpoint_interval.value_or(kind.checkpoint_interval(config)));
  loop.status_file = options.status_file;
  loop.quiet = options.quiet;
  loop.stop_after_step = options.stop_after_step;
  result.mid_checkpoint = loop.mid_checkpoint;
  fs::path resume_file = options.resume_file;
  std::optional<Checkpoint> checkpoint = std::move(options.resume);
  if (!checkpoint && options.find_resume) {
    checkpoint = resumable(loop.mid_checkpoint, job.label, fingerprint, parent_hash);
    resume_file = loop.mid_checkpoint;
  }
  const bool resuming = checkpoint.has_value();
  std::optional<Config> stored;  // a resumed stage's own configuration, with this run's kernel (checked next)
  if (resuming) {
    stored = parse_config(checkpoint->config_toml, resume_file.string() + ":/parameters/config");
    stored->gravity.kernel = config.gravity.kernel;
  } else {
    checkpoint = begin_stage(job, config, options.config_source);
    checkpoint->stage.fingerprint = fingerprint;
  }
  const Config& run_config = stored ? *stored : config;
  continue_under_gravity_kernel(*checkpoint, run_config, options.allow_kernel_change,
                                (resuming ? resume_file : job.parent_file).string());
  remove_stage_outputs(job.file, resuming, options.keep);
  if (!options.derived.empty()) fs::remove_all(options.derived);
  if (resuming)
    say(options, fmt::format("{}: resuming from {} (step {})", job.label, resume_file.string(), checkpoint->state.step));
  result.outcome = kind.run(*checkpoint, run_config, loop, job.file);
  result.checkpoint = std::move(*checkpoint);
  if (result.outcome == LoopOutcome::interrupted) return result;
  write_checkpoint(job.file, result.checkpoint);
  remove_checkpoint_files(loop.mid_checkpoint);
  if (options.finish) options.finish(result.checkpoint);
  return result;
}

}  // namespace tidalcrust
