// Issue 24, item 1 and its tests: an [ensemble] runs its members as encounters do (--jobs,
// resume), each member bitwise reproducible across kills; `report` summarises them with the
// interval code (ensembles.csv / .json) from exactly the members' rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/ensemble_statistics.hpp"
#include "io/checkpoint_file.hpp"
#include "io/json.hpp"
#include "io/state_hash.hpp"
#include "support/cli_runner.hpp"
#include "support/files.hpp"
#include "support/quick_workflow.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

/// The small body and one encounter T strong enough to crack it (then the [[encounters]] tables of
/// `more`), as a 3-member ensemble whose [ensemble] table ends with `variation`.
fs::path ensemble_workflow(const fs::path& dir, const std::string& more = "",
                           const std::string& variation = "pericenter_perturbation = 0.005\n") {
  const auto file = dir / "ensemble.toml";
  std::ofstream(file) << small_body_toml("ens", "failure_strain = 0.002\n") << R"([encounter]
failure_rule = "paper"
start_distance = 2.5
end_distance = 2.5
[[encounters]]
name = "T"
perturber_mass = 1.0
pericenter = 1.6
pericenter_speed = 1.8
)" << more << "[ensemble]\nmembers = 3\n"
                      << variation;
  return file;
}

std::string member_hash(const fs::path& out, int k) {
  return state_hash(read_checkpoint(out / fmt::format("T_m{}", k) / "encounter.h5").state);
}

/// Runs `workflow` into `killed`, each process killed at step first + spacing * attempt (steps
/// counted from its start) until one finishes, then once more: every member T_m<k> must end with
/// the bits of `hashes` (the uninterrupted run's), after at least three kills.
void expect_resumed_members_bitwise(const fs::path& workflow, const fs::path& killed, int first, int spacing,
                                    const std::vector<std::string>& hashes) {
  int kills = 0;
  for (int attempt = 0; attempt < 40; ++attempt) {
    const auto r = run_cli("run " + quoted(workflow) + " --out " + quoted(killed) + " --quiet",
                           fmt::format("TIDALCRUST_TEST_KILL_AT=step:{}", first + spacing * attempt));
    if (r.exit_code == 0) break;
    ++kills;
  }
  EXPECT_GE(kills, 3);
  ASSERT_EQ(run_cli("run " + quoted(workflow) + " --out " + quoted(killed) + " --quiet").exit_code, 0);
  for (std::size_t k = 0; k < hashes.size(); ++k)
    EXPECT_EQ(member_hash(killed, static_cast<int>(k)), hashes[k]) << k;
}

}  // namespace

