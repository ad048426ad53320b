// Material bodies on the command line (issue 12): estimate --config shows a body's material
// equivalents, an unstable dt is refused with one line, [material] with spring constants is an
// error naming the file.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "support/cli_runner.hpp"
#include "support/files.hpp"

using tidalcrust::test_support::count_lines;
using tidalcrust::test_support::quoted;
using tidalcrust::test_support::run_cli;
using tidalcrust::test_support::ScratchFolder;
using tidalcrust::test_support::workflow_file;
using tidalcrust::test_support::write_file;

namespace {

double json_number(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\": ");
  if (at == std::string::npos) return NAN;
  return std::stod(json.substr(at + key.size() + 4));
}

}  // namespace

TEST(MaterialCli, EstimateShowsPaperTsMaterialEquivalents) {
  const auto r = run_cli("estimate --body Dione --json --config " + quoted(workflow_file("paper-T.toml")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(json_number(r.out, "E_I"), 3.07, 0.05);  // as built (README: Table 3 prints 3.73)
  EXPECT_NEAR(json_number(r.out, "V_IP"), 3.93, 0.05);
  EXPECT_NEAR(json_number(r.out, "V_SP"), 3.28, 0.05);
  EXPECT_NEAR(json_number(r.out, "D_F"), 0.0075 / 4, 1e-12);  // the hinge lattice's bending (mean k_e / 4)
  EXPECT_NEAR(json_number(r.out, "D_F_eq23"), 0.0075 * 0.0755 / 2, 2e-6);  // eq. 23's k_e L_S / 2
  EXPECT_GT(json_number(r.out, "dt_unstable"), 0.002);
  const auto text = run_cli("estimate --body Dione --config " + quoted(workflow_file("paper-T.toml")));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("E_I"), std::string::npos);
  EXPECT_NE(text.out.find("GPa"), std::string::npos);
}

TEST(MaterialCli, RunRefusesADtThatCannotBeStableWithOneLine) {
  const ScratchFolder out("material_unstable");
  const auto r = run_cli("run " + quoted(workflow_file("material-L3.toml")) +
                         " --set integrator.dt=0.05 --quiet --out " + quoted(out.path));
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("cannot be stable"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("node"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out.path / "body" / "relax.h5"));
}

TEST(MaterialCli, MaterialWithSpringConstantsIsAnErrorNamingTheFile) {
  const ScratchFolder dir("material_both");
  const auto file = dir.path / "both.toml";
  write_file(file, "[material]\nyoungs_modulus = 3.7\ncrust_thickness = 0.02\ncrust_mass = 0.07\n"
                   "[interior]\nspring_constant = 0.076\n");
  const auto r = run_cli("build --config " + quoted(file) + " --out " + quoted(dir.path / "b.h5"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("both.toml"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("interior.spring_constant"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path / "b.h5"));
}
