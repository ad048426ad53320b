// `tidalcrust submit --slurm`: the --dry-run output (job array of the expanded encounters in
// order, throttle, dependency on the body job, requeue, per-task logs, absolute paths) and bad
// options as one-line errors with exit 2 that write nothing. The run on a real Slurm is
// tests/cli/test_submit_slurm.sh.
#include <gtest/gtest.h>

#include <filesystem>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "model/config.hpp"
#include "support/cli_runner.hpp"
#include "support/files.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

/// The lines of `text` from the one after `header` up to the next "# ==>" line.
std::vector<std::string> section(const std::string& text, const std::string& header) {
  std::istringstream in(text);
  std::vector<std::string> lines;
  bool inside = false;
  for (std::string line; std::getline(in, line);) {
    if (line.starts_with("# ==>") || line.starts_with("# the sbatch")) {
      if (inside) break;
      inside = line.find(header) != std::string::npos;
      continue;
    }
    if (inside) lines.push_back(line);
  }
  return lines;
}

bool contains_line(const std::vector<std::string>& lines, const std::string& wanted) {
  for (const auto& line : lines)
    if (line == wanted) return true;
  return false;
}

}  // namespace

TEST(CmdSubmit, DryRunPrintsTheBodyJobAndAThrottledRequeueableArrayOfTheExpandedEncounters) {
  const ScratchFolder scratch("submit_dry");
  const fs::path workflow = source_file("tests/support/sweep-small.toml");
  const fs::path out = scratch.path / "sweep";
  const CliResult r = run_cli(fmt::format("submit {} --slurm --dry-run --max-running 3 --cpus-per-task 2 --time 2:00:00 "
                                          "--partition short --account moons --out {}",
                                          quoted(workflow), quoted(out)));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_FALSE(fs::exists(out)) << "--dry-run wrote " << out;

  // The names file holds exactly the expanded encounters, in the workflow's order.
  std::vector<std::string> expected;
  for (const auto& e : load_config(workflow).encounters) expected.push_back(e.name);
  ASSERT_EQ(expected.size(), 4u);
  EXPECT_EQ(section(r.out, "/slurm/encounters-"), expected) << r.out;

  const auto body = section(r.out, "/slurm/body.sbatch");
  const auto array = section(r.out, "/slurm/encounters.sbatch");
  ASSERT_FALSE(body.empty()) << r.out;
  ASSERT_FALSE(array.empty()) << r.out;
  for (const auto* script : {&body, &array}) {
    for (const char* line : {"#SBATCH --requeue", "#SBATCH --open-mode=append", "#SBATCH --signal=B:TERM@60",
                             "#SBATCH --cpus-per-task=2", "#SBATCH --time=2:00:00", "#SBATCH --partition=short",
                             "#SBATCH --account=moons"})
      EXPECT_TRUE(contains_line(*script, line)) << line << " missing in\n" << r.out;
  }
  EXPECT_TRUE(contains_line(array, "#SBATCH --array=0-3%3")) << r.out;
  EXPECT_TRUE(contains_line(array, "#SBATCH --output=" + (out / "slurm/logs/encounter-%a.log").string())) << r.out;
  EXPECT_TRUE(contains_line(body, "#SBATCH --output=" + (out / "slurm/logs/body-%j.log").string())) << r.out;
  // The runs: this executable and the workflow by absolute path, exec'd so Slurm's SIGTERM
  // reaches tidalcrust itself.
  const std::string run = fmt::format("exec '{}' run '{}' --out '{}'", fs::canonical(TIDALCRUST_EXE).string(),
                                      workflow.string(), out.string());
  EXPECT_EQ(body.back(), run + " --body-only --threads 2") << r.out;
  EXPECT_EQ(array.back(), run + " --only \"$name\" --threads 2") << r.out;
  // The array starts only after the body job succeeded.
  EXPECT_NE(r.out.find("body_job=$(sbatch --parsable '" + (out / "slurm/body.sbatch").string() + "')"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("sbatch --parsable --dependency=afterok:${body_job%%;*} '" +
                       (out / "slurm/encounters.sbatch").string() + "'"),
            std::string::npos)
      << r.out;

  // Without --max-running the array is not throttled.
  const CliResult plain = run_cli(fmt::format("submit {} --slurm --dry-run --out {}", quoted(workflow), quoted(out)));
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_TRUE(contains_line(section(plain.out, "/slurm/encounters.sbatch"), "#SBATCH --array=0-3")) << plain.out;

  // Slurm's forms of a time limit are accepted as written.
  for (const char* time : {"90", "2:30", "1:00:00", "1-0", "1-12:30", "1-12:30:15", "unlimited"}) {
    const CliResult r =
        run_cli(fmt::format("submit {} --slurm --dry-run --time {} --out {}", quoted(workflow), time, quoted(out)));
    EXPECT_EQ(r.exit_code, 0) << time << ": " << r.err;
    EXPECT_NE(r.out.find(fmt::format("#SBATCH --time={}\n", time)), std::string::npos) << time;
  }
}

TEST(CmdSubmit, BadOptionsAreOneLineErrorsWithExitTwoThatWriteAndSubmitNothing) {
  const ScratchFolder scratch("submit_bad");
  const fs::path workflow = source_file("tests/support/sweep-small.toml");
  const fs::path out = scratch.path / "sweep";
  const std::string base = fmt::format("submit {} --out {} ", quoted(workflow), quoted(out));
  const struct {
    std::string args, message;
  } cases[] = {
      {"--dry-run", "name the batch system: --slurm"},
      {"--slurm --dry-run --max-running 0", "--max-running must be at least 1, got 0"},
      {"--slurm --dry-run --max-running -2", "--max-running must be at least 1, got -2"},
      {"--slurm --dry-run --cpus-per-task 0", "--cpus-per-task must be in 1..256, got 0"},
      {"--slurm --dry-run --time 1h", "--time '1h' is not a Slurm time limit"},
      {"--slurm --dry-run --time forever", "--time 'forever' is not a Slurm time limit"},
      {"--slurm --dry-run --time 1:2:3:4", "--time '1:2:3:4' is not a Slurm time limit"},
      {"--slurm --dry-run --time 1", "--time '1' is shorter than 120 s"},
      {"--slurm --dry-run --partition 'a b'", "--partition 'a b' is not a Slurm name"},
  };
  for (const auto& c : cases) {
    const CliResult r = run_cli(base + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args;
    EXPECT_EQ(count_lines(r.err), 1) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
    EXPECT_EQ(r.out, "") << c.args;
  }
  // No sbatch on PATH (and no --dry-run): refused before anything is written.
  const std::string command = fmt::format("PATH=/nonexistent '{}' submit {} --slurm --out {} 2>&1 >/dev/null",
                                          TIDALCRUST_EXE, quoted(workflow), quoted(out));
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string err;
  for (char buffer[256]; fgets(buffer, sizeof buffer, pipe);) err += buffer;
  const int status = pclose(pipe);
  EXPECT_EQ(WEXITSTATUS(status), 2) << err;
  EXPECT_EQ(count_lines(err), 1) << err;
  EXPECT_NE(err.find("sbatch is not on PATH"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(out));
  // An output folder that holds another body: the body job would fail and its array never run.
  const fs::path other = scratch.path / "other";
  fs::create_directories(other / "body");
  const CliResult built = run_cli(fmt::format("build --config {} --set workflow.seed=8 --out {}", quoted(workflow),
                                              quoted(other / "body/build.h5")));
  ASSERT_EQ(built.exit_code, 0) << built.err;
  const CliResult other_body =
      run_cli(fmt::format("submit {} --slurm --out {} --dry-run", quoted(workflow), quoted(other)));
  EXPECT_EQ(other_body.exit_code, 2);
  EXPECT_EQ(count_lines(other_body.err), 1) << other_body.err;
  EXPECT_NE(other_body.err.find("build.h5: the output folder holds checkpoints of a different body"),
            std::string::npos)
      << other_body.err;
  EXPECT_FALSE(fs::exists(other / "slurm"));
  // A workflow error names the file.
  const CliResult missing = run_cli("submit " + quoted(scratch.path / "none.toml") + " --slurm --dry-run");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(count_lines(missing.err), 1) << missing.err;
  EXPECT_NE(missing.err.find("none.toml"), std::string::npos) << missing.err;
}

TEST(CmdSubmit, RunBodyOnlyComputesTheBodyChainAndNoEncounter) {
  // The body job of a submission: `run --body-only`.
  const ScratchFolder scratch("submit_body_only");
  const fs::path workflow = source_file("tests/support/sweep-small.toml");
  const CliResult both = run_cli(fmt::format("run {} --out {} --body-only --only M0.3_q2.2_V1.6", quoted(workflow),
                                             quoted(scratch.path / "both")));
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_EQ(both.err, "tidalcrust run: error: --body-only and --only exclude each other\n");
  EXPECT_FALSE(fs::exists(scratch.path / "both"));

  const fs::path out = scratch.path / "sweep";
  const CliResult r = run_cli(fmt::format("run {} --out {} --body-only --quiet", quoted(workflow), quoted(out)));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "body/relax.h5"));
  std::vector<std::string> folders;
  for (const auto& entry : fs::directory_iterator(out))
    if (entry.is_directory()) folders.push_back(entry.path().filename().string());
  EXPECT_EQ(folders, std::vector<std::string>{"body"});
}

// Issue 24: an [ensemble] workflow's job array holds its members, each a task of its own.
TEST(CmdSubmit, AnEnsembleIsAnArrayOfItsMembers) {
  const ScratchFolder scratch("submit_ensemble");
  const fs::path workflow = scratch.path / "ens.toml";
  write_file(workflow, read_file(source_file("tests/support/sweep-small.toml")) + "\n[ensemble]\nmembers = 3\n");
  const fs::path out = scratch.path / "out";
  const CliResult r = run_cli(fmt::format("submit {} --slurm --dry-run --out {}", quoted(workflow), quoted(out)));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> expected;
  for (const auto& e : load_config(source_file("tests/support/sweep-small.toml")).encounters)
    for (int k = 0; k < 3; ++k) expected.push_back(fmt::format("{}_m{}", e.name, k));
  ASSERT_EQ(expected.size(), 12u);
  EXPECT_EQ(section(r.out, "/slurm/encounters-"), expected) << r.out;
  EXPECT_TRUE(contains_line(section(r.out, "/slurm/encounters.sbatch"), "#SBATCH --array=0-11")) << r.out;
}