TEST(Ensemble, MembersRunResumeBitwiseAndAreSummarisedWithIntervals) {
  const ScratchFolder scratch("ensemble");
  const auto workflow = ensemble_workflow(scratch.path);
  const auto straight = scratch.path / "straight";
  const auto ran = run_cli("run " + quoted(workflow) + " --out " + quoted(straight) + " --quiet --jobs 2");
  ASSERT_EQ(ran.exit_code, 0) << ran.err;
  std::vector<std::string> hashes;
  for (int k = 0; k < 3; ++k) hashes.push_back(member_hash(straight, k));
  // The members are different trajectories: their final states differ.
  EXPECT_NE(hashes[0], hashes[1]);
  EXPECT_NE(hashes[1], hashes[2]);
  // Each member's q is the stratified offset of the table (u = -2/3, 0, 2/3 of 0.005).
  const Checkpoint m0 = read_checkpoint(straight / "T_m0" / "encounter.h5");
  EXPECT_DOUBLE_EQ(m0.stage.as<EncounterRecord>().encounter.pericenter, 1.6 * (1 - 0.005 * 2.0 / 3.0));

  // Killed at steps counted from the start of each process, and resumed: the same bits per member.
  expect_resumed_members_bitwise(workflow, scratch.path / "killed", 150, 90, hashes);

  // The report: one ensemble row whose statistics are those of the members' rows.
  const auto report = run_cli("report " + quoted(workflow) + " --out " + quoted(straight));
  ASSERT_EQ(report.exit_code, 0) << report.err;
  EXPECT_NE(report.out.find("ensemble T: 3 of 3 members finished"), std::string::npos) << report.out;
  const Json sweep = Json::parse(read_file(straight / "report" / "sweep.json"));
  const Json ensembles = Json::parse(read_file(straight / "report" / "ensembles.json"));
  ASSERT_EQ(ensembles["ensembles"].size(), 1u);
  const Json& row = ensembles["ensembles"][0];
  EXPECT_EQ(row["name"], "T");
  EXPECT_EQ(row["pericenter"].get<double>(), 1.6);
  EXPECT_EQ(row["finished"], 3);
  std::vector<double> failures, lengths;
  std::size_t cracked = 0;
  for (const auto& e : sweep["encounters"]) {
    failures.push_back(e["failures"].get<double>());
    lengths.push_back(e["total_crack_length"].get<double>());
    cracked += e["failures"].get<int>() > 0;
  }
  ASSERT_EQ(failures.size(), 3u);
  EXPECT_GT(failures[0] + failures[1] + failures[2], 0) << "the encounter must crack the crust to test anything";
  const double delta = 0.005;
  const std::vector<double> offsets = {-delta * 2 / 3, 0, delta * 2 / 3};
  const SampleSummary expected = summarize_about_trend(failures, offsets);
  EXPECT_DOUBLE_EQ(row["statistics"]["failures"]["mean"].get<double>(), expected.mean);
  EXPECT_DOUBLE_EQ(row["statistics"]["failures"]["sd"].get<double>(), expected.standard_deviation);
  EXPECT_DOUBLE_EQ(row["statistics"]["failures"]["low"].get<double>(), expected.low);
  EXPECT_DOUBLE_EQ(row["statistics"]["total_crack_length"]["mean"].get<double>(), summarize_about_trend(lengths, offsets).mean);
  EXPECT_EQ(row["cracked"]["members"], cracked);
  // The rose's four sectors are statistics of every cracked member; their shares sum to 1 in each
  // member, so their means (each a least-squares line at offset 0) sum to 1.
  ASSERT_EQ(cracked, 3u) << "every member must crack the crust to test the rose";
  double rose_sum = 0;
  for (const char* sector : {"rose_0", "rose_45", "rose_90", "rose_135"}) {
    const Json& stat = row["statistics"][sector];
    EXPECT_EQ(stat["count"].get<std::size_t>(), 3u) << sector;
    rose_sum += stat["mean"].get<double>();
  }
  EXPECT_NEAR(rose_sum, 1, 1e-12);
  EXPECT_NE(ensembles["method"].get<std::string>().find("Student t with n - 2"), std::string::npos);
  const std::string csv = read_file(straight / "report" / "ensembles.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 2) << csv;
  EXPECT_NE(csv.find("failures_mean [1],failures_sd [1],failures_low [1],failures_high [1]"), std::string::npos);

  // compare --ensembles: an ensemble against itself is within the noise in every statistic; a
  // file that is not an ensemble table is a one-line error naming it.
  const auto table = straight / "report" / "ensembles.json";
  const auto same = run_cli("compare --ensembles " + quoted(table) + " " + quoted(table) + " --json");
  ASSERT_EQ(same.exit_code, 0) << same.err;
  const Json compared = Json::parse(same.out);
  ASSERT_EQ(compared["ensembles"].size(), 1u);
  for (const auto& s : compared["ensembles"][0]["statistics"]) {
    EXPECT_FALSE(s["beyond_noise"].get<bool>()) << s;
    if (s["difference"].is_number()) {
      EXPECT_EQ(s["difference"].get<double>(), 0) << s;
    }
  }
  // An ensemble no member of which finished (a workflow run with --only) is left out.
  Json with_empty = Json::parse(read_file(table));
  Json empty = with_empty["ensembles"][0];
  empty["name"] = "E";
  empty["finished"] = 0;
  with_empty["ensembles"].push_back(empty);
  const auto table_with_empty = scratch.path / "with-empty.json";
  write_file(table_with_empty, with_empty.dump());
  const auto skipped = run_cli("compare --ensembles " + quoted(table_with_empty) + " " + quoted(table_with_empty) + " --json");
  ASSERT_EQ(skipped.exit_code, 0) << skipped.err;
  EXPECT_EQ(Json::parse(skipped.out)["ensembles"], compared["ensembles"]);
  // --pair names the two ensembles (here the same one); a name neither table has is a one-line error.
  const auto paired = run_cli("compare --ensembles " + quoted(table) + " " + quoted(table) + " --pair T:T --json");
  ASSERT_EQ(paired.exit_code, 0) << paired.err;
  EXPECT_EQ(Json::parse(paired.out)["ensembles"], compared["ensembles"]);
  for (const std::string pair : {"T:V", "T", ":T"}) {
    const auto unknown = run_cli("compare --ensembles " + quoted(table) + " " + quoted(table) + " --pair " + pair);
    EXPECT_EQ(unknown.exit_code, 2) << pair;
    EXPECT_EQ(count_lines(unknown.err), 1) << unknown.err;
    EXPECT_NE(unknown.err.find(pair == "T:V" ? table.string() + ": no ensemble named 'V'" : "expected NAME_IN_A:NAME_IN_B"),
              std::string::npos)
        << unknown.err;
  }
  const auto sweep_file = straight / "report" / "sweep.json";
  const auto bad = run_cli("compare --ensembles " + quoted(table) + " " + quoted(sweep_file));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find(sweep_file.string() + ": not an ensemble table"), std::string::npos) << bad.err;
  EXPECT_EQ(count_lines(bad.err), 1) << bad.err;

  // The report of an ensemble none of whose members has run yet (four members: other pericenters)
  // says so, with no statistics of nothing ("nan").
  const auto unrun = run_cli("report " + quoted(workflow) + " --set ensemble.members=4 --out " + quoted(straight));
  ASSERT_EQ(unrun.exit_code, 0) << unrun.err;
  EXPECT_NE(unrun.out.find("ensemble T: 0 of 4 members finished, 0 cracked\n"), std::string::npos) << unrun.out;
  EXPECT_EQ(unrun.out.find("nan"), std::string::npos) << unrun.out;
}

