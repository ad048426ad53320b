#pragma once
// What each stage's result depends on, as text: a stage is redone exactly when its
// fingerprint (or its parent's state) changed. Stored as /checkpoint@fingerprint
// (StageInfo::fingerprint).
//
// Derived from the key descriptions (model/config.cpp): every key declares the stages whose
// results it changes (KeyInfo::read_by), and a stage's fingerprint is one line
// "section.key = value" per key it reads, in to_toml order; an optional key only when set. A
// stage that runs one encounter (`own`) reads the keys of that [[encounters]] table, written as
// the table; any other stage reads the keys it declares of every encounter of the configuration,
// as "encounters.NAME.key = value" (the stability probe of relax: each encounter's eps_S).
// Each later stage also records its parent's state_hash, so a fingerprint only needs what the
// stage itself reads.
#include <string>

#include "model/checkpoint.hpp"
#include "model/config.hpp"

namespace tidalcrust {

/// The fingerprint of `stage` run with `config` (and, for a stage that runs one encounter, `own`).
std::string stage_fingerprint(const Config& config, StageId stage, const Encounter* own = nullptr);

/// Whether two fingerprints name the same values: the same lines in any order, each without its
/// trailing comment ("  # ..."). Fingerprints written before they were derived from the key
/// descriptions (sections in another order, the [[encounters]] table with unit comments), and
/// body-stage fingerprints that named the encounter holding a value ("encounters.T1.failure_strain",
/// before 2026-12-06; now "encounters.*.failure_strain", once per distinct value), equal today's
/// when the values are equal.
bool same_fingerprint(const std::string& a, const std::string& b);

/// The first line of `new_text` that `old_text` lacks, as "'old line of that key' -> 'new line'"
/// (or "'old line' -> ''" for a key only `old_text` has), for messages; "" when the two are the
/// same fingerprint.
std::string first_difference(const std::string& old_text, const std::string& new_text);

/// The fingerprint today's code gives the stage of `checkpoint`, from its stored configuration
/// (config_toml) and, for an encounter, its [[encounters]] table of the recorded name in that
/// configuration (else the recorded encounter: name, M2, q, V_q). For a checkpoint format upgrade
/// step (io/checkpoint_file.cpp) when the fingerprint text changes: the step replaces the stored
/// fingerprint by this one when the stored one is not empty. InputError when the stored
/// configuration does not parse.
std::string recomputed_fingerprint(const Checkpoint& checkpoint, const std::string& origin);

}  // namespace tidalcrust
