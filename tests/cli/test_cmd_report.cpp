// `tidalcrust report`: on a small sweep with two encounters finished, one stopped part-way and
// one not started, the CSV and JSON hold one row per encounter with exactly the values of the
// checkpoints (fracture analysis, energy budget, eq. 5 with the relaxed body's E_I, state_hash),
// the unfinished and missing ones listed as such; a folder with nothing run is a one-line error.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/energy_budget.hpp"
#include "analysis/fracture_analysis.hpp"
#include "io/checkpoint_file.hpp"
#include "io/checkpoint_names.hpp"
#include "io/json.hpp"
#include "io/state_hash.hpp"
#include "model/derived_quantities.hpp"
#include "physics/encounter_estimates.hpp"
#include "support/quick_workflow.hpp"
#include "support/cli_runner.hpp"
#include "support/files.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

/// A small body and a 2 x 2 sweep: M0.5_q1.6_V1.8, M0.5_q1.9_V1.8, M1_q1.6_V1.8, M1_q1.9_V1.8.
fs::path sweep_workflow(const fs::path& dir) {
  const auto file = dir / "sweep.toml";
  std::ofstream(file) << small_body_toml("reported", "failure_strain = 0.002\n") << R"([encounter]
failure_rule = "paper"
start_distance = 2.5
end_distance = 2.5
[sweep]
perturber_mass = [0.5, 1.0]
pericenter = [1.6, 1.9]
pericenter_speed = [1.8]
)";
  return file;
}

std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::vector<std::string> cells;
    std::istringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.push_back("");
    rows.push_back(cells);
  }
  return rows;
}

}  // namespace