// Issue 24 item 1: an ensemble that varies the body. Member k of every encounter branches from the
// body of seed workflow.seed + k, built, stretched and relaxed once in its own folder
// (body-seed<N>/) and shared by the encounters of that member; each member resumes bitwise; the
// report summarises the members without a trend (n - 1).
TEST(Ensemble, MembersOnBodiesOfTheirOwnSeedShareThemAndResumeBitwise) {
  const ScratchFolder scratch("ensemble-seeds");
  const auto workflow = ensemble_workflow(scratch.path, "[[encounters]]\nname = \"U\"\nperturber_mass = 0.5\npericenter = "
                                                        "1.7\npericenter_speed = 1.8\n",
                                          "vary = \"body_seed\"\n");
  const auto straight = scratch.path / "straight";
  const auto ran = run_cli("run " + quoted(workflow) + " --out " + quoted(straight) + " --quiet --jobs 2");
  ASSERT_EQ(ran.exit_code, 0) << ran.err;
  // small_body_toml's seed is 3: bodies 3 (body/), 4 and 5, and no other body folder.
  std::vector<std::string> bodies;
  for (const auto& entry : fs::directory_iterator(straight))
    if (entry.path().filename().string().starts_with("body")) bodies.push_back(entry.path().filename().string());
  std::sort(bodies.begin(), bodies.end());
  EXPECT_EQ(bodies, (std::vector<std::string>{"body", "body-seed4", "body-seed5"}));
  const auto relaxed_hash = [&](const std::string& dir) {
    return state_hash(read_checkpoint(straight / dir / "relax.h5").state);
  };
  const auto parent_of = [&](const fs::path& out, const std::string& name) {
    return read_checkpoint(out / name / "encounter.h5").stage.parent_hash;
  };
  const std::string body_dirs[] = {"body", "body-seed4", "body-seed5"};
  std::vector<std::string> hashes;
  for (int k = 0; k < 3; ++k) {
    const std::string& dir = body_dirs[k];
    EXPECT_EQ(parent_of(straight, fmt::format("T_m{}", k)), relaxed_hash(dir)) << k;
    EXPECT_EQ(parent_of(straight, fmt::format("U_m{}", k)), relaxed_hash(dir)) << k;  // one body per member
    // The body's own seed is what built it; every member flies its encounter's own orbit.
    EXPECT_NE(read_checkpoint(straight / dir / "build.h5").config_toml.find(fmt::format("\nseed = {}  #", 3 + k)),
              std::string::npos)
        << dir;
    EXPECT_EQ(read_checkpoint(straight / fmt::format("T_m{}", k) / "encounter.h5")
                  .stage.as<EncounterRecord>()
                  .encounter.pericenter,
              1.6);
    hashes.push_back(member_hash(straight, k));
  }
  EXPECT_NE(relaxed_hash("body"), relaxed_hash("body-seed4"));
  EXPECT_NE(relaxed_hash("body-seed4"), relaxed_hash("body-seed5"));

  // Killed at steps counted from the start of each process (in the body chains of the other seeds
  // too), and resumed: the same bits per member.
  expect_resumed_members_bitwise(workflow, scratch.path / "killed", 200, 250, hashes);

  // The report: every member finished and judged current against its own body; plain statistics.
  const auto report = run_cli("report " + quoted(workflow) + " --out " + quoted(straight));
  ASSERT_EQ(report.exit_code, 0) << report.err;
  EXPECT_NE(report.out.find("ensemble T: 3 of 3 members finished"), std::string::npos) << report.out;
  EXPECT_NE(report.out.find("ensemble U: 3 of 3 members finished"), std::string::npos) << report.out;
  const Json sweep = Json::parse(read_file(straight / "report" / "sweep.json"));
  std::vector<double> failures;
  for (const auto& e : sweep["encounters"]) {
    EXPECT_EQ(e["status"], "finished") << e;
    if (e["name"].get<std::string>().starts_with("T_")) failures.push_back(e["failures"].get<double>());
  }
  ASSERT_EQ(failures.size(), 3u);
  const Json ensembles = Json::parse(read_file(straight / "report" / "ensembles.json"));
  EXPECT_EQ(ensembles["vary"], "body_seed");
  EXPECT_NE(ensembles["method"].get<std::string>().find("n - 1 degrees of freedom"), std::string::npos);
  const Json& row = ensembles["ensembles"][0];
  const SampleSummary expected = summarize_sample(failures);
  EXPECT_DOUBLE_EQ(row["statistics"]["failures"]["mean"].get<double>(), expected.mean);
  EXPECT_DOUBLE_EQ(row["statistics"]["failures"]["sd"].get<double>(), expected.standard_deviation);
  EXPECT_EQ(row["statistics"]["failures"]["degrees_of_freedom"].get<double>(), 2.0);

  // A folder the workflow does not name (a member dropped from the ensemble, here a copy of T_m1)
  // that branched from another seed's body is that body's: the scan of the workflow's own body
  // leaves it alone.
  fs::copy(straight / "T_m1", straight / "X_m1", fs::copy_options::recursive);
  fs::remove(straight / "body" / "encounters-checked");
  const auto again = run_cli("run " + quoted(workflow) + " --out " + quoted(straight) + " --only T_m0");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_TRUE(fs::exists(straight / "X_m1" / "encounter.h5")) << again.out;
  EXPECT_EQ(again.out.find("removed the encounter"), std::string::npos) << again.out;

  // A member's body changed under it (here: removed and rebuilt from another seed's files) makes
  // that member's encounters stale in the report, the others stay finished.
  fs::copy_file(straight / "body-seed5" / "relax.h5", straight / "body-seed4" / "relax.h5",
                fs::copy_options::overwrite_existing);
  const auto stale = run_cli("report " + quoted(workflow) + " --out " + quoted(straight));
  ASSERT_EQ(stale.exit_code, 0) << stale.err;
  EXPECT_NE(stale.out.find("stale: 2: T_m1 (branched from another relaxed body"), std::string::npos) << stale.out;
}
