#pragma once
// The 128-bit fingerprint of a state (docs/determinism.md): XXH3-128 of the canonical
// little-endian bytes of time, step, positions, velocities, spring rest lengths, stiffnesses,
// failed flags, hinge rest angles and perturber state. Equal hashes = bitwise identical runs.
#include <string>

#include "model/state.hpp"

namespace tidalcrust {

/// 32 lowercase hex digits.
std::string state_hash(const State& state);

}  // namespace tidalcrust
