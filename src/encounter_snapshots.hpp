#pragma once
// Snapshot checkpoints of an encounter (for the hemisphere views of paper Figure 6): full
// "encounter" checkpoints written mid-stage beside the encounter's output file, at steps fixed
// when the encounter begins and stored in StageInfo scalars, so that analyze finds them.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "checkpoint.hpp"

namespace tidalcrust {

namespace encounter_snapshot_keys {
inline constexpr const char* count = "snapshot_count";        ///< number of snapshot steps
inline constexpr const char* step_prefix = "snapshot_step_";  ///< + index 0..count-1: global step
}  // namespace encounter_snapshot_keys

/// The snapshot of `output` (e.g. "dir/ENC.h5") at global step `step`: "dir/ENC.snap-<step>.h5"
/// (decimal step, no padding).
std::filesystem::path encounter_snapshot_path(const std::filesystem::path& output, std::int64_t step);

/// Stores the snapshot steps (ascending) in stage.scalars.
void store_snapshot_steps(StageInfo& stage, const std::vector<std::int64_t>& steps);

/// The snapshot steps stored in stage.scalars (empty if none). InputError if the count is there
/// but a step is missing.
std::vector<std::int64_t> snapshot_steps(const StageInfo& stage);

}  // namespace tidalcrust
