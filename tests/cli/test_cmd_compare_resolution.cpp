// `tidalcrust compare --resolution`: one small real encounter run at shell levels 1 and 2, the
// table sorted coarsest first, its JSON equal to each encounter's own summary.json, the files of
// --out, and the one-line errors (exit 2) for input that is not one encounter at two resolutions.
#include <gtest/gtest.h>

#include <algorithm>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "io/checkpoint_file.hpp"
#include "io/json.hpp"
#include "support/cli_runner.hpp"
#include "support/files.hpp"
#include "support/quick_workflow.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

class CompareResolutionCli : public ::testing::Test {
 protected:
  /// The small test body with eps_S = 0.002 and one strong encounter, run once per suite at
  /// shell levels 1 and 2 (`--set shell.level=1`): two bodies of one material layout, one
  /// encounter.
  static void SetUpTestSuite() {
    scratch = std::make_unique<ScratchFolder>("compare_resolution");
    const fs::path workflow = scratch->path / "res.toml";
    std::ofstream(workflow) << small_body_toml("res", "failure_strain = 0.002\n") << R"([encounter]
failure_rule = "paper"
start_distance = 2.2
end_distance = 2.2
[[encounters]]
name = "S"
perturber_mass = 1.0
pericenter = 1.5
pericenter_speed = 1.6
)";
    for (const int level : {1, 2}) {
      const fs::path out = scratch->path / ("L" + std::to_string(level));
      const auto r = run_cli("run " + quoted(workflow) + " --out " + quoted(out) + " --quiet --set shell.level=" +
                             std::to_string(level));
      ASSERT_EQ(r.exit_code, 0) << r.err;
    }
  }
  static void TearDownTestSuite() { scratch.reset(); }

  static fs::path encounter(int level) { return scratch->path / ("L" + std::to_string(level)) / "S" / "encounter.h5"; }
  static inline std::unique_ptr<ScratchFolder> scratch;
};

}  // namespace

