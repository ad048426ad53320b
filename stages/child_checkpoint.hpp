#pragma once
// How every stage after build starts: from its parent checkpoint, with fresh bookkeeping.
#include <fmt/format.h>

#include <initializer_list>

#include "base/errors.hpp"
#include "model/checkpoint.hpp"
#include "model/config.hpp"

namespace tidalcrust {

/// The parent's body and state with a fresh StageInfo: the given (empty) record, which names the
/// stage; parent_hash = state_hash(parent.state); the clock starting at the parent's step and time
/// with the configured time step (integrator.dt); end_step = the parent's step; not complete. The
/// stage's resolved configuration, and empty observables (they belong to the new stage). It keeps
/// the parent's gravity_kernel until it computes forces of its own (gravity_kernel_check.hpp).
Checkpoint child_checkpoint(const Checkpoint& parent, StageRecord record, const Config& config);

/// InputError unless `parent` is a complete checkpoint of stage Parent, for the named stage.
template <typename Parent>
void require_complete(const Checkpoint& parent, const char* stage) {
  if (!std::holds_alternative<Parent>(parent.stage.record) || !parent.stage.complete)
    throw InputError(fmt::format("{} needs a complete '{}' checkpoint, got {} '{}' checkpoint", stage,
                                 stage_name_of<Parent>(),
                                 parent.stage.complete ? "a complete" : "an incomplete (mid-stage)",
                                 parent.stage.name()));
}

}  // namespace tidalcrust
