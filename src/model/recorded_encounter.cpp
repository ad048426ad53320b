#include "model/recorded_encounter.hpp"

#include <fmt/format.h>

#include <limits>

#include "base/errors.hpp"

namespace tidalcrust {

RecordedEncounter recorded_encounter(const Checkpoint& checkpoint, std::string_view file) {
  if (checkpoint.stage.stage != "encounter")
    throw InputError(fmt::format("{}: stage is '{}', expected an 'encounter' checkpoint", file, checkpoint.stage.stage));
  const auto& scalars = checkpoint.stage.scalars;
  auto required = [&](const char* key) {
    const auto it = scalars.find(key);
    if (it == scalars.end())
      throw InputError(fmt::format("{}: encounter scalar '{}' (/checkpoint) is missing", file, key));
    return it->second;
  };
  auto optional = [&](const char* key) {
    const auto it = scalars.find(key);
    return it == scalars.end() ? std::numeric_limits<double>::quiet_NaN() : it->second;
  };
  RecordedEncounter encounter;
  const auto label = checkpoint.stage.labels.find(encounter_keys::name_label);
  if (label != checkpoint.stage.labels.end()) encounter.name = label->second;
  encounter.perturber_mass = required(encounter_keys::perturber_mass);
  encounter.pericenter = required(encounter_keys::pericenter);
  encounter.pericenter_speed = required(encounter_keys::pericenter_speed);
  encounter.pericenter_time = required(encounter_keys::pericenter_time);
  encounter.min_distance = optional(encounter_keys::perturber_min_distance);
  encounter.speed_at_min = optional(encounter_keys::perturber_speed_at_min);
  return encounter;
}

}  // namespace tidalcrust
