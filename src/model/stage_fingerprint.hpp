#pragma once
// What each stage's result depends on, as text: a stage is redone exactly when its
// fingerprint (or its parent's state) changed. Stored as /checkpoint@fingerprint
// (StageInfo::fingerprint).
#include <string>

#include "model/config.hpp"

namespace tidalcrust {

/// Body identity: seed, softening, interior, shell and cross geometry and stiffnesses. Another
/// value = another body.
std::string build_fingerprint(const Config& config);
/// [stretch] and the force-law keys.
std::string stretch_fingerprint(const Config& config);
/// [relax] (but its checkpoint interval), dt, force-law and failure keys the probe uses.
std::string relax_fingerprint(const Config& config);
/// [encounter] (but its checkpoint interval), the encounter's own table, force-law and failure
/// keys and the encounter time step.
std::string encounter_fingerprint(const Config& config, const Encounter& spec);

/// The first line that differs between two fingerprints, "a -> b", for messages.
std::string first_difference(const std::string& old_text, const std::string& new_text);


}  // namespace tidalcrust
