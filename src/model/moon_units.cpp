#include "model/moon_units.hpp"

#include <fmt/format.h>
#include <udunits2.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <memory>
#include <mutex>
#include <numbers>

#include "base/errors.hpp"

namespace tidalcrust {
namespace {

bool equal_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  return true;
}

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

struct UnitDeleter {
  void operator()(ut_unit* unit) const { ut_free(unit); }
};
using UnitPtr = std::unique_ptr<ut_unit, UnitDeleter>;

/// udunits2 is not thread-safe: one unit system, read once, used under this lock.
std::mutex udunits_mutex;

/// The unit system of udunits2's own database (UDUNITS2_XML_PATH, else the one it was built with).
ut_system* unit_system() {
  static ut_system* const system = [] {
    ut_set_error_message_handler(ut_ignore);  // its messages go to stderr; ours name the key
    return ut_read_xml(nullptr);
  }();
  if (!system)
    throw InputError("cannot read the udunits2 units database (package libudunits2-data; or set UDUNITS2_XML_PATH)");
  return system;
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

ModelUnits model_units(double mass_kg, double radius_m) {
  if (!std::isfinite(mass_kg) || mass_kg <= 0)
    throw InputError(fmt::format("body mass must be a finite number > 0 (kg), got {}", mass_kg));
  if (!std::isfinite(radius_m) || radius_m <= 0)
    throw InputError(fmt::format("body radius must be a finite number > 0 (m), got {}", radius_m));
  const double G = gravitational_constant_si, M = mass_kg, R = radius_m;
  ModelUnits u;
  u.mass_kg = M;
  u.radius_m = R;
  u.modulus_Pa = G * M * M / (R * R * R * R);
  u.time_s = std::sqrt(R * R * R / (G * M));
  u.speed_m_s = std::sqrt(G * M / R);
  u.density_kg_m3 = M / (R * R * R);
  u.mean_density_kg_m3 = M / (4.0 / 3.0 * std::numbers::pi * R * R * R);
  u.energy_J = G * M * M / R;
  return u;
}

std::string_view si_unit(Dimension dimension) {
  switch (dimension) {
    case Dimension::length: return "m";
    case Dimension::mass: return "kg";
    case Dimension::density: return "kg/m^3";
    case Dimension::pressure: return "Pa";
    case Dimension::speed: return "m/s";
    case Dimension::time: return "s";
    case Dimension::energy: return "J";
  }
  return "";
}

std::optional<Dimension> dimension_of_si_unit(std::string_view unit) {
  for (Dimension d : all_dimensions)
    if (si_unit(d) == unit) return d;
  return std::nullopt;
}

std::string_view dimension_name(Dimension dimension) {
  switch (dimension) {
    case Dimension::length: return "a length";
    case Dimension::mass: return "a mass";
    case Dimension::density: return "a density";
    case Dimension::pressure: return "a pressure";
    case Dimension::speed: return "a speed";
    case Dimension::time: return "a time";
    case Dimension::energy: return "an energy";
  }
  return "";
}

std::string_view dimension_example(Dimension dimension) {
  switch (dimension) {
    case Dimension::length: return "531 km";
    case Dimension::mass: return "6.17e20 kg";
    case Dimension::density: return "0.93 g/cm3";
    case Dimension::pressure: return "0.9 GPa";
    case Dimension::speed: return "2.0 km/s";
    case Dimension::time: return "3 h";
    case Dimension::energy: return "1e18 J";
  }
  return "";
}

double model_unit(const ModelUnits& units, Dimension dimension) {
  switch (dimension) {
    case Dimension::length: return units.radius_m;
    case Dimension::mass: return units.mass_kg;
    case Dimension::density: return units.density_kg_m3;
    case Dimension::pressure: return units.modulus_Pa;
    case Dimension::speed: return units.speed_m_s;
    case Dimension::time: return units.time_s;
    case Dimension::energy: return units.energy_J;
  }
  return 0;
}

std::string_view model_unit_name(Dimension dimension) {
  switch (dimension) {
    case Dimension::length: return "R";
    case Dimension::mass: return "M";
    case Dimension::density: return "M/R^3";
    case Dimension::pressure: return "e_g";
    case Dimension::speed: return "sqrt(GM/R)";
    case Dimension::time: return "t_grav";
    case Dimension::energy: return "G M^2/R";
  }
  return "";
}

std::optional<Dimension> dimension_of_model_unit(std::string_view name) {
  if (name == "GM^2/R") return Dimension::energy;  // the spelling of report's tables
  for (Dimension d : all_dimensions)
    if (model_unit_name(d) == name) return d;
  return std::nullopt;
}

double model_to_si(const ModelUnits& units, Dimension dimension, double model_value) {
  return model_value * model_unit(units, dimension);
}

double si_to_model(const ModelUnits& units, Dimension dimension, double value_in_si) {
  return value_in_si / model_unit(units, dimension);
}

OutputUnit output_unit(Dimension dimension) {
  switch (dimension) {
    case Dimension::length: return {"km", "_km", 1e3};
    case Dimension::mass: return {"kg", "_kg", 1};
    case Dimension::density: return {"kg/m^3", "_kg_m3", 1};
    case Dimension::pressure: return {"Pa", "_Pa", 1};
    case Dimension::speed: return {"km/s", "_km_s", 1e3};
    case Dimension::time: return {"h", "_h", 3600};
    case Dimension::energy: return {"J", "_J", 1};
  }
  return {};
}

double model_to_output(const ModelUnits& units, Dimension dimension, double model_value) {
  return model_to_si(units, dimension, model_value) / output_unit(dimension).si_per_unit;
}

double output_to_model(const ModelUnits& units, Dimension dimension, double output_value) {
  return si_to_model(units, dimension, output_value * output_unit(dimension).si_per_unit);
}

std::string si_key(std::string_view key, Dimension dimension) {
  return std::string(key) + std::string(output_unit(dimension).key_suffix);
}

double quantity_si(std::string_view text, Dimension dimension, const std::string& where) {
  const auto fail = [&](const std::string& problem) {
    return InputError(fmt::format("{} = \"{}\": {}", where, text, problem));
  };
  const std::string_view s = trimmed(text);
  double number = 0;
  const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), number);
  if (error != std::errc() || end == s.data())
    throw fail(fmt::format("expected a number and a unit, e.g. \"{}\"", dimension_example(dimension)));
  const std::string unit_text(trimmed(std::string_view(end, static_cast<std::size_t>(s.data() + s.size() - end))));
  if (unit_text.empty())
    throw fail(fmt::format("needs a unit of {}, e.g. \"{}\"", dimension_name(dimension), dimension_example(dimension)));
  double si = 0;
  {
    const std::lock_guard lock(udunits_mutex);
    ut_system* system = unit_system();
    const UnitPtr unit(ut_parse(system, unit_text.c_str(), UT_UTF8));
    if (!unit) throw fail(fmt::format("'{}' is not a unit udunits2 knows", unit_text));
    const UnitPtr target(ut_parse(system, std::string(si_unit(dimension)).c_str(), UT_ASCII));
    if (!target) throw InputError(fmt::format("udunits2 does not know the SI unit '{}'", si_unit(dimension)));
    if (ut_are_convertible(unit.get(), target.get()) == 0)
      throw fail(fmt::format("'{}' is not a unit of {} (expected one convertible to {})", unit_text,
                             dimension_name(dimension), si_unit(dimension)));
    cv_converter* converter = ut_get_converter(unit.get(), target.get());
    if (!converter) throw fail(fmt::format("udunits2 cannot convert '{}' to {}", unit_text, si_unit(dimension)));
    si = cv_convert_double(converter, number);
    cv_free(converter);
  }
  if (!std::isfinite(si) || si <= 0) throw fail("must be finite and > 0");
  return si;
}

