#include "physics/physical_units.hpp"

#include <fmt/format.h>

#include <cmath>

#include "base/errors.hpp"

namespace tidalcrust {

PhysicalBody body_from_mass_radius(double mass_kg, double radius_km) {
  if (!std::isfinite(mass_kg) || mass_kg <= 0)
    throw InputError(fmt::format("body mass must be a finite number > 0 (kg), got {}", mass_kg));
  if (!std::isfinite(radius_km) || radius_km <= 0)
    throw InputError(fmt::format("body radius must be a finite number > 0 (km), got {}", radius_km));
  return {"custom", mass_kg, radius_km};
}

BodyScales body_scales(const PhysicalBody& body) {
  const ModelUnits u = model_units(body.mass_kg, body.radius_km * 1e3);
  BodyScales s;
  s.e_g_GPa = u.modulus_Pa * 1e-9;
  s.t_grav_s = u.time_s;
  s.density_g_cm3 = u.mean_density_kg_m3 * 1e-3;  // kg/m^3 -> g/cm^3
  s.v_c_km_s = u.speed_m_s * 1e-3;
  return s;
}

}  // namespace tidalcrust