TEST(Report, TableHoldsEveryEncounterWithTheCheckpointsValues) {
  const ScratchFolder scratch("report");
  const auto workflow = sweep_workflow(scratch.path);
  const auto out = scratch.path / "out";
  const auto ran = run_cli("run " + quoted(workflow) + " --out " + quoted(out) +
                           " --quiet --jobs 2 --only M0.5_q1.6_V1.8 --only M1_q1.6_V1.8");
  ASSERT_EQ(ran.exit_code, 0) << ran.err;
  // M0.5_q1.9_V1.8 stopped part-way: a mid-stage checkpoint only (a snapshot of another one).
  const auto snapshots = find_snapshots(out / "M1_q1.6_V1.8" / "encounter.h5");
  ASSERT_FALSE(snapshots.empty());
  fs::create_directories(out / "M0.5_q1.9_V1.8");
  fs::copy_file(snapshots.front().file, out / "M0.5_q1.9_V1.8" / "encounter.mid.h5");

  const auto report = run_cli("report " + quoted(workflow) + " --out " + quoted(out));
  ASSERT_EQ(report.exit_code, 0) << report.err;
  EXPECT_NE(report.out.find("finished: 2"), std::string::npos) << report.out;
  EXPECT_NE(report.out.find(fmt::format("unfinished: 1: M0.5_q1.9_V1.8 (mid-stage checkpoint at step {} of", snapshots.front().step)),
            std::string::npos)
      << report.out;
  EXPECT_NE(report.out.find("missing: 1: M1_q1.9_V1.8"), std::string::npos) << report.out;

  const Checkpoint relaxed = read_checkpoint(out / "body" / "relax.h5");
  const double youngs = derive_quantities(relaxed.body, relaxed.state, 0.85).E_I;
  const auto rows = csv_rows(read_file(out / "report" / "sweep.csv"));
  ASSERT_EQ(rows.size(), 5u) << "a header and one row per encounter";
  const auto& header = rows[0];
  ASSERT_EQ(header.size(), 23u);
  EXPECT_EQ(header[3], "q [R]");
  EXPECT_EQ(header[11], "largest_network_length [R]");
  EXPECT_EQ(header[15], "note");
  EXPECT_EQ(header[16], "concentricity [1]");  // the crack geometry after the others
  EXPECT_EQ(header[20], "total_crack_length [R]");  // then the crack sizes
  EXPECT_EQ(header[21], "cracks [1]");
  EXPECT_EQ(header[22], "after");  // the encounter an encounter of a history comes after
  const Json json = Json::parse(read_file(out / "report" / "sweep.json"));
  EXPECT_EQ(json["counts"]["finished"], 2);
  EXPECT_EQ(json["counts"]["unfinished"], 1);
  EXPECT_EQ(json["counts"]["missing"], 1);
  ASSERT_EQ(json["encounters"].size(), 4u);
  EXPECT_DOUBLE_EQ(json["youngs_modulus_E_I"].get<double>(), youngs);

  const std::vector<std::string> names = {"M0.5_q1.6_V1.8", "M0.5_q1.9_V1.8", "M1_q1.6_V1.8", "M1_q1.9_V1.8"};
  const std::vector<std::string> statuses = {"finished", "unfinished", "finished", "missing"};
  for (std::size_t i = 0; i < names.size(); ++i) {
    const auto& row = rows[i + 1];
    const Json& entry = json["encounters"][i];
    ASSERT_EQ(row.size(), header.size()) << names[i];
    EXPECT_EQ(row[0], names[i]);
    EXPECT_EQ(row[1], statuses[i]);
    EXPECT_EQ(entry["name"], names[i]);
    EXPECT_EQ(entry["status"], statuses[i]);
    const Encounter spec = encounter_of(names[i], i < 2 ? 0.5 : 1.0, i % 2 ? 1.9 : 1.6, 1.8);
    EXPECT_EQ(row[5], "0.002");
    EXPECT_EQ(row[6], fmt::format("{}", estimate_encounter(spec, youngs).strain)) << names[i];
    if (statuses[i] != "finished") {
      EXPECT_EQ(row[7], "") << "no results for an encounter that has not finished";
      EXPECT_TRUE(entry["failures"].is_null());
      continue;
    }
    const Checkpoint c = read_checkpoint(out / names[i] / "encounter.h5");
    const FractureSummary fractures = analyze_fractures(c.body, c.state);
    const EnergyBudget budget = energy_budget(c.observables.timeseries, spec);
    EXPECT_EQ(row[7], std::to_string(fractures.count())) << names[i];
    EXPECT_EQ(entry["failures"], fractures.count());
    EXPECT_EQ(row[8], fmt::format("{}", fractures.fraction_shell));
    EXPECT_EQ(entry["failed_fraction"].get<double>(), fractures.fraction_shell);
    EXPECT_EQ(row[11], fmt::format("{}", fractures.longest_crack_length));
    EXPECT_EQ(entry["largest_network_length"].get<double>(), fractures.longest_crack_length);
    EXPECT_EQ(row[12], fmt::format("{}", budget.internal_change));
    EXPECT_EQ(entry["energy_deposited"].get<double>(), budget.internal_change);
    EXPECT_EQ(row[14], state_hash(c.state));
    EXPECT_EQ(entry["state_hash"], state_hash(c.state));
    EXPECT_EQ(row[17], std::to_string(fractures.geometry.arcs.size())) << names[i];
    EXPECT_EQ(entry["fitted_arcs"], fractures.geometry.arcs.size());
    if (fractures.count() > 0) {
      EXPECT_EQ(row[16], fmt::format("{}", fractures.geometry.orientations.concentricity)) << names[i];
      EXPECT_EQ(entry["concentricity"].get<double>(), fractures.geometry.orientations.concentricity);
    }
  }
  for (const char* figure : {"phase_M0.5_eps0.002.png", "phase_M1_eps0.002.png", "phase_M1_eps0.002.svg"})
    EXPECT_TRUE(fs::exists(out / "report" / figure)) << figure;
  // The phase diagrams are drawn (tidalcrust.figures) from report/figure_data.json: one per
  // (M2, eps_S), together one point per encounter of the table.
  const Json figures = Json::parse(read_file(out / "report" / "figure_data.json"))["figures"];
  ASSERT_EQ(figures.size(), 2u) << figures.dump();
  std::size_t points = 0;
  for (const char* stem : {"phase_M0.5_eps0.002", "phase_M1_eps0.002"}) {
    const Json& d = figures.at(stem);
    EXPECT_EQ(d["kind"], "phase_diagram");
    EXPECT_EQ(d["x_label"], "pericenter q [R]");
    EXPECT_EQ(d["eq5"]["q"].size(), d["eq5"]["v_q"].size());
    points += d["points"].size();
  }
  EXPECT_EQ(points, names.size());
}

