// `tidalcrust inspect` as a user runs it: JSON equal to the report, an aligned table, the counts
// of a built body, and exit code 2 with one line for every kind of damaged file.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>

#include "analysis/inspect_report.hpp"
#include "build_info.hpp"
#include "io/checkpoint_file.hpp"
#include "io/state_hash.hpp"
#include "model/config.hpp"
#include "support/bad_checkpoints.hpp"
#include "support/cli_runner.hpp"
#include "support/files.hpp"
#include "support/quick_workflow.hpp"
#include "support/synthetic_checkpoint.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST(InspectCli, JsonOfAWrittenCheckpoint) {
  const ScratchFolder scratch("inspect_json");
  const fs::path& dir = scratch.path;
  const Checkpoint c = synthetic_checkpoint();
  write_checkpoint(dir / "enc.h5", c);
  const CliResult r = run_cli("inspect " + quoted(dir / "enc.h5") + " --json");
  EXPECT_EQ(r.exit_code, 0);
  // The report of the file as read back: with the provenance its writer stored.
  EXPECT_EQ(r.out, inspect_report_json(build_inspect_report(read_checkpoint(dir / "enc.h5"), (dir / "enc.h5").string())));
  for (const char* key : {"\"counts\": {", "\"derived\": {", "\"conservation\": {", "\"perturber\": {",
                          "\"springs_cross\": 4", "\"time\": 2.25", "\"step\": 1125"})
    EXPECT_TRUE(contains(r.out, key)) << key;
}

TEST(InspectCli, TableIsAlignedAndNamesEveryKey) {
  const ScratchFolder scratch("inspect_table");
  const fs::path& dir = scratch.path;
  write_checkpoint(dir / "enc.h5", synthetic_checkpoint());
  const CliResult r = run_cli("inspect " + quoted(dir / "enc.h5"));
  EXPECT_EQ(r.exit_code, 0);
  // Every "key value" line has its value in one common column.
  std::size_t column = 0;
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);) {
    const auto gap = line.find("  ", line.find_first_not_of(' '));
    if (gap == std::string::npos) continue;  // a section title
    const auto value = line.find_first_not_of(' ', gap);
    if (column == 0) column = value;
    EXPECT_EQ(value, column) << line;
  }
  EXPECT_GT(column, 0u);
  EXPECT_TRUE(contains(r.out, "state_hash" + std::string(column - 10, ' ') + state_hash(synthetic_checkpoint().state)))
      << r.out;
  EXPECT_TRUE(contains(r.out, "\ncounts\n  interior" + std::string(column - 10, ' ') + "1\n")) << r.out;
  EXPECT_TRUE(contains(r.out, "\nfailures\n")) << r.out;
}

TEST(InspectCli, BuiltQuickBodyCountsMatch) {
  const ScratchFolder scratch("inspect_quick");
  const fs::path& dir = scratch.path;
  const Config config = quick_config();
  Checkpoint c = quick_built();
  c.config_toml = to_toml(config);
  write_checkpoint(dir / "body.h5", c);
  const CliResult r = run_cli("inspect " + quoted(dir / "body.h5") + " --json");
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_TRUE(contains(r.out, "\"stage\": \"build\""));
  EXPECT_TRUE(contains(r.out, fmt::format("\"interior\": {}", config.interior.count)));
  EXPECT_TRUE(contains(r.out, "\"shell\": 642"));
  EXPECT_TRUE(contains(r.out, "\"springs_shell\": 1920"));
  EXPECT_TRUE(contains(r.out, "\"faces\": 1280"));
  EXPECT_TRUE(contains(r.out, "\"hinges\": 1920"));
  EXPECT_TRUE(contains(r.out, "\"failed\": 0"));
  EXPECT_FALSE(contains(r.out, "\"E_I\": 0,"));  // a real interior has a modulus
}

