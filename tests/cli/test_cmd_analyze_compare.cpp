#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/checkpoint_file.hpp"
#include "stages/analysis_stage.hpp"
#include "io/json.hpp"
#include "io/checkpoint_names.hpp"
#include "support/cli_runner.hpp"
#include "support/files.hpp"
#include "support/synthetic_encounter.hpp"

using namespace std::string_literals;
using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

class AnalyzeCompareCli : public ::testing::Test {
 protected:
  void SetUp() override {
    // Final state: five failed shell springs; a snapshot at an earlier step with two of them.
    Checkpoint c = synthetic_encounter(2);
    for (int i = 0; i < 20; ++i) {
      TimeseriesSample s;
      s.time = 0.1 * i;
      s.failed = i / 4;
      s.kinetic_energy = 0.1;
      s.angular_momentum = {0, 0, 2.0};
      c.observables.timeseries.push_back(s);
    }
    Checkpoint snapshot = c;
    for (std::size_t s : {10, 20}) snapshot.state.springs.failed[s] = 1;
    snapshot.state.step = 600;
    snapshot.state.time = 1.2;
    snapshot.stage.complete = false;
    for (std::size_t s : {10, 20, 30, 40, 50}) c.state.springs.failed[s] = 1;
    encounter = dir / "enc.h5";
    write_checkpoint(encounter, c);
    write_checkpoint(snapshot_path(encounter, 600), snapshot);
    std::ofstream(snapshot_path(encounter, 700)) << "not a checkpoint";
    std::ofstream(dir / "enc.snap-abc.h5") << "ignored: not a step";

    Checkpoint other = c;  // same body, different fractures: springs 10, 20, 60
    std::fill(other.state.springs.failed.begin(), other.state.springs.failed.end(), 0);
    for (std::size_t s : {10, 20, 60}) other.state.springs.failed[s] = 1;
    write_checkpoint(dir / "other.h5", other);

    Checkpoint relaxed = c;
    relaxed.stage.record = RelaxRecord{};
    write_checkpoint(dir / "relaxed.h5", relaxed);
    write_checkpoint(dir / "coarse.h5", synthetic_encounter(1));
  }
  const ScratchFolder scratch{"analyze_compare"};
  const fs::path& dir = scratch.path;
  fs::path encounter;
};

}  // namespace

