#pragma once
// What each stage's result depends on, as text: a stage is redone exactly when its
// fingerprint (or its parent's state) changed. Stored in each checkpoint's labels.
#include <string>

#include "config.hpp"

namespace tidalcrust {

/// Body identity: seed, interior, shell, cross and softening. Another value = another body.
std::string build_fingerprint(const Config& config);
/// build + [stretch]
std::string stretch_fingerprint(const Config& config);
/// stretch + [relax] + dt
std::string relax_fingerprint(const Config& config);
/// relax + [encounter] + the encounter's own table + the encounter time step
std::string encounter_fingerprint(const Config& config, const EncounterSpec& spec);

/// The first line that differs between two fingerprints, "a -> b", for messages.
std::string first_difference(const std::string& old_text, const std::string& new_text);

inline constexpr const char* fingerprint_label = "fingerprint";

}  // namespace tidalcrust