TEST_F(CompareResolutionCli, RowsCoarsestFirstAndEqualToEachEncountersSummary) {
  // Finest first on the command line: the table sorts by shell node count.
  const auto r = run_cli("compare --resolution " + quoted(encounter(2)) + " " + quoted(encounter(1)) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json json = Json::parse(r.out);
  ASSERT_EQ(json["rows"].size(), 2u) << r.out;
  EXPECT_EQ(json["encounter"]["name"], "S");
  EXPECT_EQ(json["encounter"]["pericenter"], 1.5);
  for (const int level : {1, 2}) {
    const Json& row = json["rows"][static_cast<std::size_t>(level - 1)];
    EXPECT_EQ(row["shell_level"], level);
    EXPECT_EQ(row["shell_nodes"], level == 1 ? 42 : 162);
    EXPECT_EQ(row["file"], encounter(level).string());
    // run analysed each encounter: its summary.json holds the same failure statistics.
    const Json summary = Json::parse(read_file(encounter(level).parent_path() / "analysis" / "summary.json"));
    EXPECT_EQ(row["failures"], summary["failures"]) << level;
    EXPECT_EQ(row["state_hash"], summary["state_hash"]);
    const Checkpoint c = read_checkpoint(encounter(level));
    EXPECT_EQ(row["particles"], c.body.particle_count());
    EXPECT_EQ(row["dt"], c.stage.clock.dt);
  }
  EXPECT_GT(json["rows"][1]["failures"]["count"].get<int>(), 0) << "the level-2 crust cracks";
  EXPECT_TRUE(json["rows"][0]["change_percent"]["failed_area_fraction"].is_null());
  const double coarse = json["rows"][0]["failures"]["failed_area_fraction"].get<double>();
  const double fine = json["rows"][1]["failures"]["failed_area_fraction"].get<double>();
  if (coarse > 0) {
    EXPECT_DOUBLE_EQ(json["rows"][1]["change_percent"]["failed_area_fraction"].get<double>(),
                     100 * (fine - coarse) / coarse);
  }

  // The text table: the level-1 row above the level-2 row.
  const auto text = run_cli("compare --resolution " + quoted(encounter(2)) + " " + quoted(encounter(1)));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  const auto level1 = text.out.find("level 1: " + encounter(1).string());
  const auto level2 = text.out.find("level 2: " + encounter(2).string());
  ASSERT_NE(level1, std::string::npos) << text.out;
  ASSERT_NE(level2, std::string::npos) << text.out;
  EXPECT_LT(level1, level2);
  EXPECT_NE(text.out.find("\n    1      42 "), std::string::npos) << text.out;
  EXPECT_LT(text.out.find("\n    1      42 "), text.out.find("\n    2     162 "));
}

TEST_F(CompareResolutionCli, OutWritesJsonCsvAndOneMapPerLevel) {
  const fs::path out = scratch->path / "study";
  const auto r = run_cli("compare --resolution " + quoted(encounter(1)) + " " + quoted(encounter(2)) + " --out " +
                         quoted(out) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Json::parse(read_file(out / "convergence.json")), Json::parse(r.out));
  std::istringstream csv(read_file(out / "convergence.csv"));
  std::vector<std::string> lines;
  for (std::string line; std::getline(csv, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 3u) << "a header and one row per level";
  EXPECT_EQ(lines[0].substr(0, 34), "file,shell_level [1],shell_nodes [");
  EXPECT_EQ(lines[1].find(encounter(1).string() + ",1,42,"), 0u) << lines[1];
  EXPECT_EQ(lines[2].find(encounter(2).string() + ",2,162,"), 0u) << lines[2];
  EXPECT_NE(lines[0].find(",total_crack_length_change [%],state_hash"), std::string::npos) << lines[0];
  for (const std::string& line : lines)  // every row has the header's columns (no commas in the paths)
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), std::count(lines[0].begin(), lines[0].end(), ',')) << line;
  // One figure of two map panels (matplotlib, tidalcrust.figures), drawn from figure_data.json:
  // one panel per level, coarsest first, each holding that level's cracks as its cracks.json does.
  EXPECT_TRUE(fs::exists(out / "convergence_maps.png"));
  EXPECT_TRUE(fs::exists(out / "convergence_maps.svg"));
  const Json data = Json::parse(read_file(out / "figure_data.json"));
  const Json& row = data["figures"]["convergence_maps"];
  EXPECT_EQ(row["kind"], "fracture_map_row");
  ASSERT_EQ(row["panels"].size(), 2u);
  for (const int level : {1, 2}) {
    const Json& panel = row["panels"][static_cast<std::size_t>(level - 1)];
    EXPECT_EQ(panel["title"].get<std::string>().rfind("level " + std::to_string(level) + ",", 0), 0u) << panel["title"];
    // The crust's field (docs/crust.md), which analyze adds to cracks.json, is not drawn on these maps.
    Json cracks = Json::parse(read_file(encounter(level).parent_path() / "analysis" / "cracks.json"));
    cracks.erase("crust");
    EXPECT_EQ(panel["cracks"], cracks);
  }
}

TEST_F(CompareResolutionCli, BadInputIsOneLineNamingTheFileAndWritesNothing) {
  const fs::path out = scratch->path / "refused";
  auto expect_refused = [&](const std::string& files, const fs::path& named, const std::string& what) {
    const auto r = run_cli("compare --resolution " + files + " --out " + quoted(out));
    EXPECT_EQ(r.exit_code, 2) << files << "\n" << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(named.string() + ": " + what), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << "nothing written for bad input";
  };
  const fs::path relaxed = scratch->path / "L1" / "body" / "relax.h5";
  expect_refused(quoted(encounter(1)) + " " + quoted(relaxed), relaxed, "stage is 'relax'");
  expect_refused(quoted(encounter(1)), encounter(1), "compare --resolution needs at least two");
  // The level-2 encounter with another pericenter.
  Checkpoint other = read_checkpoint(encounter(2));
  std::get<EncounterRecord>(other.stage.record).encounter.pericenter = 1.7;
  const fs::path moved = scratch->path / "other_q.h5";
  write_checkpoint(moved, other);
  expect_refused(quoted(encounter(1)) + " " + quoted(moved), moved, "another encounter than");
  // Without --resolution, --out is refused and two files of different bodies stay an error.
  auto r = run_cli("compare " + quoted(encounter(1)) + " " + quoted(encounter(1)) + " --out " + quoted(out));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--out is for --resolution only"), std::string::npos) << r.err;
  r = run_cli("compare " + quoted(encounter(1)) + " " + quoted(encounter(2)));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("do not branch from the same body"), std::string::npos) << r.err;
}