TEST(Report, NothingRunIsOneLineErrorAndWritesNothing) {
  const ScratchFolder scratch("report_empty");
  const auto workflow = sweep_workflow(scratch.path);
  const auto out = scratch.path / "out";
  const auto result = run_cli("report " + quoted(workflow) + " --out " + quoted(out));
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(count_lines(result.err), 1) << result.err;
  EXPECT_NE(result.err.find("nothing has been run for workflow 'reported'"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("relax.h5"), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(out));
}

// A [material] body without integrator.dt has its time step chosen by run from the stretched
// body (stages/time_step.hpp); report resolves it the same way, so an encounter run with that
// time step is finished, not "computed with other values" (issue 28).
TEST(Report, AMaterialBodyWhoseTimeStepRunChoseIsFinishedNotStale) {
  const ScratchFolder scratch("report_material");
  const fs::path out = scratch.path / "out";
  const std::string workflow = quoted(fs::path(TIDALCRUST_SOURCE_DIR) / "workflows" / "material-L3.toml");
  const std::string shorter =
      " --set relax.duration=0.3 --set relax.settle_duration=0.1 --set relax.stability_probe=false"
      " --set encounter.start_distance=2.0 --set encounter.end_distance=2.0";
  const auto ran = run_cli("run " + workflow + " --only T5 --quiet --out " + quoted(out) + shorter);
  ASSERT_EQ(ran.exit_code, 0) << ran.err;
  const auto r = run_cli("report " + workflow + " --out " + quoted(out) + shorter);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("finished: 1"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("stale"), std::string::npos) << r.out;
}

// A [moon] workflow (docs/moon.md, "Output in SI"): report's table has the SI columns last, each
// the model value beside it in the moon's units; the JSON an "si" object per encounter; and the
// encounter's summary.json and inspect give the same values in SI.
TEST(Report, AMoonsTableHasItsSiColumnsAfterTheModelOnes) {
  const ScratchFolder scratch("report_moon");
  const fs::path workflow = source_file("tests/support/tiny-moon.toml"), out = scratch.path / "out";
  const auto ran = run_cli("run " + quoted(workflow) + " --quiet --out " + quoted(out));
  ASSERT_EQ(ran.exit_code, 0) << ran.err;
  const auto r = run_cli("report " + quoted(workflow) + " --out " + quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const double R_km = 1000, M_kg = 1e21, v_c_km_s = std::sqrt(6.674e-11 * 1e21 / 1e6) / 1e3;
  const double energy_J = 6.674e-11 * 1e21 * 1e21 / 1e6;
  const auto rows = csv_rows(read_file(out / "report" / "sweep.csv"));
  ASSERT_EQ(rows.size(), 2u);
  const auto& header = rows[0];
  ASSERT_EQ(header.size(), 30u);
  EXPECT_EQ(header[22], "after");  // the model columns as before, then SI
  const std::vector<std::string> si_header = {"M2 [kg]", "q [km]", "V_q [km/s]", "largest_network_length [km]",
                                              "total_crack_length [km]", "energy_deposited [J]",
                                              "energy_dissipated [J]"};
  EXPECT_EQ(std::vector<std::string>(header.begin() + 23, header.end()), si_header);
  const auto& row = rows[1];
  ASSERT_EQ(row.size(), header.size());
  const auto cell = [&](std::size_t i) { return std::stod(row.at(i)); };
  EXPECT_NEAR(cell(23), cell(2) * M_kg, 1e-12 * M_kg);
  EXPECT_NEAR(cell(24), 1200, 1e-9);
  EXPECT_NEAR(cell(24), cell(3) * R_km, 1e-9);
  EXPECT_NEAR(cell(25), 0.45, 1e-12);
  EXPECT_NEAR(cell(25), cell(4) * v_c_km_s, 1e-12);
  EXPECT_NEAR(cell(26), cell(11) * R_km, 1e-9 * cell(26));
  EXPECT_NEAR(cell(27), cell(20) * R_km, 1e-9 * cell(27));
  EXPECT_NEAR(cell(28), cell(12) * energy_J, 1e-9 * std::abs(cell(28)));
  EXPECT_GT(cell(27), 0);
  const Json json = Json::parse(read_file(out / "report" / "sweep.json"));
  EXPECT_EQ(json["si"]["moon"]["radius_km"], R_km);
  const Json& e = json["encounters"][0];
  EXPECT_EQ(e["si"]["total_crack_length_km"].get<double>(), cell(27));
  EXPECT_EQ(e["si"]["pericenter_km"].get<double>(), cell(24));

  // The same numbers in the encounter's summary.json and in inspect.
  const Json summary = Json::parse(read_file(out / "A" / "analysis" / "summary.json"));
  EXPECT_EQ(summary["si"]["failures"]["total_crack_length_km"].get<double>(), cell(27));
  EXPECT_EQ(summary["si"]["encounter"]["pericenter_km"].get<double>(), cell(24));
  const auto inspected = run_cli("inspect --json " + quoted(out / "A" / "encounter.h5"));
  ASSERT_EQ(inspected.exit_code, 0) << inspected.err;
  const Json inspect = Json::parse(inspected.out);
  EXPECT_EQ(inspect["si"]["failures"]["total_crack_length_km"].get<double>(), cell(27));
  EXPECT_EQ(inspect["si"]["record"]["pericenter_km"].get<double>(), cell(24));
  const auto table = run_cli("inspect " + quoted(out / "A" / "encounter.h5"));
  EXPECT_NE(table.out.find(" sqrt(GM/R) = 0.45 km/s"), std::string::npos) << table.out;
}
