// A moon in SI (issue 25, docs/moon.md): quantities with units read by udunits2, the conversion
// to G = M = R = 1 (model/moon_units.hpp), the presets, and the [moon] table of a workflow that
// fills [material] and [core].
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "base/errors.hpp"
#include "model/config.hpp"
#include "model/moon_units.hpp"
#include "support/files.hpp"

using namespace tidalcrust;

namespace {

/// The message of the InputError `f` throws ("" when it throws none).
template <class F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

/// |a - b| in units in the last place of b.
double ulps(double a, double b) { return std::abs(a - b) / (std::nextafter(std::abs(b), INFINITY) - std::abs(b)); }

/// The round trip's tolerance: SI / unit * unit is two roundings, and a unit such as e_g five more.
constexpr double round_trip_ulps = 4;

const char* const moon_toml = R"(
[workflow]
name = "moon"
[moon]
preset = "TeThYs"
crust_thickness = "10.6 km"
[resolution]
shell_level = 2
[[encounters]]
name = "T5"
perturber_mass = 0.5
pericenter = 1.84
pericenter_speed = 1.6
)";

}  // namespace

TEST(MoonUnits, QuantitiesAreConvertedToSiByUdunits) {
  EXPECT_DOUBLE_EQ(quantity_si("531 km", Dimension::length, "k"), 531e3);
  EXPECT_DOUBLE_EQ(quantity_si("6.17e20 kg", Dimension::mass, "k"), 6.17e20);
  EXPECT_DOUBLE_EQ(quantity_si("0.93 g/cm3", Dimension::density, "k"), 930);
  EXPECT_DOUBLE_EQ(quantity_si("0.9 GPa", Dimension::pressure, "k"), 0.9e9);
  EXPECT_DOUBLE_EQ(quantity_si(" 1 MPa ", Dimension::pressure, "k"), 1e6);
  EXPECT_DOUBLE_EQ(quantity_si("2.0 km/s", Dimension::speed, "k"), 2e3);
  EXPECT_DOUBLE_EQ(quantity_si("20km", Dimension::length, "k"), 20e3);
}

