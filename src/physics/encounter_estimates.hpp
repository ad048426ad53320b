#pragma once
// Order-of-magnitude estimates of a tidal encounter in the impulse approximation (paper
// section 1.1, after Press & Teukolsky 1977). Everything is in code units G = M = R = 1:
// velocities in v_c = sqrt(GM/R), times in t_grav = sqrt(R^3/GM), moduli in e_g = GM^2/R^4.
#include "model/encounter.hpp"
#include "physics/physical_units.hpp"

namespace tidalcrust {

/// Young's modulus of ice from tidal flexure of ice shelves (Vaughan 1995), as the paper uses.
inline constexpr double ice_youngs_modulus_GPa = 0.9;

/// The encounter of the section 1.1 estimates when none is given: an equal-mass perturber on a
/// parabolic orbit grazing at q = 2 R (V_q = sqrt(2 G (M + M2)/q) = sqrt(2)).
inline Encounter grazing_parabolic_encounter() { return encounter_of("grazing", 1.0, 2.0, 1.4142135623730951); }

struct EncounterEstimates {
  double delta_v = 0;        ///< eq. 3: Delta v = 2 m R / (q^2 V_q), v_c (Press's eta if parabolic)
  double strain = 0;         ///< eq. 5: (e_g/E)^(1/2) (R/q)^2 (m/M) (v_c/V_q)
  double encounter_time = 0; ///< eq. 2: t_enc = 2 q / V_q, t_grav
  double elastic_time = 0;   ///< eq. 8: t_elas = (e_g/E)^(1/2) t_grav, t_grav
  /// eq. 11 as printed: (q/R) (v_c/V_q) (E/e_g)^(1/2). Note it equals encounter_time /
  /// elastic_time / 2: the paper's eq. 11 takes t_enc ~ q/V_q where eq. 2 has 2q/V_q.
  double time_ratio = 0;
  double strain_rate = 0;    ///< eq. 10: strain / t_elas = (R/q)^2 (m/M) (v_c/V_q), 1/t_grav
};

/// Estimates for Young's modulus E given in units of e_g. InputError unless m >= 0, q > 0,
/// V_q > 0 and E > 0 (all finite).
EncounterEstimates estimate_encounter(const Encounter& encounter, double youngs_in_e_g);

/// Young's modulus (GPa) in units of this body's e_g.
double youngs_in_e_g(double youngs_GPa, const BodyScales& scales);

}  // namespace tidalcrust
