#pragma once
// When an encounter writes its snapshot checkpoints (for the hemisphere views of paper
// Figure 6; file names in snapshot_files.hpp): global steps fixed when the encounter begins and
// stored in StageInfo scalars, so that a resumed run writes the same snapshots.
#include <cstdint>
#include <vector>

#include "model/checkpoint.hpp"

namespace tidalcrust {

namespace encounter_snapshot_keys {
inline constexpr const char* count = "snapshot_count";        ///< number of snapshot steps
inline constexpr const char* step_prefix = "snapshot_step_";  ///< + index 0..count-1: global step
}  // namespace encounter_snapshot_keys

/// Stores the snapshot steps (ascending) in stage.scalars.
void store_snapshot_steps(StageInfo& stage, const std::vector<std::int64_t>& steps);

/// The snapshot steps stored in stage.scalars (empty if none). InputError if the count is there
/// but a step is missing.
std::vector<std::int64_t> snapshot_steps(const StageInfo& stage);

}  // namespace tidalcrust
