// `tidalcrust validate` as a user meets it: it runs the body chain of a workflow, writes
// validation.json with one comparison per check (measured, theory, their ratio, tolerance,
// source) and the figures; bad input is one line on stderr and exit 2, with nothing written.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "io/json.hpp"
#include "support/quick_workflow.hpp"
#include "support/cli_runner.hpp"
#include "support/files.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

/// A tiny body (shell level 2, 150 interior nodes) with a short relaxation.
fs::path tiny_workflow(const fs::path& dir) {
  const auto file = dir / "tiny.toml";
  std::ofstream(file) << small_body_toml("tiny");
  return file;
}

}  // namespace

TEST(CmdValidate, WritesEveryComparisonWithItsRatioAndTheFigures) {
  const ScratchFolder scratch("validate_json");
  const fs::path out = scratch.path / "out";
  const auto r = run_cli("validate " + quoted(tiny_workflow(scratch.path)) + " --quiet --out " + quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("breathing"), std::string::npos);  // the printed table
  const Json json = Json::parse(read_file(out / "validate" / "validation.json"));
  EXPECT_EQ(json["workflow"], "tiny");
  EXPECT_FALSE(json["git_commit"].get<std::string>().empty());  // the code that measured
  EXPECT_GT(json["material"]["youngs_modulus"].get<double>(), 0);
  for (const char* name : {"breathing", "love", "flexure", "p-wave"}) {
    SCOPED_TRACE(name);
    const Json& c = json["comparisons"][name];
    ASSERT_TRUE(c.is_object());
    for (const char* key : {"quantity", "unit", "measured", "theory", "ratio", "tolerance", "within_tolerance", "source"})
      EXPECT_TRUE(c.contains(key)) << key;
    const double measured = c["measured"].get<double>(), theory = c["theory"].get<double>();
    EXPECT_GT(theory, 0);
    EXPECT_DOUBLE_EQ(c["ratio"].get<double>(), measured / theory);
    EXPECT_EQ(c["within_tolerance"].get<bool>(), std::abs(measured / theory - 1) <= c["tolerance"].get<double>());
    EXPECT_FALSE(c["source"].get<std::string>().empty());
  }
  EXPECT_NEAR(json["comparisons"]["flexure"]["tolerance"].get<double>(), 0.20, 1e-12);
  // The same measurements against theory with the network's measured moduli: same measured
  // value, another theory; the moduli themselves under network_moduli.
  for (const auto& [network, eq15] : {std::pair{"breathing-network", "breathing"}, std::pair{"love-network", "love"},
                                      std::pair{"love-layered", "love"}, std::pair{"p-wave-network", "p-wave"},
                                      std::pair{"p-wave-layered", "p-wave"}}) {
    SCOPED_TRACE(network);
    const Json& c = json["comparisons"][network];
    ASSERT_TRUE(c.is_object());
    EXPECT_EQ(c["measured"].get<double>(), json["comparisons"][eq15]["measured"].get<double>());
    EXPECT_GT(c["theory"].get<double>(), 0);
    EXPECT_NE(c["theory"].get<double>(), json["comparisons"][eq15]["theory"].get<double>());
  }
  const Json& moduli = json["network_moduli"];
  EXPECT_GT(moduli["youngs_factor"].get<double>(), 0.5);
  EXPECT_LT(moduli["youngs_factor"].get<double>(), 1.0);  // non-affine: below eq. 15
  EXPECT_GT(moduli["geometric"]["free_nodes"].get<int>(), 0);
  EXPECT_NE(r.out.find("network moduli: E ="), std::string::npos) << r.out;
  for (const char* figure : {"breathing.png", "breathing.svg", "p_wave.png", "p_wave.svg"})
    EXPECT_GT(fs::file_size(out / "validate" / figure), 1000u) << figure;
  // Drawn (tidalcrust.figures) from validate/figure_data.json: the measured signals and marks.
  const Json plots = Json::parse(read_file(out / "validate" / "figure_data.json"))["figures"];
  for (const char* stem : {"breathing", "p_wave"}) {
    const Json& p = plots.at(stem);
    EXPECT_EQ(p["kind"], "signal");
    EXPECT_GE(p["time"].size(), 2u);
    EXPECT_EQ(p["time"].size(), p["signal"].size());
    bool measured = false;
    for (const Json& mark : p["marks"]) measured = measured || mark["measured"].get<bool>();
    EXPECT_TRUE(measured) << stem;
  }
  // The body chain is reused on a second call: only the selected measurement is redone.
  const auto again = run_cli("validate " + quoted(tiny_workflow(scratch.path)) + " --measure flexure --out " + quoted(out));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("up to date"), std::string::npos) << again.out;
  const Json only = Json::parse(read_file(out / "validate" / "validation.json"));
  EXPECT_EQ(only["comparisons"].size(), 1u);
}

