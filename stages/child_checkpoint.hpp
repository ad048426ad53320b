#pragma once
// How every stage after build starts: from its parent checkpoint, with fresh bookkeeping.
#include <string>

#include "model/checkpoint.hpp"
#include "model/config.hpp"

namespace tidalcrust {

/// The parent's body and state with a fresh StageInfo (stage name, parent_hash =
/// state_hash(parent.state), start_step = end_step = the parent's step, not complete), the
/// stage's resolved configuration and empty observables (they belong to the new stage).
Checkpoint child_checkpoint(const Checkpoint& parent, const std::string& stage, const Config& config);

}  // namespace tidalcrust
