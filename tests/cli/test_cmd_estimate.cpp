#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/cli_runner.hpp"

using namespace std::string_literals;
using tidalcrust::test_support::count_lines;
using tidalcrust::test_support::run_cli;

namespace {

bool has_key(const std::string& json, const std::string& key) {
  return json.find("\"" + key + "\": ") != std::string::npos;
}

/// The number after "key": in a JSON text (first occurrence).
double json_number(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\": ");
  if (at == std::string::npos) return NAN;
  return std::stod(json.substr(at + key.size() + 4));
}


}  // namespace

TEST(CommandEstimate, DioneJsonHasTable1AndEncounterKeys) {
  const auto r = run_cli("estimate --body Dione --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  for (const char* key : {"mass_kg", "radius_km", "e_g_GPa", "t_grav_s", "rho_g_cm3", "v_c_km_s", "strain",
                          "t_enc_over_t_elas", "delta_v", "strain_rate_per_s"})
    EXPECT_TRUE(has_key(r.out, key)) << key << "\n" << r.out;
  EXPECT_NEAR(json_number(r.out, "e_g_GPa"), 0.81, 0.02 * 0.81);  // Table 1
  EXPECT_NEAR(json_number(r.out, "t_grav_s"), 1556, 0.02 * 1556);
  EXPECT_NEAR(json_number(r.out, "rho_g_cm3"), 1.48, 0.02 * 1.48);
  EXPECT_DOUBLE_EQ(json_number(r.out, "mass_kg"), 1.1e21);
  // Defaults: M2 = 1, q = 2, V_q = sqrt(2), E = 0.9 GPa: strain = (e_g/E)^(1/2) / (4 sqrt 2).
  const double e_g = json_number(r.out, "e_g_GPa");
  EXPECT_NEAR(json_number(r.out, "strain"), std::sqrt(e_g / 0.9) / (4 * std::sqrt(2.0)), 1e-12);
  EXPECT_EQ(r.out.front(), '{');
  EXPECT_EQ(r.out.substr(r.out.size() - 2), "}\n");
}

TEST(CommandEstimate, EncounterOptionsChangeTheEstimates) {
  const auto r = run_cli("estimate --mass 1.1e21 --radius 561 --m2 0.5 --q 1.84 --vq=1.6 --youngs 2.7 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const double e_g = json_number(r.out, "e_g_GPa");
  EXPECT_NEAR(json_number(r.out, "strain"), std::sqrt(e_g / 2.7) * 0.5 / (1.84 * 1.84 * 1.6), 1e-12);
  // t_enc = 2q/V_q (eq. 2) over t_elas; eq. 11 as printed takes t_enc ~ q/V_q: half of it.
  EXPECT_NEAR(json_number(r.out, "t_enc_over_t_elas"), 2 * 1.84 / 1.6 * std::sqrt(2.7 / e_g), 1e-12);
  EXPECT_NEAR(json_number(r.out, "eq11_time_ratio"), 1.84 / 1.6 * std::sqrt(2.7 / e_g), 1e-12);
  EXPECT_NEAR(json_number(r.out, "delta_v"), 2 * 0.5 / (1.84 * 1.84 * 1.6), 1e-12);
}

TEST(CommandEstimate, WithoutABodyPrintsAllOfTable1) {
  const auto json = run_cli("estimate --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  for (const char* name : {"Tethys", "Dione", "Rhea", "Ariel", "Titania", "Charon", "Mars"})
    EXPECT_NE(json.out.find("\""s + name + "\""), std::string::npos) << name;
  const auto table = run_cli("estimate");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_EQ(count_lines(table.out), 2 + 7);  // title, header, one row per body
  EXPECT_NE(table.out.find("Titania"), std::string::npos);
}

TEST(CommandEstimate, KnowsTheMoonPresetsBesideTable1) {
  const auto r = run_cli("estimate --body europa --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has_key(r.out, "mass_kg")) << r.out;
  EXPECT_NE(r.out.find("\"Europa\""), std::string::npos) << r.out;
  EXPECT_DOUBLE_EQ(json_number(r.out, "mass_kg"), 4.80e22);  // Anderson et al. 1998 (docs/moon.md)
  EXPECT_DOUBLE_EQ(json_number(r.out, "radius_km"), 1560.8);
  const auto unknown = run_cli("estimate --body Pluto2");
  EXPECT_NE(unknown.err.find("Miranda"), std::string::npos) << unknown.err;
}

TEST(CommandEstimate, UnknownBodyIsAOneLineInputError) {
  const auto r = run_cli("estimate --body Pluto2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("Pluto2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("Charon"), std::string::npos) << r.err;
}

TEST(CommandEstimate, BadInputNamesTheOption) {
  const std::pair<const char*, const char*> cases[] = {
      {"estimate --mass -1e21 --radius 500", "--mass"}, {"estimate --mass nan --radius 500", "--mass"},
      {"estimate --mass 1e21", "--radius"},              {"estimate --radius 500", "--mass"},
      {"estimate --mass 1e21 --radius 0", "--radius"},  {"estimate --q 0", "--q"},
      {"estimate --q=-2", "--q"},                        {"estimate --vq abc", "--vq"},
      {"estimate --youngs 0", "--youngs"},               {"estimate --body Rhea --mass 1e21", "--body"}};
  for (const auto& [args, option] : cases) {
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.err.find(option), std::string::npos) << args << ": " << r.err;
  }
}

/// The number after `label` in a text (first occurrence), NAN if absent.
static double number_after(const std::string& text, const std::string& label) {
  const auto at = text.find(label);
  if (at == std::string::npos) return NAN;
  return std::stod(text.substr(at + label.size()));
}

// The printed ratio t_enc/t_elas is the ratio of the two printed times (to their printed
// precision); eq. 11's value, which takes t_enc ~ q/V_q, has its own label and is half of it.
TEST(CommandEstimate, PrintedRatioIsTheRatioOfThePrintedTimes) {
  const auto r = run_cli("estimate --body Dione");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const double t_enc = number_after(r.out, "t_enc            = ");
  const double t_elas = number_after(r.out, "t_elas = ");
  const double ratio = number_after(r.out, "t_enc/t_elas     = ");
  const double eq11 = number_after(r.out, "eq. 11 as printed = ");
  ASSERT_TRUE(std::isfinite(t_enc) && std::isfinite(t_elas) && std::isfinite(ratio) && std::isfinite(eq11)) << r.out;
  EXPECT_NEAR(ratio, t_enc / t_elas, 0.005 * ratio) << r.out;
  EXPECT_NEAR(eq11, 0.5 * ratio, 0.005 * ratio) << r.out;
}