const std::vector<MoonPreset>& moon_presets() {
  static const std::vector<MoonPreset> presets = [] {
    std::vector<MoonPreset> out;
    for (const PhysicalBody& body : table1_bodies())
      if (body.name != "Mars")  // no icy crust
        out.push_back({body.name, body.mass_kg, body.radius_km * 1e3, "the paper's Table 1, as printed"});
    out.push_back({"Enceladus", 1.080e20, 252.1e3,
                   "mass: Jacobson et al. 2006, AJ 132, 2520; radius: Thomas 2010, Icarus 208, 395"});
    out.push_back({"Europa", 4.80e22, 1560.8e3,
                   "mass: Anderson et al. 1998, Science 281, 2019; radius: Nimmo et al. 2007, Icarus 191, 183"});
    out.push_back({"Mimas", 3.75e19, 198.2e3,
                   "mass: Jacobson et al. 2006, AJ 132, 2520; radius: Thomas 2010, Icarus 208, 395"});
    out.push_back({"Miranda", 6.59e19, 235.8e3,
                   "mass: Jacobson et al. 1992, AJ 103, 2068; radius: Thomas 1988, Icarus 73, 427"});
    return out;
  }();
  return presets;
}

const MoonPreset& find_moon_preset(std::string_view name, const std::string& where) {
  std::string known;
  for (const MoonPreset& preset : moon_presets()) {
    if (equal_ignoring_case(preset.name, name)) return preset;
    known += fmt::format("{}{}", known.empty() ? "" : ", ", preset.name);
  }
  throw InputError(fmt::format("{} = \"{}\": unknown preset (known: {})", where, name, known));
}

