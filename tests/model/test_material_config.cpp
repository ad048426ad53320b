// [material], [resolution], [core] in a workflow (issue 12): what the configuration derives
// before building, and the one-line errors for bad or conflicting material values.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "base/errors.hpp"
#include "model/config.hpp"

using namespace tidalcrust;

namespace {

const std::string material_toml = R"(
[material]
youngs_modulus = 3.7
crust_thickness = 0.0187
flexural_rigidity = 2.8e-4
crust_mass = 0.07
coupling_speed_ratio = 0.73
failure_strain = 0.002
)";

std::string error_of(const std::string& text) {
  try {
    parse_config(text, "bad.toml");
  } catch (const InputError& err) {
    return err.what();
  }
  return "";
}

}  // namespace

TEST(MaterialConfig, DerivesTheGeometryAndTheCrustBeforeBuilding) {
  const Config c = parse_config(material_toml, "m.toml");
  ASSERT_TRUE(c.from_material());
  // Level 4 reproduces paper-T's geometry (d_IS 0.10, d_I 0.23, r_I 0.897, N_I 1869).
  EXPECT_EQ(c.shell.level, 4);
  EXPECT_DOUBLE_EQ(c.interior.min_separation, 0.10);
  EXPECT_NEAR(c.interior.spring_distance, 0.23, 1e-12);
  EXPECT_NEAR(c.interior.radius, 0.897, 1e-12);
  EXPECT_EQ(c.interior.count, 1869);
  EXPECT_NEAR(c.shell.spring_constant, std::sqrt(3.0) / 2 * 3.7 * 0.0187, 1e-15);  // eq. 20
  EXPECT_DOUBLE_EQ(c.shell.mass, 0.07);
  EXPECT_DOUBLE_EQ(c.shell.failure_strain, 0.002);
  EXPECT_TRUE(c.choose_dt);  // no integrator.dt given
  // Level 5: the interior spacing shrinks by sqrt 2, the count grows by about 2^(3/2).
  const Config c5 = parse_config(material_toml + "[resolution]\nshell_level = 5\n", "m.toml");
  EXPECT_NEAR(c5.interior.min_separation, 0.10 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(static_cast<double>(c5.interior.count) / 1869.0, 3.1, 0.1);
}

TEST(MaterialConfig, ResolvedTextRoundTripsWithoutTheDerivedKeys) {
  const Config c = parse_config(material_toml + "[resolution]\nshell_level = 3\n[core]\nradius = 0.4\n", "m.toml");
  const std::string text = to_toml(c);
  EXPECT_EQ(text.find("spring_constant"), std::string::npos) << text;
  EXPECT_EQ(text.find("\ndt ="), std::string::npos) << text;
  const Config again = parse_config(text, "stored");
  EXPECT_EQ(to_toml(again), text);
  EXPECT_EQ(again.interior.count, c.interior.count);
  EXPECT_TRUE(again.choose_dt);
  // A dt given (in the file or with --set) is kept and written.
  Config given = c;
  apply_override(given, "integrator.dt=0.001");
  EXPECT_FALSE(given.choose_dt);
  EXPECT_NE(to_toml(given).find("dt = 0.001"), std::string::npos);
}

TEST(MaterialConfig, ASetResolutionRederivesTheGeometry) {
  Config c = parse_config(material_toml, "m.toml");
  apply_override(c, "resolution.shell_level=3");
  EXPECT_EQ(c.shell.level, 3);
  EXPECT_NEAR(c.interior.min_separation, 0.10 * std::sqrt(2.0), 1e-12);
}

TEST(MaterialConfig, MaterialAndSpringConstantsTogetherIsAnErrorNamingTheFileAndKey) {
  for (const char* printed : {"[interior]\nspring_constant = 0.076\n", "[shell]\nbending_constant = 0.0075\n",
                              "[cross]\ndistance = 0.18\n", "[shell]\nlevel = 5\n"}) {
    const std::string message = error_of(material_toml + printed);
    EXPECT_NE(message.find("bad.toml"), std::string::npos) << message;
    EXPECT_NE(message.find("not both"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_NE(error_of(material_toml + "[shell]\nfailure_strain = 0.003\n").find("shell.failure_strain"),
            std::string::npos);
  Config c = parse_config(material_toml, "m.toml");
  EXPECT_THROW(apply_override(c, "cross.spring_constant=0.01"), InputError);
}

TEST(MaterialConfig, BadMaterialValuesAreOneLineErrorsNamingTheKey) {
  const std::string base = "[material]\ncrust_thickness = 0.02\ncrust_mass = 0.07\n";
  struct Case {
    std::string toml;
    std::string key;
  };
  const Case cases[] = {
      {base + "youngs_modulus = -1\n", "material.youngs_modulus"},
      {base + "youngs_modulus = 0\n", "material.youngs_modulus"},
      {base + "youngs_modulus = nan\n", "material.youngs_modulus"},
      {"[material]\nyoungs_modulus = 3\ncrust_mass = 0.07\ncrust_thickness = 0.7\n", "material.crust_thickness"},
      {"[material]\nyoungs_modulus = 3\ncrust_thickness = 0.02\ncrust_mass = 1.5\n", "material.crust_mass"},
      {base + "youngs_modulus = 3\ncoupling_speed_ratio = 0\n", "material.coupling_speed_ratio"},
      {base + "youngs_modulus = 3\nflexural_rigidity = -2e-4\n", "material.flexural_rigidity"},
      {base + "youngs_modulus = 3\n[resolution]\nshell_level = 9\n", "resolution.shell_level"},
      {base + "youngs_modulus = 3\n[resolution]\ninterior_spacing = 0\n", "resolution.interior_spacing"},
      {base + "youngs_modulus = 3\n[core]\nradius = 0.5\ndensity_ratio = -3\n", "core.density_ratio"},
      {"[material]\nyoungs_modulus = 3\ncrust_mass = 0.07\n", "material.crust_thickness"},  // missing
      {"[material]\nyoungs_modulus = 3\ncrust_thickness = 0.02\n", "material.crust_mass"},   // missing
      {base + "youngs_modulus = 3\ncrust_density = 0.3\n", "material.crust_density"},       // both
      {base, "material.youngs_modulus"},                                                     // no E_I
      {"[resolution]\nshell_level = 5\n", "[resolution]"},                                   // no [material]
      {"[core]\ndensity_ratio = 3\n", "core.radius"},
  };
  for (const auto& c : cases) {
    const std::string message = error_of(c.toml);
    EXPECT_NE(message.find(c.key), std::string::npos) << c.toml << " -> " << message;
    EXPECT_NE(message.find("bad.toml"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(MaterialConfig, PaperTKeepsItsPrintedConstantsAndItsText) {
  const Config t = load_config(std::string(TIDALCRUST_SOURCE_DIR) + "/workflows/paper-T.toml");
  EXPECT_FALSE(t.from_material());
  EXPECT_FALSE(t.choose_dt);
  EXPECT_FALSE(t.core.present());
  EXPECT_DOUBLE_EQ(t.interior.spring_constant, 0.076);
  EXPECT_DOUBLE_EQ(t.integrator.dt, 0.002);
  EXPECT_NE(to_toml(t).find("spring_constant = 0.076"), std::string::npos);
}

TEST(MaterialConfig, AMaterialBodyCarriesItsPressureByCompressionUnlessTheFileSaysOtherwise) {
  EXPECT_EQ(parse_config(material_toml, "m.toml").stretch.hydrostatic_support, HydrostaticSupport::compress);
  const Config asked = parse_config(material_toml + "[stretch]\nhydrostatic_support = \"strengthen\"\n", "m.toml");
  EXPECT_EQ(asked.stretch.hydrostatic_support, HydrostaticSupport::strengthen);
  // The resolved text states the choice, so a checkpoint's stored configuration reloads to it.
  EXPECT_EQ(parse_config(to_toml(asked), "stored").stretch.hydrostatic_support, HydrostaticSupport::strengthen);
  const Config t = load_config(std::string(TIDALCRUST_SOURCE_DIR) + "/workflows/paper-T.toml");
  EXPECT_EQ(t.stretch.hydrostatic_support, HydrostaticSupport::strengthen);  // the paper's method
  const std::string message = error_of(material_toml + "[stretch]\nhydrostatic_support = \"stiffen\"\n");
  EXPECT_NE(message.find("bad.toml"), std::string::npos) << message;
  EXPECT_NE(message.find("stretch.hydrostatic_support"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}
