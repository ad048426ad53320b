#pragma once
// Checkpoints of older format versions, read through one small upgrade step per version
// (docs/checkpoint-layout.md, "Format versions and upgrades"). read_checkpoint verifies a file's
// integrity record on the file as stored, then, for an older file, applies the layout steps
// k -> k+1 in order to a writable in-memory copy of its objects, interprets that copy with the
// reader of the current format, verifies the state_hash, and applies the steps' meaning parts
// (values the current program computes differently, e.g. a new fingerprint scheme) to the
// checkpoint read. Writing always writes the current format (checkpoint_format_version).
#include <hdf5.h>

#include <cstdint>

#include "model/checkpoint.hpp"

namespace tidalcrust {

/// The oldest format read_checkpoint upgrades. Formats 1 and 2 (written before 2026-11-29's
/// typed stage records) stored the stage's parameters as untyped scalars, per-spring damping in
/// the evolving state (so in their state_hash) and no stage clock: they cannot be interpreted
/// as the stages of today and are refused.
inline constexpr std::int64_t oldest_readable_format = 3;

/// True when the objects of the open file `root`, of format `version` (oldest_readable_format
/// up to the current one), must be upgraded before they are read: an older version, or a
/// version-4 file written before the objects later added without a version bump (the energy
/// budget, the local failure rule's record fields).
bool needs_layout_upgrade(hid_t root, std::int64_t version);

/// Brings the objects of the writable, open file `root` of format `version` to the current
/// layout, one step per version, then completes what version 4 first lacked. Every step writes
/// the layout of its own target version (the step from 3 to 4 names the objects of format 4, never
/// today's names), so each step stays true when later formats change. Throws h5::Error naming the
/// object it cannot upgrade.
void upgrade_layout(hid_t root, std::int64_t version);

/// The meaning parts of the steps from `version` to the current format, applied to the checkpoint
/// read (after its state_hash is verified). None so far: a change of how the program derives a
/// stored value (a new fingerprint scheme: recompute Checkpoint::stage.fingerprint from its
/// stored configuration) is a format bump whose step has a meaning part.
void upgrade_meaning(Checkpoint& checkpoint, std::int64_t version);

}  // namespace tidalcrust
