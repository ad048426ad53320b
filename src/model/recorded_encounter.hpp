#pragma once
// The encounter parameters and results that the encounter stage stores in StageInfo (scalars
// and labels), read back by analyze, inspect and compare. The key names live here only.
#include <string>
#include <string_view>

#include "model/checkpoint.hpp"

namespace tidalcrust {

namespace encounter_keys {
inline constexpr const char* perturber_mass = "perturber_mass";                  ///< M2, M
inline constexpr const char* pericenter = "pericenter";                          ///< q, R
inline constexpr const char* pericenter_speed = "pericenter_speed";              ///< V_q, sqrt(GM/R)
inline constexpr const char* pericenter_time = "pericenter_time";                ///< time of closest approach, t_grav
inline constexpr const char* perturber_min_distance = "perturber_min_distance";  ///< R
inline constexpr const char* perturber_speed_at_min = "perturber_speed_at_min";  ///< sqrt(GM/R)
inline constexpr const char* name_label = "encounter";                           ///< label: encounter name
}  // namespace encounter_keys

struct RecordedEncounter {
  std::string name;             ///< "" when the label is absent
  double perturber_mass = 0;    ///< M2, M
  double pericenter = 0;        ///< q, R
  double pericenter_speed = 0;  ///< V_q, sqrt(GM/R)
  double pericenter_time = 0;   ///< t_grav
  double min_distance = 0;      ///< measured closest approach, R (NaN if not stored)
  double speed_at_min = 0;      ///< measured relative speed there (NaN if not stored)
};

/// Throws InputError naming `file` unless the checkpoint is of stage "encounter" and holds the
/// scalars perturber_mass, pericenter, pericenter_speed and pericenter_time.
RecordedEncounter recorded_encounter(const Checkpoint& checkpoint, std::string_view file);

}  // namespace tidalcrust