TEST_F(AnalyzeCompareCli, AnalyzeWritesFiguresAndSummary) {
  const fs::path out = dir / "analysis";
  const auto r = run_cli("analyze --from \"" + encounter.string() + "\" --out \"" + out.string() + "\"");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Every figure of analyze, drawn by the Python package (tidalcrust.figures) as PNG and SVG, and
  // listed in summary.json; figure_data.json names them.
  const std::string summary = read_file(out / "summary.json");
  const Json json = Json::parse(summary);
  const Json data = Json::parse(read_file(out / "figure_data.json"));
  EXPECT_EQ(data["figures"], Json({"fracture_map", "hemisphere", "orbit", "failures", "conservation", "body_shape",
                                   "axis_ratios", "crack_geometry"}));
  Json listed = Json::array();
  for (const Json& name : data["figures"]) {
    const std::string stem = name.get<std::string>();
    const std::string png = read_file(out / (stem + ".png"));
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << stem;
    EXPECT_NE(read_file(out / (stem + ".svg")).find("</svg>"), std::string::npos) << stem;
    listed.push_back(stem + ".png"), listed.push_back(stem + ".svg");
  }
  EXPECT_EQ(json["figures"], listed);
  EXPECT_EQ(data["state_hash"], json["state_hash"]);
  // The hemisphere and body-shape panels: the snapshot at step 600 and the final state.
  ASSERT_EQ(data["hemisphere"]["panels"].size(), 2u);
  EXPECT_EQ(data["hemisphere"]["panels"][1]["failed"], 5);
  EXPECT_EQ(data["hemisphere"]["panels"][0]["failed"], 2);
  EXPECT_EQ(data["body_shape"]["panels"].size(), 2u);
  EXPECT_EQ(data["failures"]["source"], "samples");
  EXPECT_EQ(data["failures"]["failed"].back(), 4.0);  // the last sample's count (i / 4 at i = 19)
  EXPECT_EQ(data["conservation"]["time_from_pericenter"].size(), 20u);
  EXPECT_EQ(json["failures"]["count"], 5) << summary;
  EXPECT_EQ(json["failures"]["fraction_shell"], 5.0 / 480);
  EXPECT_EQ(json["failed_springs"]["spring"], Json({10, 20, 30, 40, 50}));
  EXPECT_EQ(json["encounter"]["name"], "T5");
  EXPECT_EQ(json["encounter"]["pericenter_time"], 1.2);
  EXPECT_EQ(json["conservation"]["max_momentum_change"], 0.0);
  EXPECT_EQ(json["conservation"]["samples"], 20);
  // Snapshot row: the readable snapshot at step 600 and the final state; the corrupt one skipped.
  EXPECT_NE(summary.find("enc.snap-600.h5"), std::string::npos);
  EXPECT_EQ(json["snapshots"].dump().find("enc.snap-700.h5"), std::string::npos) << summary;
  EXPECT_NE(r.err.find("enc.snap-700.h5"), std::string::npos);
  EXPECT_NE(r.out.find("5 failed shell springs"), std::string::npos);
  // Issue 28: an analysis that skipped a snapshot it could not read is not finished: `run`
  // analyzes it again (a transient read error once made a panel go missing for good).
  EXPECT_EQ(json["skipped_snapshots"], Json({"enc.snap-700.h5"})) << summary;
  EXPECT_FALSE(analysis_is_current(out, read_checkpoint(encounter)));
  fs::remove(snapshot_path(encounter, 700));
  const auto again = run_cli("analyze --from \"" + encounter.string() + "\" --out \"" + out.string() + "\"");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(Json::parse(read_file(out / "summary.json"))["skipped_snapshots"], Json::array());
  EXPECT_TRUE(analysis_is_current(out, read_checkpoint(encounter)));
  // Principal axis ratios at the snapshot (at pericenter) and at the end; the particles did not
  // move between them, so the ratios agree; a >= b >= c.
  const Json& shapes = json["principal_axis_ratios"];
  ASSERT_EQ(shapes.size(), 2u) << summary;
  EXPECT_EQ(shapes[0]["time_from_pericenter"], 0.0);
  for (const Json& shape : shapes) {
    EXPECT_GT(shape["c_over_a"].get<double>(), 0.0);
    EXPECT_LE(shape["c_over_a"].get<double>(), shape["b_over_a"].get<double>());
    EXPECT_LE(shape["b_over_a"].get<double>(), 1.0);
  }
  EXPECT_EQ(shapes[0]["b_over_a"], shapes[1]["b_over_a"]);
  EXPECT_EQ(shapes[0]["c_over_a"], shapes[1]["c_over_a"]);
}

// --no-figures writes the numbers without the figure process (here: no interpreter at all) and
// removes the figures of an earlier analysis, as `[analysis] figures = false` does for run.
TEST_F(AnalyzeCompareCli, AnalyzeWithoutFiguresWritesTheNumbersAndNoFigure) {
  const fs::path out = dir / "analysis";
  const std::string args = "analyze --from " + quoted(encounter) + " --out " + quoted(out);
  const std::string no_python = "TIDALCRUST_PYTHON=" + (dir / "no-python").string();
  ASSERT_EQ(run_cli(args).exit_code, 0);
  ASSERT_TRUE(fs::exists(out / "fracture_map.png"));
  const auto r = run_cli(args + " --no-figures", no_python);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("no figures"), std::string::npos) << r.out;
  const Json json = Json::parse(read_file(out / "summary.json"));
  EXPECT_EQ(json["figures"], Json::array());
  EXPECT_EQ(json["failures"]["count"], 5);
  EXPECT_TRUE(fs::exists(out / "cracks.json"));
  EXPECT_TRUE(fs::exists(out / "figure_data.json"));
  for (const auto& entry : fs::directory_iterator(out))
    EXPECT_NE(entry.path().extension(), ".png") << entry.path();
}

