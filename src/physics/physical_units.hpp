#pragma once
// Physical units of the code units G = M = R = 1 for a real body (paper section 1.1 and
// Table 1): gravitational energy density e_g, gravitational time t_grav, mean density and
// grazing circular speed v_c, for the bodies of Table 1 or any mass and radius, in the units
// Table 1 prints. G, the Table 1 bodies and the formulas live in model/moon_units.hpp.
#include "model/moon_units.hpp"

namespace tidalcrust {

/// What one code unit is worth for a body.
struct BodyScales {
  double e_g_GPa = 0;        ///< e_g = G M^2 / R^4 (eq. 7): unit of moduli and pressure
  double t_grav_s = 0;       ///< t_grav = sqrt(R^3 / G M) (eq. 9): unit of time
  double density_g_cm3 = 0;  ///< mean density 3 M / (4 pi R^3)
  double v_c_km_s = 0;       ///< v_c = sqrt(G M / R) (eq. 6): unit of velocity
};

/// A body of the given mass (kg) and radius (km); InputError unless both are finite and > 0.
PhysicalBody body_from_mass_radius(double mass_kg, double radius_km);

/// e_g, t_grav, mean density and v_c of a body (G = gravitational_constant_si).
BodyScales body_scales(const PhysicalBody& body);

}  // namespace tidalcrust
