#pragma once
// One encounter (paper Table 4): the perturber's mass and its two-body orbit, named. The same type
// is a [[encounters]] table of the configuration, what an encounter checkpoint records
// (stage_records.hpp), and the input of the impulse estimates (physics/encounter_estimates.hpp).
#include <optional>
#include <string>

namespace tidalcrust {

struct Encounter {
  std::string name;                      ///< folder and label of the encounter
  double perturber_mass = 0.5;           ///< M2, M
  double pericenter = 1.84;              ///< q, R (distance of closest approach on the two-body orbit)
  double pericenter_speed = 1.60;        ///< V_q, sqrt(GM/R) (relative speed at pericenter)
  std::optional<double> failure_strain;  ///< eps_S for this encounter (T1 uses 0.002); none: shell.failure_strain
  /// Relaxation interval of the local failure rule for this encounter (L_S/V_SP); none:
  /// encounter.relaxation_crossings.
  std::optional<double> relaxation_crossings;
  bool operator==(const Encounter&) const = default;
};

}  // namespace tidalcrust
