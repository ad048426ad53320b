#pragma once
// One encounter (paper Table 4): the perturber's mass and its two-body orbit, named. The same type
// is a [[encounters]] table of the configuration, what an encounter checkpoint records
// (stage_records.hpp), and the input of the impulse estimates (physics/encounter_estimates.hpp).
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

namespace tidalcrust {

/// V_q of a parabolic orbit (zero energy) with pericenter q about the body of mass M = 1:
/// sqrt(2 (1 + M2) / q), sqrt(GM/R). The one default speed: an [[encounters]] table, a [sweep]
/// and `encounter --m2 --q` without a speed all fly the perturber on this orbit.
inline double parabolic_speed(double perturber_mass, double pericenter) {
  return std::sqrt(2.0 * (1.0 + perturber_mass) / pericenter);
}

struct Encounter {
  std::string name;                      ///< folder and label of the encounter
  double perturber_mass = 0.5;           ///< M2, M
  double pericenter = 1.84;              ///< q, R (distance of closest approach on the two-body orbit)
  /// V_q, sqrt(GM/R) (relative speed at pericenter); an [[encounters]] table without it gets
  /// parabolic_speed of its own M2 and q (parse_config), this default is that of the defaults.
  double pericenter_speed = parabolic_speed(0.5, 1.84);
  std::optional<double> failure_strain;  ///< eps_S for this encounter (T1 uses 0.002); none: shell.failure_strain
  /// Relaxation interval of the local failure rule for this encounter (L_S/V_SP); none:
  /// encounter.relaxation_crossings.
  std::optional<double> relaxation_crossings;
  /// Seed of the body this encounter branches from (workflow.seed of its own body chain, in the
  /// output folder's body-seed<N>/); none: the workflow's body (body/, workflow.seed). An
  /// [ensemble] that varies the body sets it for its members (docs/ensembles.md).
  std::optional<std::uint64_t> body_seed;
  bool operator==(const Encounter&) const = default;
};

}  // namespace tidalcrust
