#pragma once
// Pieces shared by the single-stage commands (build, stretch, relax, encounter).
#include <cxxopts.hpp>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>

#include "io/stage_lock.hpp"
#include "model/checkpoint.hpp"
#include "cli/cli_options.hpp"
#include "stages/step_loop.hpp"

namespace tidalcrust {

/// The value of a required option; InputError naming it when missing.
std::string required_option(const cxxopts::ParseResult& parsed, const char* name);
/// The output folder must exist and the name end in .h5 (checked before any work).
void check_output_path(const std::filesystem::path& out);
/// The lock of a single-stage command's output `out` (io/stage_lock.hpp), taken before any work:
/// InputError naming the holder when another process holds it (a stale one is taken over, with
/// a line on stderr). Then what a superseded run left beside `out` is removed: its diagnostic
/// checkpoint and, unless `resuming` (they belong to the run resumed), its mid-stage checkpoint
/// and snapshots; never `out` itself (replaced when the stage is done) nor `from`.
StageLock lock_output(const std::filesystem::path& out, const std::filesystem::path& from, bool resuming);
/// --checkpoint-every, --stop-after-step, --quiet.
void add_loop_options(cxxopts::Options& options);
StepLoopOptions loop_options_for(const cxxopts::ParseResult& parsed, const std::filesystem::path& out,
                                 std::string label, std::int64_t default_interval);
/// Writes the finished stage and removes its mid-stage file; 130 after an interruption.
int finish_stage(LoopOutcome outcome, const Checkpoint& checkpoint, const std::filesystem::path& out,
                 const StepLoopOptions& loop);
/// The configuration for a stage: from the input checkpoint, --config and --set. A mid-stage
/// checkpoint resumes with exactly the configuration it started with, except the gravity kernel
/// (--gravity-kernel, refused by continue_under_gravity_kernel unless it gives the same bits).
Config stage_config(const Checkpoint& input, const std::filesystem::path& from, const CommonOptions& common,
                    bool resuming);
/// What a command that continues a checkpoint (stretch, relax, encounter) starts from.
struct StageInput {
  cxxopts::ParseResult parsed;
  CommonOptions common;
  std::filesystem::path from;  ///< --from, the input checkpoint
  std::filesystem::path out;   ///< --out, checked before any work
  Checkpoint input;            ///< read from `from`, of one of the allowed stages
};

/// Declares the options every such command has (--config, --set, --threads, --dt-factor, --from
/// described by `from_help`, --out, and for a time-stepping stage --checkpoint-every,
/// --stop-after-step, --quiet) beside the command's own, parses the command line, checks --out and
/// reads the input checkpoint, which must be of one of the `allowed` stages (InputError
/// otherwise). Nothing when --help was asked: the help is printed.
std::optional<StageInput> read_stage_input(cxxopts::Options& options, int argc, char** argv, const char* from_help,
                                           bool time_stepping, std::initializer_list<const char*> allowed,
                                           const char* command);

/// InputError unless the input checkpoint is of one of the allowed stages.
void require_stage(const Checkpoint& input, const std::filesystem::path& from,
                   std::initializer_list<const char*> allowed, const char* command);

}  // namespace tidalcrust