TEST(MoonUnits, BadQuantitiesAreOneLineErrorsNamingTheKey) {
  for (const auto& [text, dimension, problem] : std::initializer_list<std::tuple<const char*, Dimension, const char*>>{
           {"0.9 GPaa", Dimension::pressure, "'GPaa' is not a unit udunits2 knows"},
           {"5 kg", Dimension::length, "'kg' is not a unit of a length"},
           {"531", Dimension::length, "needs a unit of a length"},
           {"km", Dimension::length, "expected a number and a unit"},
           {"-3 km", Dimension::length, "must be finite and > 0"}}) {
    const std::string message = input_error([&] { quantity_si(text, dimension, "f.toml: moon.radius"); });
    EXPECT_NE(message.find("f.toml: moon.radius = \"" + std::string(text) + "\": " + problem), std::string::npos)
        << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// Every preset, SI -> model -> SI, each value to within round_trip_ulps of what it was.
TEST(MoonUnits, EveryPresetRoundTripsSiToModelToSi) {
  const MoonPresetMaterial& m = moon_preset_material;
  ASSERT_EQ(moon_presets().size(), 10u);
  for (const MoonPreset& preset : moon_presets()) {
    SCOPED_TRACE(std::string(preset.name));
    MoonConfig moon;
    moon.preset = std::string(preset.name);
    const MoonModelValues v = moon_model_values(moon, "test");
    const ModelUnits& u = v.units;
    EXPECT_EQ(u.mass_kg, preset.mass_kg);
    EXPECT_EQ(u.radius_m, preset.radius_m);
    EXPECT_LE(ulps(v.youngs_modulus * model_unit(u, Dimension::pressure), m.youngs_modulus_Pa), round_trip_ulps);
    EXPECT_LE(ulps(v.crust_thickness * model_unit(u, Dimension::length), m.crust_thickness_radii * preset.radius_m),
              round_trip_ulps);
    EXPECT_LE(ulps(v.crust_density * model_unit(u, Dimension::density), m.crust_density_kg_m3), round_trip_ulps);
    ASSERT_TRUE(v.crust_modulus_2d && v.failure_strain);
    const double crust_modulus = *v.crust_modulus_2d / v.crust_thickness * model_unit(u, Dimension::pressure);
    EXPECT_LE(ulps(crust_modulus, m.crust_youngs_modulus_Pa), round_trip_ulps);
    EXPECT_LE(ulps(*v.failure_strain * m.crust_youngs_modulus_Pa, m.tensile_strength_Pa), round_trip_ulps);
    // e_g, t_grav and v_c of eqs. 7, 9, 6 agree: v_c = R / t_grav, e_g = (M / R^3) v_c^2.
    EXPECT_LE(ulps(u.speed_m_s, u.radius_m / u.time_s), round_trip_ulps);
    EXPECT_LE(ulps(u.modulus_Pa, u.density_kg_m3 * u.speed_m_s * u.speed_m_s), round_trip_ulps);
  }
}

// The output in SI (docs/moon.md, "Output in SI"): for every preset and every kind of quantity,
// SI -> model -> SI, model -> SI -> model and the output unit (km, h, km/s, ...) -> model -> output
// unit each come back to within round_trip_ulps of where they started.
TEST(MoonUnits, EveryQuantityKindRoundTripsSiToModelToSi) {
  ASSERT_EQ(std::size(all_dimensions), 7u);
  for (const MoonPreset& preset : moon_presets()) {
    const ModelUnits u = model_units(preset.mass_kg, preset.radius_m);
    for (const Dimension d : all_dimensions) {
      SCOPED_TRACE(std::string(preset.name) + ", " + std::string(dimension_name(d)));
      EXPECT_EQ(model_to_si(u, d, 1.0), model_unit(u, d));
      for (const double factor : {1.0, 0.37, 1.84, 3.1e-4, 2.5e3, 1.0 / 3.0}) {
        const double si = factor * model_unit(u, d);
        EXPECT_LE(ulps(model_to_si(u, d, si_to_model(u, d, si)), si), round_trip_ulps) << factor;
        EXPECT_LE(ulps(si_to_model(u, d, model_to_si(u, d, factor)), factor), round_trip_ulps) << factor;
        const double shown = factor * 977;  // a value in the output unit (km, kg, h, ...)
        EXPECT_LE(ulps(model_to_output(u, d, output_to_model(u, d, shown)), shown), round_trip_ulps) << factor;
        EXPECT_LE(ulps(model_to_output(u, d, factor) * output_unit(d).si_per_unit, model_to_si(u, d, factor)),
                  round_trip_ulps)
            << factor;
      }
      // The names the output writes: the model unit read back, the SI key of the output unit.
      EXPECT_EQ(dimension_of_model_unit(model_unit_name(d)), d);
      EXPECT_TRUE(si_key("x", d).starts_with("x_"));
    }
  }
  // The units are those of quantity_si: one km read is 1 km written, one hour 3600 s.
  const ModelUnits tethys = model_units(0.62e21, 531e3);
  EXPECT_EQ(model_to_output(tethys, Dimension::length, si_to_model(tethys, Dimension::length,
                                                                   quantity_si("977 km", Dimension::length, "k"))),
            977.0);
  EXPECT_DOUBLE_EQ(quantity_si("1 h", Dimension::time, "k"), output_unit(Dimension::time).si_per_unit);
  EXPECT_DOUBLE_EQ(quantity_si("1 km/s", Dimension::speed, "k"), output_unit(Dimension::speed).si_per_unit);
  EXPECT_DOUBLE_EQ(tethys.energy_J, tethys.mass_kg * tethys.speed_m_s * tethys.speed_m_s);
  EXPECT_EQ(si_key("pericenter", Dimension::length), "pericenter_km");
  EXPECT_EQ(si_key("min_distance", Dimension::time), "min_distance_h");
  EXPECT_EQ(dimension_of_model_unit("GM^2/R"), Dimension::energy);
  EXPECT_FALSE(dimension_of_model_unit("deg"));
}

// Tethys (Table 1: M = 0.62e21 kg, R = 531 km) with a 10.6 km crust, by hand (Python, G = 6.674e-11):
// e_g = G M^2 / R^4 = 3.226944506855669e8 Pa; E_I = 9e9 / e_g = 27.89016043157677; h_S = 10.6 / 531
// = 0.019962335216572504; rho_S = 930 / (M / R^3) = 0.22458193650000002; E_2D = (0.9e9 / e_g) h_S
// = 0.055675273177912196; eps_S = 1e6 / 0.9e9 = 0.0011111111111111111; M_S = 4 pi h_S rho_S = 0.05633730015424569.
TEST(MoonConfig, TethysPresetGivesTheHandComputedMaterial) {
  const Config c = parse_config(moon_toml, "moon.toml");
  ASSERT_TRUE(c.from_material());
  EXPECT_NEAR(*c.material.youngs_modulus, 27.89016043157677, 1e-13 * 27.9);
  EXPECT_NEAR(*c.material.crust_thickness, 0.019962335216572504, 1e-15);
  EXPECT_NEAR(*c.material.crust_density, 0.22458193650000002, 1e-15);
  EXPECT_NEAR(*c.material.crust_modulus_2d, 0.055675273177912196, 1e-15);
  EXPECT_NEAR(*c.material.failure_strain, 0.0011111111111111111, 1e-18);
  EXPECT_NEAR(c.shell.mass, 0.05633730015424569, 1e-15);
  EXPECT_EQ(c.shell.failure_strain, *c.material.failure_strain);
  EXPECT_FALSE(c.core.present());
}

TEST(MoonConfig, WorkflowResolvesToTomlAndReadsBackTheSame) {
  const Config c = parse_config(moon_toml, "moon.toml");
  const std::string stored = to_toml(c);
  // Both the [moon] strings and the model values they gave.
  EXPECT_NE(stored.find("[moon]\npreset = 'TeThYs'"), std::string::npos) << stored;
  EXPECT_NE(stored.find("crust_thickness = '10.6 km'"), std::string::npos) << stored;
  EXPECT_NE(stored.find("youngs_modulus = 27.89016043157677"), std::string::npos) << stored;
  const Config again = parse_config(stored, "stored");
  EXPECT_EQ(to_toml(again), stored);
  EXPECT_EQ(again.material.youngs_modulus, c.material.youngs_modulus);
  EXPECT_EQ(again.moon.crust_thickness, c.moon.crust_thickness);
  EXPECT_EQ(again.encounters, c.encounters);
}

TEST(MoonConfig, MaterialKeyBesideMoonIsAnErrorNamingBoth) {
  std::string text = moon_toml;
  text += "[material]\nyoungs_modulus = 3.0\n";
  const std::string message = input_error([&] { parse_config(text, "both.toml"); });
  EXPECT_NE(message.find("both.toml: material.youngs_modulus = 3.0 and [moon] (moon.youngs_modulus"), std::string::npos)
      << message;
  Config c = parse_config(moon_toml, "moon.toml");
  EXPECT_THROW(apply_override(c, "material.crust_density=0.3"), InputError);
}

TEST(MoonConfig, MalformedOrWrongUnitNamesFileAndKey) {
  std::string text = moon_toml;
  text.replace(text.find("crust_thickness = \"10.6 km\""), 27, "youngs_modulus = \"0.9 GPaa\"");
  std::string message = input_error([&] { parse_config(text, "bad.toml"); });
  EXPECT_EQ(message, "bad.toml: moon.youngs_modulus = \"0.9 GPaa\": 'GPaa' is not a unit udunits2 knows");
  text = moon_toml;
  text.replace(text.find("crust_thickness = \"10.6 km\""), 27, "radius = \"5 kg\"");
  message = input_error([&] { parse_config(text, "bad.toml"); });
  EXPECT_NE(message.find("bad.toml: moon.radius = \"5 kg\": 'kg' is not a unit of a length"), std::string::npos)
      << message;
  text = moon_toml;
  text.replace(text.find("crust_thickness = \"10.6 km\""), 27, "radius = 531");
  message = input_error([&] { parse_config(text, "bad.toml"); });
  EXPECT_NE(message.find("bad.toml: moon: 'radius' must be a length with its unit, as a string (e.g. \"531 km\")"),
            std::string::npos)
      << message;
}

TEST(MoonConfig, PoissonRatioOtherThanAQuarterIsRefused) {
  std::string text = moon_toml;
  text.replace(text.find("crust_thickness"), 0, "poisson_ratio = 0.25\n");
  EXPECT_NO_THROW(parse_config(text, "nu.toml"));
  text.replace(text.find("0.25"), 4, "0.33");
  EXPECT_NE(input_error([&] { parse_config(text, "nu.toml"); }).find("nu.toml: moon.poisson_ratio = 0.33: the random spring network has nu = 1/4"),
            std::string::npos);
}

TEST(MoonConfig, GivenKeysOverrideThePresetAndSetMakesTheModelFollow) {
  Config c = parse_config(moon_toml, "moon.toml");
  apply_override(c, "moon.youngs_modulus=\"0.9 GPa\"");
  EXPECT_DOUBLE_EQ(*c.material.youngs_modulus, 0.9e9 / 322694450.6855669);
  apply_override(c, "moon.failure_strain=0.002");
  EXPECT_EQ(*c.material.failure_strain, 0.002);
  EXPECT_EQ(c.shell.failure_strain, 0.002);
  EXPECT_THROW(apply_override(c, "moon.tensile_strength=\"2 MPa\""), InputError);  // beside failure_strain
  EXPECT_THROW(apply_override(c, "moon.poisson_ratio=0.3"), InputError);
  Config by_density = parse_config(moon_toml, "moon.toml");
  apply_override(by_density, "moon.mean_density=\"0.98 g/cm3\"");
  EXPECT_NEAR(*by_density.material.crust_density, 930.0 / 980.0 * 3 / (4 * std::numbers::pi), 1e-15);
}

// A core: the mantle holds what the crust and the core leave of M in the ball under the crust.
TEST(MoonConfig, CoreDensityRatioIsToTheMantleUnderTheCrust) {
  std::string text = moon_toml;
  text.replace(text.find("crust_thickness"), 0,
               "core_radius = \"200 km\"\ncore_density = \"2.5 g/cm3\"\ncore_youngs_modulus = \"90 GPa\"\n");
  const Config c = parse_config(text, "core.toml");
  const double pi = std::numbers::pi, R = 531e3, h = 10.6e3, M = 0.62e21;
  const double mantle = (M - 4 * pi * R * R * h * 930 - 4.0 / 3.0 * pi * std::pow(200e3, 3) * 2500) /
                        (4.0 / 3.0 * pi * (std::pow(R - h, 3) - std::pow(200e3, 3)));
  EXPECT_NEAR(*c.core.radius, 200.0 / 531.0, 1e-15);
  EXPECT_NEAR(*c.core.density_ratio, 2500 / mantle, 1e-12);
  EXPECT_NEAR(*c.core.modulus_ratio, 10.0, 1e-14);
  text.replace(text.find("2.5 g/cm3"), 9, "50 g/cm3");
  EXPECT_NE(input_error([&] { parse_config(text, "core.toml"); }).find("leave the mantle no mass"), std::string::npos);
}

TEST(MoonConfig, ShippedTethysWorkflowIsAMoon) {
  const Config c = load_config(test_support::workflow_file("tethys.toml"));
  EXPECT_EQ(c.moon.preset, "tethys");
  EXPECT_TRUE(c.from_material());
  EXPECT_EQ(c.cross.coupling, CrossCoupling::welded);
}

// [[encounters]] in SI: divided by M, R and v_c of the moon; plain numbers stay model units.
TEST(MoonConfig, EncounterInSiIsConvertedWithTheMoonsUnits) {
  std::string text = moon_toml;
  text.replace(text.find("perturber_mass = 0.5\npericenter = 1.84\npericenter_speed = 1.6"), 61,
               "perturber_mass = \"3.1e20 kg\"\npericenter = \"977 km\"\npericenter_speed = \"0.447 km/s\"");
  text += "[[encounters]]\nname = \"par\"\nperturber_mass = 0.5\npericenter = \"977 km\"\n";
  const Config c = parse_config(text, "si.toml");
  const double v_c = std::sqrt(6.674e-11 * 0.62e21 / 531e3);  // 279.15 m/s
  EXPECT_EQ(c.encounters.at(0).perturber_mass, 0.5);  // 3.1e20 / 6.2e20, both exact halves of each other
  EXPECT_NEAR(c.encounters.at(0).pericenter, 977.0 / 531.0, 1e-15);
  EXPECT_NEAR(c.encounters.at(0).pericenter_speed, 447.0 / v_c, 1e-14);
  EXPECT_EQ(c.encounters.at(1).pericenter_speed, parabolic_speed(0.5, c.encounters.at(1).pericenter));
  const Config again = parse_config(to_toml(c), "stored");
  EXPECT_EQ(again.encounters, c.encounters);

  std::string no_moon = "[[encounters]]\nname = \"A\"\npericenter = \"977 km\"\n";
  EXPECT_NE(input_error([&] { parse_config(no_moon, "a.toml"); })
                .find("a.toml: encounters[0]: pericenter = \"977 km\": a string is a quantity with its unit, which needs the "
                      "moon in SI"),
            std::string::npos);
  text.replace(text.find("\"977 km\""), 8, "\"977 kg\"");
  EXPECT_NE(input_error([&] { parse_config(text, "si.toml"); })
                .find("si.toml: encounters[0]: pericenter = \"977 kg\": 'kg' is not a unit of a length"),
            std::string::npos);
}

TEST(MoonConfig, AQuantityWithItsUnitInAModelUnitKeyPointsToTheMoonTable) {
  // The case users report: [material] youngs_modulus = "0.9 GPa" (in e_g) said only "must be a number".
  try {
    parse_config("[material]\nyoungs_modulus = \"0.9 GPa\"\n[[encounters]]\nname = \"A\"\nperturber_mass = 0.5\n"
                 "pericenter = 2.0\n",
                 "m.toml");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "m.toml: material: 'youngs_modulus' must be a number in e_g (model units G = M = R = 1); a quantity "
              "with its unit (\"0.9 GPa\", \"531 km\") goes in [moon] (docs/moon.md)");
  }
}
