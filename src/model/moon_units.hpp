#pragma once
// A moon in SI (docs/moon.md): the one home of the conversion between SI and the model's units
// G = M = R = 1 (paper section 1.1: e_g = G M^2 / R^4, eq. 7; t_grav = sqrt(R^3 / G M), eq. 9;
// v_c = sqrt(G M / R), eq. 6), of quantities written with their unit ("531 km", read by udunits2),
// of the bodies of the paper's Table 1 and of the [moon] presets with their sources.
#include <optional>
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

/// The bodies of Table 1 (Tethys, Dione, Rhea, Ariel, Titania, Charon, Mars) with mass and
/// radius exactly as printed there (mass to two significant digits, 10^21 kg).
const std::vector<PhysicalBody>& table1_bodies();

/// The Table 1 body of this name, compared case-insensitively; InputError listing the known
/// names otherwise.
const PhysicalBody& find_table1_body(std::string_view name);

/// A body by name for `estimate --body`: a Table 1 body, else a [moon] preset (mass and radius;
/// compared case-insensitively); InputError listing every known name otherwise.
PhysicalBody find_named_body(std::string_view name);

/// What one model unit is worth in SI for a body of mass M and radius R (G = gravitational_constant_si).
struct ModelUnits {
  double mass_kg = 0;        ///< M
  double radius_m = 0;       ///< R
  double modulus_Pa = 0;     ///< e_g = G M^2 / R^4 (eq. 7): moduli, pressures, strengths
  double time_s = 0;         ///< t_grav = sqrt(R^3 / (G M)) (eq. 9)
  double speed_m_s = 0;      ///< v_c = sqrt(G M / R) (eq. 6)
  double density_kg_m3 = 0;  ///< M / R^3 (the mean density is 3 / (4 pi) of it)
  double mean_density_kg_m3 = 0;  ///< 3 M / (4 pi R^3)
  double energy_J = 0;       ///< G M^2 / R = M v_c^2: energies
};
/// The model units of a body; InputError unless M and R are finite and > 0.
ModelUnits model_units(double mass_kg, double radius_m);

/// What a quantity with a unit measures.
enum class Dimension { length, mass, density, pressure, speed, time, energy };
/// Every dimension, in declaration order.
inline constexpr Dimension all_dimensions[] = {Dimension::length, Dimension::mass,  Dimension::density,
                                               Dimension::pressure, Dimension::speed, Dimension::time,
                                               Dimension::energy};
/// The SI unit a quantity of `dimension` is converted to ("m", "kg", "kg/m^3", "Pa", "m/s", "s", "J").
std::string_view si_unit(Dimension dimension);
/// The dimension whose si_unit is `unit`; none for another text ("-", "R", ...).
std::optional<Dimension> dimension_of_si_unit(std::string_view unit);
/// "a length", "a mass", ...: for messages.
std::string_view dimension_name(Dimension dimension);
/// An example value of the dimension ("531 km"), for messages and docs.
std::string_view dimension_example(Dimension dimension);
/// One model unit of `dimension` for `units`, in SI (R, M, M/R^3, e_g, v_c, t_grav, G M^2/R).
double model_unit(const ModelUnits& units, Dimension dimension);
/// The name of the model unit of `dimension` as the output writes it beside a value ("R", "M",
/// "M/R^3", "e_g", "sqrt(GM/R)", "t_grav", "G M^2/R").
std::string_view model_unit_name(Dimension dimension);
/// The dimension of a model unit named as the output writes it (model_unit_name; also "GM^2/R"
/// and "G M^2/R"); none for another text ("1", "deg", "e_g R", ...).
std::optional<Dimension> dimension_of_model_unit(std::string_view name);

/// A model value in SI and back: value * model_unit, value / model_unit.
double model_to_si(const ModelUnits& units, Dimension dimension, double model_value);
double si_to_model(const ModelUnits& units, Dimension dimension, double value_in_si);

/// The unit the output in SI writes a quantity of `dimension` in (docs/moon.md, "Output in SI"):
/// lengths in km, masses in kg, densities in kg/m^3, moduli in Pa, speeds in km/s, times in hours,
/// energies in J.
struct OutputUnit {
  std::string_view symbol;      ///< "km", "kg", "kg/m^3", "Pa", "km/s", "h", "J"
  std::string_view key_suffix;  ///< what a JSON key or CSV column in it ends with: "_km", ..., "_h", "_J"
  double si_per_unit = 1;       ///< 1e3 for km, 3600 for h
};
OutputUnit output_unit(Dimension dimension);
/// A model value in the output unit of its dimension, and back.
double model_to_output(const ModelUnits& units, Dimension dimension, double model_value);
double output_to_model(const ModelUnits& units, Dimension dimension, double output_value);
/// `key` with the suffix of the output unit of `dimension`: si_key("pericenter", length) = "pericenter_km".
std::string si_key(std::string_view key, Dimension dimension);

/// The SI value of a number followed by a unit ("0.9 GPa", "6.17e20 kg", "0.93 g/cm3"), converted
/// by udunits2 (ut_parse of the unit, ut_are_convertible and ut_get_converter to si_unit).
/// InputError "<where> = "<text>": <problem>" (one line) for a missing number or unit, a unit
/// udunits2 does not know, one of another dimension, or a value that is not finite and > 0.
double quantity_si(std::string_view text, Dimension dimension, const std::string& where);

