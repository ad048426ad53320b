#pragma once
// Physical units of the code units G = M = R = 1 for a real body (paper section 1.1 and
// Table 1): gravitational energy density e_g, gravitational time t_grav, mean density and
// grazing circular speed v_c, for the bodies of Table 1 or any mass and radius.
#include <string>
#include <string_view>
#include <vector>

namespace tidalcrust {

/// Newton's constant in SI units (m^3 kg^-1 s^-2), the value the paper's Table 1 implies.
inline constexpr double gravitational_constant_si = 6.674e-11;

/// A body of mass and radius; Table 1 bodies carry their name, others "custom".
struct PhysicalBody {
  std::string name;
  double mass_kg = 0;
  double radius_km = 0;
};

/// What one code unit is worth for a body.
struct BodyScales {
  double e_g_GPa = 0;        ///< e_g = G M^2 / R^4 (eq. 7): unit of moduli and pressure
  double t_grav_s = 0;       ///< t_grav = sqrt(R^3 / G M) (eq. 9): unit of time
  double density_g_cm3 = 0;  ///< mean density 3 M / (4 pi R^3)
  double v_c_km_s = 0;       ///< v_c = sqrt(G M / R) (eq. 6): unit of velocity
};

/// The bodies of Table 1 (Tethys, Dione, Rhea, Ariel, Titania, Charon, Mars) with mass and
/// radius exactly as printed there (mass to two significant digits, 10^21 kg).
const std::vector<PhysicalBody>& table1_bodies();

/// The Table 1 body of this name, compared case-insensitively; InputError listing the known
/// names otherwise.
const PhysicalBody& find_table1_body(std::string_view name);

/// A body of the given mass (kg) and radius (km); InputError unless both are finite and > 0.
PhysicalBody body_from_mass_radius(double mass_kg, double radius_km);

/// e_g, t_grav, mean density and v_c of a body (G = gravitational_constant_si).
BodyScales body_scales(const PhysicalBody& body);

}  // namespace tidalcrust
