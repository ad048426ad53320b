#pragma once
// Checkpoint files: the HDF5 layout of docs/checkpoint-layout.md (valid H5MD 1.1), written
// atomically and reproducibly, read back with full validation, plus the .xdmf sidecar.
#include <cstdint>
#include <filesystem>

#include "model/checkpoint.hpp"

namespace tidalcrust {

/// 2: /observables/timeseries/perturber_offset. 3: typed stage records (/checkpoint/record), the
/// stage clock (@dt, @start_time), hinge stiffness as a body property, no per-spring damping.
/// 4: valid H5MD 1.1 (units, particles_group references, extensible time dimension, labels);
/// the failure log and the timeseries moved from /observables to /checkpoint. 5: an encounter's
/// record stores the shadow rule's shadow_distance. 6: and the griffith rule's flaw_length and
/// growth_strain_factor. 7: and the encounter history's `after` and the orbit's inclination,
/// ascending_node and argument_of_pericenter.
/// Every change of the layout or of how a stored value is derived is a new version with its
/// upgrade step (io/checkpoint_upgrade.cpp); tests/reference/format-4/ must still be read.
inline constexpr std::int64_t checkpoint_format_version = 9;

/// Writes atomically: temporary file in the same folder, flush, fsync, rename, fsync folder.
/// The file carries its integrity record (/integrity: a digest of every object).
/// Never overwrites a valid checkpoint in place. Equal checkpoints give byte-identical files.
/// Also writes the .xdmf sidecar beside it. Throws InputError if the folder is not writable.
void write_checkpoint(const std::filesystem::path& file, const Checkpoint& checkpoint);

/// Reads the file's bytes with plain POSIX calls (a transient EIO, EAGAIN, ESTALE, ETIMEDOUT
/// or ENOMEM is tried again, 4 attempts in all; HDF5 then reads only memory, so an I/O error is
/// never mistaken for a missing group or a file that is not HDF5) and validates: format version (formats oldest_readable_format up to the current one;
/// a newer or older one is an InputError saying which it reads), then the integrity record on
/// the file as stored (every dataset, attribute and link digested and compared with
/// /integrity, io/content_hash.hpp), then, for an older format, the upgrade steps on an
/// in-memory copy (io/checkpoint_upgrade.hpp), then dataset shapes, stage name, indices and
/// state_hash. Throws InputError naming the file and the dataset or attribute for a missing,
/// unreadable, truncated, corrupt or tampered file, or one declaring more than it holds.
Checkpoint read_checkpoint(const std::filesystem::path& file);

/// True if `file` exists and read_checkpoint would succeed (used by restart logic).
bool is_valid_checkpoint(const std::filesystem::path& file);

}  // namespace tidalcrust