TEST(InspectCli, BadFilesExitWithCode2AndAOneLineMessage) {
  const ScratchFolder scratch("inspect_bad");
  const fs::path& dir = scratch.path;
  write_checkpoint(dir / "valid.h5", synthetic_checkpoint());
  for (const auto& bad : make_bad_checkpoints(dir / "valid.h5", dir)) {
    const CliResult json = run_cli("inspect " + quoted(bad.file) + " --json");
    EXPECT_EQ(json.exit_code, 2) << bad.what;
    EXPECT_EQ(std::count(json.err.begin(), json.err.end(), '\n'), 1) << bad.what << ": " << json.err;
    EXPECT_TRUE(contains(json.err, bad.file.string() + ": ")) << bad.what << ": " << json.err;
    EXPECT_TRUE(contains(json.err, bad.expected_message)) << bad.what << ": " << json.err;
    const CliResult stdout_only = run_cli("inspect " + quoted(bad.file));
    EXPECT_EQ(stdout_only.exit_code, 2) << bad.what;
    EXPECT_EQ(stdout_only.out, "") << bad.what;
  }
}

TEST(InspectCli, UsageErrorsExitWithCode2) {
  EXPECT_EQ(run_cli("inspect").exit_code, 2);
  EXPECT_EQ(run_cli("inspect a.h5 b.h5").exit_code, 2);
  EXPECT_EQ(run_cli("inspect --bogus x.h5").exit_code, 2);
  EXPECT_EQ(run_cli("inspect --help").exit_code, 0);
}

TEST(InspectCli, CheckpointOfANewerOrTooOldFormatIsRefusedNamingItsVersion) {
  // One line naming the file, its version and the versions this program reads, exit 2, and the
  // file stays as it was.
  const ScratchFolder scratch("inspect_other_version");
  write_checkpoint(scratch.path / "valid.h5", synthetic_checkpoint());
  const std::string current = std::to_string(checkpoint_format_version);
  const std::pair<std::int64_t, std::string> cases[] = {
      {checkpoint_format_version + 1, "written by a newer tidalcrust (format " +
                                          std::to_string(checkpoint_format_version + 1) + "); this one reads up to " +
                                          current},
      {2, "written in format 2, too old: this tidalcrust reads formats 3 to " + current}};
  for (const auto& [version, expected] : cases) {
    const fs::path file = edited_copy(scratch.path / "valid.h5", scratch.path, fmt::format("v{}.h5", version),
                                      [version](hid_t f) { overwrite_attribute(f, "/checkpoint", "format_version", version); });
    const std::string before = read_file(file);
    const CliResult r = run_cli("inspect " + quoted(file));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_TRUE(contains(r.err, file.string() + ": " + expected)) << r.err;
    EXPECT_EQ(read_file(file), before);
  }
}

TEST(InspectCli, ShowsTheWritersProvenanceAndTheFingerprintOnRequest) {
  const ScratchFolder scratch("inspect_provenance");
  const fs::path file = scratch.path / "enc.h5";
  const Checkpoint c = synthetic_checkpoint();
  write_checkpoint(file, c);
  const CliResult table = run_cli("inspect " + quoted(file));
  EXPECT_EQ(table.exit_code, 0);
  for (const std::string& part : {std::string("  version "), std::string(build_info::version) + "\n",
                                 std::string("  git_commit "), std::string(build_info::git_commit) + "\n",
                                 std::string(build_info::compiler) + "\n", fingerprint_hash(c.stage.fingerprint) + "\n",
                                 std::string(" t_grav\n")})
    EXPECT_TRUE(contains(table.out, part)) << part << "\n" << table.out;
  EXPECT_FALSE(contains(table.out, "integrator.dt = 0.002")) << table.out;
  const CliResult json = run_cli("inspect " + quoted(file) + " --json");
  EXPECT_TRUE(contains(json.out, "\"git_commit\": \"" + std::string(build_info::git_commit) + "\"")) << json.out;
  const CliResult text = run_cli("inspect " + quoted(file) + " --fingerprint");
  EXPECT_EQ(text.exit_code, 0);
  EXPECT_EQ(text.out, c.stage.fingerprint);
  const CliResult both = run_cli("inspect " + quoted(file) + " --json --fingerprint");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_EQ(std::count(both.err.begin(), both.err.end(), '\n'), 1) << both.err;
}
