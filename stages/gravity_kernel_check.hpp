#pragma once
// Which gravity kernel computed a stage, and the refusal to step on under another one
// (docs/determinism.md, "Bits across machines"). The kernel is not part of a stage's fingerprint:
// the same stage computed by another kernel is the same physics, but not the same bits, and a
// mid-stage checkpoint continued under another kernel (a requeued cluster job on another kind of
// node) ends with bits that neither kernel alone gives. So it is recorded (StageInfo::gravity_kernel)
// and checked wherever a stage steps on from a checkpoint.
#include <string>

#include "model/checkpoint.hpp"
#include "model/config.hpp"

namespace tidalcrust {

/// Prepares `checkpoint`, a time-stepping stage about to step on (just begun from its parent, whose
/// kernel it inherited, or read back from the mid-stage checkpoint `source`), to continue under the
/// kernel of `config` ([gravity] kernel, in this build: gravity_kernel_label()). When the recorded
/// kernel gives other bits (same_gravity_bits()), InputError (exit 2), one line naming `source` and
/// both kernels, unless `allow_change`: then the change is appended to
/// StageInfo::gravity_kernel_changes. A recorded "" (no forces yet, or an older file) is never
/// refused. Afterwards the checkpoint records the new kernel, in gravity_kernel and in its stored
/// configuration (config_toml), so the stage runs and resumes with it.
void continue_under_gravity_kernel(Checkpoint& checkpoint, const Config& config, bool allow_change,
                                   const std::string& source);

}  // namespace tidalcrust