/// A [moon] preset: mass and radius with their published source. The material is the same model
/// choice for every preset (moon_preset_material; docs/moon.md).
struct MoonPreset {
  std::string_view name;
  double mass_kg;
  double radius_m;
  std::string_view source;  ///< of mass and radius
};
/// The presets: the paper's Table 1 moons (mass and radius as printed there, table1_bodies), then
/// Enceladus, Europa, Mimas, Miranda.
const std::vector<MoonPreset>& moon_presets();
/// The preset of this name, compared case-insensitively; InputError "<where>: unknown preset ..."
/// listing the names otherwise.
const MoonPreset& find_moon_preset(std::string_view name, const std::string& where);

/// The material every preset gives (SI), a model choice from the paper (section 1.2, 2.5; docs/moon.md).
struct MoonPresetMaterial {
  double youngs_modulus_Pa = 9e9;        ///< solid ice (an order of magnitude above Vaughan 1995's 0.9 GPa)
  double crust_youngs_modulus_Pa = 0.9e9;///< the effective modulus of ice shelves (Vaughan 1995)
  double crust_thickness_radii = 0.02;   ///< h_S = 0.02 R, the paper's simulated crust
  double crust_density_kg_m3 = 930;      ///< ice Ih at about 100 K
  double tensile_strength_Pa = 1e6;      ///< ice (paper section 1.2: a few MPa)
};
inline constexpr MoonPresetMaterial moon_preset_material{};

/// The [moon] table (docs/moon.md): a moon in SI, every dimensional value a string with its unit.
/// Given, it fills [material] and [core] in model units (moon_model_values).
struct MoonConfig {
  std::optional<std::string> preset;              ///< a name of moon_presets(), any case
  std::optional<std::string> radius;              ///< R, a length
  std::optional<std::string> mass;                ///< M, a mass (or mean_density)
  std::optional<std::string> mean_density;        ///< 3 M / (4 pi R^3) (or mass)
  std::optional<std::string> youngs_modulus;      ///< E_I, the interior's, a pressure
  std::optional<std::string> crust_thickness;     ///< h_S, a length
  std::optional<std::string> crust_density;       ///< rho_S, a density
  std::optional<std::string> crust_youngs_modulus;///< E_S; default E_I
  std::optional<std::string> tensile_strength;    ///< sigma_t: eps_S = sigma_t / E_S (or failure_strain)
  std::optional<double> failure_strain;           ///< eps_S (or tensile_strength)
  std::optional<std::string> core_radius;         ///< r_c, a length (optional core)
  std::optional<std::string> core_density;        ///< rho_c, with core_radius
  std::optional<std::string> core_youngs_modulus; ///< E_c; default E_I
  std::optional<std::string> spin_period;         ///< P, the rotation period, a time (optional spin)
  bool given() const {
    return preset || radius || mass || mean_density || youngs_modulus || crust_thickness || crust_density ||
           crust_youngs_modulus || tensile_strength || failure_strain || core_radius || core_density ||
           core_youngs_modulus || spin_period;
  }
};

/// The values a [moon] table sets, in model units, as a user would write them in [material]
/// (youngs_modulus e_g, crust_thickness R, crust_density M/R^3; crust_modulus_2d = E_S h_S in
/// e_g R when the crust's modulus is not the interior's; failure_strain) and [core] (radius R,
/// density_ratio rho_c / rho_mantle, modulus_ratio E_c / E_I).
struct MoonModelValues {
  ModelUnits units;
  double youngs_modulus = 0;
  double crust_thickness = 0;
  double crust_density = 0;
  std::optional<double> crust_modulus_2d;
  std::optional<double> failure_strain;
  std::optional<double> core_radius;
  std::optional<double> core_density_ratio;
  std::optional<double> core_modulus_ratio;
  /// [spin]'s angular_velocity Omega = 2 pi t_grav / P, rad/t_grav (with spin_period)
  std::optional<double> spin_angular_velocity;
};
/// The model values of `moon`: its given values, the rest from its preset. The mantle density of
/// a core is what the crust (4 pi R^2 h_S rho_S, the model's) and the core leave of M in the ball
/// under the crust. InputError "<origin>: moon.<key> ..." naming the key for a bad value, a missing
/// one, two alternatives given together (mass and mean_density, tensile_strength and
/// failure_strain), or a core that leaves the mantle no mass. (resolve_moon checks the spin's range.)
MoonModelValues moon_model_values(const MoonConfig& moon, const std::string& origin);

/// The moon whose units a [moon] workflow's output is also written in (docs/moon.md, "Output in SI").
struct MoonScale {
  std::string name;  ///< the preset's name as listed ("Tethys"); "custom" for one given by radius and mass
  ModelUnits units;
};
/// The scale of `moon` (moon_model_values' units, the preset's name); InputError as moon_model_values.
MoonScale moon_scale(const MoonConfig& moon, const std::string& origin);

/// Refuses a Poisson ratio the random spring network cannot have: it has nu = 1/4 (paper eq. 15,
/// docs/material.md). InputError "<where> = <nu>: ..." unless `nu` is 0.25.
void check_moon_poisson_ratio(double nu, const std::string& where);

}  // namespace tidalcrust
