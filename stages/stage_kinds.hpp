#pragma once
// The stages of the pipeline as values: one row per kind of stage (stage_kinds.cpp). From this
// table come the workflow's chain (workflow.cpp), the single-stage commands `tidalcrust
// build|stretch|relax|encounter` (cli/stage_command.cpp), their names, summaries and options, and
// the one way a stage is computed into its file (run_stage.hpp). A stage added later costs its own
// files plus one row here (docs/architecture.md, "Where to add: a stage").
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "model/checkpoint.hpp"
#include "model/config.hpp"
#include "stages/step_loop.hpp"

namespace tidalcrust {

struct StageKind {
  /// Its record (model/stage_records.hpp), and with it its name: stage_name(id).
  StageId id;
  /// One line for `tidalcrust --help` and the head of the command's --help.
  const char* summary;
  /// It begins from a complete checkpoint of one of these stages; none: from the configuration
  /// alone (build). In the workflow it begins from the stage before it in the chain.
  StageSet parents;
  /// It runs once per encounter of the workflow, after the body chain (build, stretch, relax),
  /// reading its [[encounters]] table; its command takes the encounter options (--encounter NAME
  /// or --m2 M --q Q --vq V, and --failure-strain).
  bool per_encounter;
  /// An instant stage (run is null): the whole stage. A stepping stage: its fresh checkpoint at
  /// its first step (child_checkpoint.hpp). `parent` is null for a stage without parents,
  /// `encounter` null for a stage that is not per encounter. InputError for bad input.
  Checkpoint (*begin)(const Checkpoint* parent, const Config& config, const Encounter* encounter);
  /// A stepping stage: runs or resumes `checkpoint` until complete (step_loop.hpp); `file` is its
  /// final checkpoint, beside which it may write snapshots. Null for an instant stage.
  LoopOutcome (*run)(Checkpoint& checkpoint, const Config& config, const StepLoopOptions& options,
                     const std::filesystem::path& file);
  /// A stepping stage: the configuration key of its mid-stage checkpoint interval
  /// ("relax.checkpoint_interval": steps, 0 for none; a key that changes no result). Null for an
  /// instant stage.
  const char* checkpoint_interval_key;
  /// Before it begins anew (not on a resume): adapts the configuration to the parent and returns a
  /// line to print ("" for none; one starting with "warning" goes to stderr). The configuration it
  /// leaves is the one this stage and every later one run with. Null: nothing to adapt.
  std::string (*prepare)(Config& config, const Checkpoint& parent, const std::string& parent_file);
  /// An instant stage: what `run` says it is doing ("building the body").
  std::string (*doing)(const Config& config);
  /// What its command prints about the finished checkpoint ("642 particles, ..."); null: its step
  /// and time.
  std::string (*written)(const Checkpoint& done);

  const char* name() const { return stage_name(id); }
  bool stepping() const { return run != nullptr; }
  /// Its mid-stage checkpoint interval in `config` (0 for an instant stage).
  std::int64_t checkpoint_interval(const Config& config) const;
};

/// Every kind of stage, in pipeline order (the order of StageRecord's alternatives).
std::span<const StageKind> stage_kinds();
/// The row of a stage.
const StageKind& stage_kind(StageId id);

}  // namespace tidalcrust