PhysicalBody find_named_body(std::string_view name) {
  std::string known;
  for (const auto& body : table1_bodies()) {
    if (equal_ignoring_case(body.name, name)) return body;
    known += (known.empty() ? "" : ", ") + body.name;
  }
  for (const MoonPreset& preset : moon_presets()) {
    if (equal_ignoring_case(preset.name, name)) return {std::string(preset.name), preset.mass_kg, preset.radius_m / 1e3};
    if (known.find(preset.name) == std::string::npos) known += fmt::format(", {}", preset.name);
  }
  throw InputError(fmt::format("unknown body '{}' (known: {})", name, known));
}

MoonScale moon_scale(const MoonConfig& moon, const std::string& origin) {
  MoonScale scale{"custom", moon_model_values(moon, origin).units};
  if (moon.preset) scale.name = std::string(find_moon_preset(*moon.preset, origin + ": moon.preset").name);
  return scale;
}

void check_moon_poisson_ratio(double nu, const std::string& where) {
  if (nu == 0.25) return;
  throw InputError(fmt::format("{} = {}: the random spring network has nu = 1/4 (paper eq. 15, docs/material.md); "
                               "give 0.25 or leave it out",
                               where, nu));
}

MoonModelValues moon_model_values(const MoonConfig& moon, const std::string& origin) {
  const MoonPreset* preset = moon.preset ? &find_moon_preset(*moon.preset, origin + ": moon.preset") : nullptr;
  const auto where = [&](std::string_view key) { return fmt::format("{}: moon.{}", origin, key); };
  // A given value, else the preset's (SI), else none.
  const auto value = [&](const std::optional<std::string>& given, std::string_view key, Dimension dimension,
                         std::optional<double> from_preset) -> std::optional<double> {
    if (given) return quantity_si(*given, dimension, where(key));
    return preset ? from_preset : std::nullopt;
  };
  const auto needed = [&](std::optional<double> v, std::string_view what) {
    if (!v) throw InputError(fmt::format("{}: [moon] needs {} (or a preset)", origin, what));
    return *v;
  };
  const auto one_of = [&](bool a, bool b, std::string_view what) {
    if (a && b) throw InputError(fmt::format("{}: [moon] takes {}, not both", origin, what));
  };
  const MoonPresetMaterial& choice = moon_preset_material;
  one_of(moon.mass.has_value(), moon.mean_density.has_value(), "moon.mass or moon.mean_density");
  one_of(moon.tensile_strength.has_value(), moon.failure_strain.has_value(),
         "moon.tensile_strength or moon.failure_strain");

  const double R = needed(value(moon.radius, "radius", Dimension::length, preset ? preset->radius_m : 0), "radius");
  double M = 0;
  if (moon.mean_density)
    M = 4.0 / 3.0 * std::numbers::pi * R * R * R * quantity_si(*moon.mean_density, Dimension::density, where("mean_density"));
  else
    M = needed(value(moon.mass, "mass", Dimension::mass, preset ? preset->mass_kg : 0), "mass or mean_density");
  MoonModelValues out;
  out.units = model_units(M, R);
  const ModelUnits& u = out.units;
  const double E = needed(value(moon.youngs_modulus, "youngs_modulus", Dimension::pressure, choice.youngs_modulus_Pa),
                          "youngs_modulus");
  const double h = needed(value(moon.crust_thickness, "crust_thickness", Dimension::length,
                                choice.crust_thickness_radii * R),
                          "crust_thickness");
  const double rho_s = needed(value(moon.crust_density, "crust_density", Dimension::density, choice.crust_density_kg_m3),
                              "crust_density");
  const double E_s =
      value(moon.crust_youngs_modulus, "crust_youngs_modulus", Dimension::pressure, choice.crust_youngs_modulus_Pa)
          .value_or(E);
  out.youngs_modulus = E / u.modulus_Pa;
  out.crust_thickness = h / u.radius_m;
  out.crust_density = rho_s / u.density_kg_m3;
  if (E_s != E) out.crust_modulus_2d = E_s / u.modulus_Pa * out.crust_thickness;
  if (moon.failure_strain)
    out.failure_strain = *moon.failure_strain;
  else if (const auto sigma = value(moon.tensile_strength, "tensile_strength", Dimension::pressure, choice.tensile_strength_Pa))
    out.failure_strain = *sigma / E_s;  // the crust fails in tension: its own modulus

  if (moon.spin_period)
    out.spin_angular_velocity =
        2 * std::numbers::pi / si_to_model(u, Dimension::time, quantity_si(*moon.spin_period, Dimension::time, where("spin_period")));
  if (!moon.core_radius) {
    if (moon.core_density || moon.core_youngs_modulus)
      throw InputError(fmt::format("{}: moon.{} needs moon.core_radius", origin,
                                   moon.core_density ? "core_density" : "core_youngs_modulus"));
    return out;
  }
  const double r_c = quantity_si(*moon.core_radius, Dimension::length, where("core_radius"));
  if (!moon.core_density) throw InputError(fmt::format("{}: moon.core_radius needs moon.core_density", origin));
  const double rho_c = quantity_si(*moon.core_density, Dimension::density, where("core_density"));
  const double r_m = R - h;  // the mantle fills the ball under the crust
  if (r_c >= r_m)
    throw InputError(fmt::format("{}: moon.core_radius = \"{}\" must be smaller than R - crust_thickness = {} m", origin,
                                 *moon.core_radius, r_m));
  const double pi = std::numbers::pi;
  const double crust_mass = 4 * pi * R * R * h * rho_s;  // the model's thin crust (resolve_material)
  const double core_mass = 4.0 / 3.0 * pi * r_c * r_c * r_c * rho_c;
  const double mantle_density = (M - crust_mass - core_mass) / (4.0 / 3.0 * pi * (r_m * r_m * r_m - r_c * r_c * r_c));
  if (!(mantle_density > 0))
    throw InputError(fmt::format("{}: moon.core_radius and moon.core_density leave the mantle no mass (crust {:.4g} kg "
                                 "+ core {:.4g} kg >= M = {:.4g} kg)",
                                 origin, crust_mass, core_mass, M));
  out.core_radius = r_c / u.radius_m;
  out.core_density_ratio = rho_c / mantle_density;
  if (moon.core_youngs_modulus)
    out.core_modulus_ratio = quantity_si(*moon.core_youngs_modulus, Dimension::pressure, where("core_youngs_modulus")) / E;
  return out;
}

}  // namespace tidalcrust
