#include "physics/physical_units.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <numbers>

#include "base/errors.hpp"

namespace tidalcrust {
namespace {

bool equal_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i])))
      return false;
  }
  return true;
}

}  // namespace

const std::vector<PhysicalBody>& table1_bodies() {
  static const std::vector<PhysicalBody> bodies = {
      {"Tethys", 0.62e21, 531.0}, {"Dione", 1.1e21, 561.0},   {"Rhea", 2.3e21, 764.0},
      {"Ariel", 1.3e21, 579.0},   {"Titania", 3.5e21, 788.0}, {"Charon", 1.5e21, 603.0},
      {"Mars", 642e21, 3389.0}};
  return bodies;
}

const PhysicalBody& find_table1_body(std::string_view name) {
  std::string known;
  for (const auto& body : table1_bodies()) {
    if (equal_ignoring_case(body.name, name)) return body;
    known += (known.empty() ? "" : ", ") + body.name;
  }
  throw InputError(fmt::format("unknown body '{}' (Table 1 has: {})", name, known));
}

PhysicalBody body_from_mass_radius(double mass_kg, double radius_km) {
  if (!std::isfinite(mass_kg) || mass_kg <= 0)
    throw InputError(fmt::format("body mass must be a finite number > 0 (kg), got {}", mass_kg));
  if (!std::isfinite(radius_km) || radius_km <= 0)
    throw InputError(fmt::format("body radius must be a finite number > 0 (km), got {}", radius_km));
  return {"custom", mass_kg, radius_km};
}

BodyScales body_scales(const PhysicalBody& body) {
  const double G = gravitational_constant_si;
  const double M = body.mass_kg;
  const double R = body.radius_km * 1e3;  // m
  BodyScales s;
  s.e_g_GPa = G * M * M / (R * R * R * R) * 1e-9;
  s.t_grav_s = std::sqrt(R * R * R / (G * M));
  s.density_g_cm3 = M / (4.0 / 3.0 * std::numbers::pi * R * R * R) * 1e-3;  // kg/m^3 -> g/cm^3
  s.v_c_km_s = std::sqrt(G * M / R) * 1e-3;
  return s;
}

}  // namespace tidalcrust
