#include "physics/encounter_estimates.hpp"

#include <fmt/format.h>

#include <cmath>

#include "base/errors.hpp"

namespace tidalcrust {

EncounterEstimates estimate_encounter(const Encounter& encounter, double youngs_in_e_g) {
  const double m = encounter.perturber_mass;
  const double q = encounter.pericenter;
  const double vq = encounter.pericenter_speed;
  if (!std::isfinite(m) || m < 0)
    throw InputError(fmt::format("perturber mass must be a finite number >= 0 (M), got {}", m));
  if (!std::isfinite(q) || q <= 0)
    throw InputError(fmt::format("pericenter q must be a finite number > 0 (R), got {}", q));
  if (!std::isfinite(vq) || vq <= 0)
    throw InputError(fmt::format("pericenter speed V_q must be a finite number > 0 (v_c), got {}", vq));
  if (!std::isfinite(youngs_in_e_g) || youngs_in_e_g <= 0)
    throw InputError(fmt::format("Young's modulus must be a finite number > 0, got {} e_g", youngs_in_e_g));

  // The tidal impulse per unit (v_c t_grav^-1) without the elastic factor; eq. 5 and eq. 10
  // share it.
  const double tidal = m / (q * q * vq);
  const double compliance = std::sqrt(1.0 / youngs_in_e_g);  // (e_g/E)^(1/2)
  EncounterEstimates e;
  e.delta_v = 2.0 * tidal;
  e.strain = compliance * tidal;
  e.encounter_time = 2.0 * q / vq;
  e.elastic_time = compliance;
  e.time_ratio = q / vq / compliance;
  e.strain_rate = tidal;
  return e;
}

double youngs_in_e_g(double youngs_GPa, const BodyScales& scales) {
  if (!std::isfinite(youngs_GPa) || youngs_GPa <= 0)
    throw InputError(fmt::format("Young's modulus must be a finite number > 0 (GPa), got {}", youngs_GPa));
  return youngs_GPa / scales.e_g_GPa;
}

}  // namespace tidalcrust