// The figures are drawn by a child process (figures/figure_script.hpp); without its interpreter,
// or when it fails, analyze says so in one line (exit 2) after the numbers are written, and the
// analysis is not current, so `run` draws the figures again.
TEST_F(AnalyzeCompareCli, AFigureProcessThatCannotRunIsOneLineAfterTheNumbers) {
  const fs::path out = dir / "analysis";
  const std::string args = "analyze --from " + quoted(encounter) + " --out " + quoted(out);
  auto r = run_cli(args, "TIDALCRUST_PYTHON=" + (dir / "no-python").string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 2) << r.err;  // the skipped snapshot's line, then the error
  EXPECT_NE(r.err.find((dir / "no-python").string() + ": no such interpreter"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("TIDALCRUST_PYTHON"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(out / "summary.json"));
  EXPECT_TRUE(fs::exists(out / "cracks.json"));
  EXPECT_TRUE(fs::exists(out / "figure_data.json"));
  EXPECT_FALSE(fs::exists(out / "fracture_map.png"));
  fs::remove(snapshot_path(encounter, 700));
  r = run_cli(args, "TIDALCRUST_PYTHON=/bin/false");  // an interpreter that fails
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("/bin/false -m tidalcrust.figures analysis) failed (exit 1)"), std::string::npos) << r.err;
  EXPECT_FALSE(analysis_is_current(out, read_checkpoint(encounter)));
  // A figure script that fails on its input: its own one-line message is passed on.
  std::ofstream(dir / "python.sh") << "#!/bin/sh\necho 'Traceback (most recent call last):' >&2\n"
                                       "echo \"ModuleNotFoundError: No module named 'cartopy'\" >&2\nexit 1\n";
  fs::permissions(dir / "python.sh", fs::perms::owner_all);
  r = run_cli(args, "TIDALCRUST_PYTHON=" + (dir / "python.sh").string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("No module named 'cartopy'"), std::string::npos) << r.err;
  r = run_cli(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(analysis_is_current(out, read_checkpoint(encounter)));
}

TEST_F(AnalyzeCompareCli, AnalyzeRefusesOtherStagesAndMissingFiles) {
  auto r = run_cli("analyze --from \"" + (dir / "relaxed.h5").string() + "\" --out \"" + (dir / "x").string() + "\"");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("expected an 'encounter' checkpoint"), std::string::npos) << r.err;
  r = run_cli("analyze --from \"" + (dir / "missing.h5").string() + "\" --out \"" + (dir / "x").string() + "\"");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("missing.h5"), std::string::npos);
  EXPECT_EQ(run_cli("analyze --out x").exit_code, 2);
}

TEST_F(AnalyzeCompareCli, CompareWithItselfIsIdentical) {
  const auto r = run_cli("compare \"" + encounter.string() + "\" \"" + encounter.string() + "\" --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json json = Json::parse(r.out);
  EXPECT_EQ(json["jaccard"], 1.0) << r.out;
  EXPECT_EQ(json["ks_distance_angle_from_subsatellite"], 0.0);
  EXPECT_EQ(json["identical_state"], true);
  EXPECT_EQ(json["a"]["state_hash"], json["b"]["state_hash"]);
}

TEST_F(AnalyzeCompareCli, CompareCountsOverlap) {
  const auto r = run_cli("compare \"" + encounter.string() + "\" \"" + (dir / "other.h5").string() + "\" --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json json = Json::parse(r.out);
  EXPECT_EQ(json["common_failed"], 2) << r.out;
  EXPECT_EQ(json["either_failed"], 6);
  EXPECT_EQ(json["jaccard"], 2.0 / 6);
  const auto text = run_cli("compare \"" + encounter.string() + "\" \"" + (dir / "other.h5").string() + "\"");
  EXPECT_EQ(text.exit_code, 0);
  EXPECT_NE(text.out.find("Jaccard index 0.3333"), std::string::npos) << text.out;
}

// The table shows which times (and steps) are compared: here a snapshot at t = 1.2, step 600,
// against the final state.
TEST_F(AnalyzeCompareCli, CompareShowsBothTimes) {
  const Checkpoint final_state = read_checkpoint(encounter);
  const auto r = run_cli("compare \"" + snapshot_path(encounter, 600).string() + "\" \"" + encounter.string() + "\"");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto row = r.out.find("time [t_grav]");
  ASSERT_NE(row, std::string::npos) << r.out;
  const std::string line = r.out.substr(row, r.out.find('\n', row) - row);
  EXPECT_NE(line.find(" 1.2 "), std::string::npos) << line;
  EXPECT_NE(line.find(fmt::format("{:.6g}", final_state.state.time)), std::string::npos) << line;
  EXPECT_NE(r.out.find("600"), std::string::npos) << r.out;
}

TEST_F(AnalyzeCompareCli, CompareRefusesDifferentBodiesAndStages) {
  auto r = run_cli("compare \"" + encounter.string() + "\" \"" + (dir / "coarse.h5").string() + "\"");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("do not branch from the same body"), std::string::npos) << r.err;
  r = run_cli("compare \"" + encounter.string() + "\" \"" + (dir / "relaxed.h5").string() + "\"");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(run_cli("compare \"" + encounter.string() + "\"").exit_code, 2);
}