TEST(CmdValidate, BadInputIsOneLineAndExitTwoWithNothingWritten) {
  const ScratchFolder scratch("validate_bad");
  const fs::path out = scratch.path / "out";
  const fs::path workflow = tiny_workflow(scratch.path);
  struct Case {
    std::string args, names;
  };
  for (const Case& c : {Case{"validate " + quoted(scratch.path / "missing.toml") + " --out " + quoted(out), "missing.toml"},
                        Case{"validate " + quoted(workflow) + " --bogus --out " + quoted(out), "bogus"},
                        Case{"validate " + quoted(workflow) + " --measure breathing,tides --out " + quoted(out), "tides"},
                        Case{"validate " + quoted(workflow) + " --tide-duration 0 --out " + quoted(out), "--tide-duration"},
                        Case{"validate " + quoted(workflow) + " --tide-duration nan --out " + quoted(out), "--tide-duration"},
                        Case{"validate " + quoted(workflow) + " --tide-duration 2e4 --out " + quoted(out), "--tide-duration"},
                        Case{"validate --out " + quoted(out), "WORKFLOW.toml"}}) {
    SCOPED_TRACE(c.args);
    const auto r = run_cli(c.args);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(c.names), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
}

// Issue 23 on the level-3 welded body (workflows/quick-welded.toml; docs/results/crust-coupling.md):
// the relaxed crust is free of pre-stress and nothing fails in the probe, and its tidal strain
// follows the continuum's. Stored values measured at 6560989 (kernel fast/avx512); the tolerances
// cover another gravity kernel's last bits (these are smooth fits, not fracture sets). They pin
// what the model does, not the targets: a correlation of 0.95 and a peak tension within
// 15% are not reached at level 3.
TEST(CmdValidate, TheWeldedQuickCrustFollowsTheContinuumTide) {
  const ScratchFolder scratch("validate_welded");
  const fs::path out = scratch.path / "out";
  const auto r = run_cli("validate " + quoted(fs::path(TIDALCRUST_SOURCE_DIR) / "workflows" / "quick-welded.toml") +
                         " --measure tide --out " + quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The tide's four runs (+-eps, 2/3 then the rest) report progress as one count of steps.
  EXPECT_NE(r.err.find("validate: tide: done at step 3000"), std::string::npos) << r.err;
  const auto relaxed = run_cli("inspect " + quoted(out / "body" / "relax.h5") + " --json");
  ASSERT_EQ(relaxed.exit_code, 0) << relaxed.err;
  const Json record = Json::parse(relaxed.out)["record"];
  EXPECT_LT(record["max_shell_strain"].get<double>(), 4e-5);  // measured 3.2e-5 (the issue asks 1e-5)
  EXPECT_EQ(record["probe_failures"].get<std::int64_t>(), 0);
  const Json c = Json::parse(read_file(out / "validate" / "validation.json"))["comparisons"];
  EXPECT_NEAR(c["tide"]["ratio"].get<double>(), 0.9685, 0.01);             // h2 / TS72
  EXPECT_NEAR(c["tide-l2-over-h2"]["ratio"].get<double>(), 0.9600, 0.01);  // l2/h2
  EXPECT_NEAR(c["tide-correlation"]["measured"].get<double>(), 0.9084, 0.01);
  EXPECT_NEAR(c["tide-median-ratio"]["measured"].get<double>(), 0.9344, 0.02);
  EXPECT_NEAR(c["tide-peak-tension"]["ratio"].get<double>(), 0.8199, 0.02);
  EXPECT_GT(c["tide-subsatellite"]["measured"].get<double>(), 0);  // stretched, as the continuum
}

// A welded body with a rocky core (issue 23 item 1: the weld works for [core] bodies) is no
// homogeneous sphere, so its tide is compared with the layered sphere of its own layers
// (docs/validation.md). Against the homogeneous sphere of the strain test's mixed moduli it read
// l2/h2 1.55x and a correlation of 0.68 (before 67e3ca3). Stored values: core-T welded at level 3,
// measured at 67e3ca3 (kernel fast/avx512); the tolerances cover another kernel's last bits.
TEST(CmdValidate, AWeldedBodyWithACoreFollowsItsLayeredSphere) {
  const ScratchFolder scratch("validate_welded_core");
  const fs::path out = scratch.path / "out";
  const auto r = run_cli("validate " + quoted(fs::path(TIDALCRUST_SOURCE_DIR) / "workflows" / "core-T.toml") +
                         " --set cross.coupling=welded --set resolution.shell_level=3 --measure tide --quiet --out " +
                         quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("against the layered sphere"), std::string::npos) << r.out;
  const Json json = Json::parse(read_file(out / "validate" / "validation.json"));
  const Json& tide = json["details"]["tide"];
  EXPECT_EQ(tide["reference"], "layered");
  const Json& c = json["comparisons"];
  EXPECT_DOUBLE_EQ(c["tide"]["theory"].get<double>(), tide["layered_h2"].get<double>());
  EXPECT_DOUBLE_EQ(c["tide-l2"]["theory"].get<double>(), tide["layered_l2"].get<double>());
  EXPECT_NE(c["tide"]["source"].get<std::string>().find("layered"), std::string::npos);
  EXPECT_NEAR(c["tide-l2-over-h2"]["ratio"].get<double>(), 1.0012, 0.01);  // within the 10%
  EXPECT_NEAR(c["tide"]["ratio"].get<double>(), 0.8771, 0.01);
  EXPECT_NEAR(c["tide-correlation"]["measured"].get<double>(), 0.8868, 0.01);
  EXPECT_NEAR(c["tide-peak-tension"]["ratio"].get<double>(), 0.8694, 0.02);
  // With the core, l2/h2 = 0.43 > 1/3: the continuum compresses the subsatellite crust
  // (h - 3l < 0), and so does the model.
  EXPECT_LT(c["tide-subsatellite"]["theory"].get<double>(), 0);
  EXPECT_LT(c["tide-subsatellite"]["measured"].get<double>(), 0);
  const auto relaxed = run_cli("inspect " + quoted(out / "body" / "relax.h5") + " --json");
  ASSERT_EQ(relaxed.exit_code, 0) << relaxed.err;
  const Json record = Json::parse(relaxed.out)["record"];
  EXPECT_LT(record["max_shell_strain"].get<double>(), 1e-5);  // measured 3.6e-6: free of pre-stress
  EXPECT_EQ(record["probe_failures"].get<std::int64_t>(), 0);
}
