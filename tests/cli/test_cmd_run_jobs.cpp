// `tidalcrust run --jobs N`: encounters in child processes, N at once, give the same bits as a
// sequential run for any split of the threads; --only works with it; a failed encounter makes the
// command fail naming it while the others finish; SIGTERM stops every child with its mid-stage
// checkpoint and a rerun resumes bit-identically; bad values are one-line errors.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "io/checkpoint_file.hpp"
#include "io/stage_lock.hpp"
#include "io/state_hash.hpp"
#include "support/quick_workflow.hpp"
#include "support/cli_runner.hpp"
#include "support/files.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

/// A small body and a 2 x 2 sweep (encounters M0.5_q1.6_V1.8, M0.5_q1.9_V1.8, M1_q1.6_V1.8,
/// M1_q1.9_V1.8), mid-stage checkpoints every 15 steps.
fs::path sweep_workflow(const fs::path& dir) {
  const auto file = dir / "sweep.toml";
  std::ofstream(file) << small_body_toml("jobs") << R"([encounter]
failure_rule = "paper"
start_distance = 3.0
end_distance = 3.0
checkpoint_interval = 15
[sweep]
perturber_mass = [0.5, 1.0]
pericenter = [1.6, 1.9]
pericenter_speed = [1.8]
)";
  return file;
}

const std::vector<std::string> sweep_names = {"M0.5_q1.6_V1.8", "M0.5_q1.9_V1.8", "M1_q1.6_V1.8", "M1_q1.9_V1.8"};

/// state_hash of every final checkpoint below root (mid-stage ones skipped), by relative path.
std::map<std::string, std::string> final_hashes(const fs::path& root) {
  std::map<std::string, std::string> hashes;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (entry.path().extension() != ".h5" || entry.path().string().find(".mid.") != std::string::npos) continue;
    hashes[fs::relative(entry.path(), root).string()] = state_hash(read_checkpoint(entry.path()).state);
  }
  return hashes;
}

std::string run_args(const fs::path& workflow, const fs::path& out, const std::string& more) {
  return "run " + quoted(workflow) + " --out " + quoted(out) + " " + more;
}

/// The sequential run of the sweep (one thread), computed once.
const std::map<std::string, std::string>& sequential_hashes() {
  static const std::map<std::string, std::string> hashes = [] {
    const ScratchFolder scratch("jobs_sequential");
    const auto result = run_cli(run_args(sweep_workflow(scratch.path), scratch.path / "out", "--quiet --threads 1"));
    EXPECT_EQ(result.exit_code, 0) << result.err;
    return final_hashes(scratch.path / "out");
  }();
  return hashes;
}

}  // namespace

TEST(RunJobs, EncountersInParallelAreBitIdenticalToSequential) {
  const auto& expected = sequential_hashes();
  for (const auto& name : sweep_names) ASSERT_TRUE(expected.count(name + "/encounter.h5")) << name;
  const ScratchFolder scratch("jobs_parallel");
  const auto workflow = sweep_workflow(scratch.path);
  // Three threads over two processes: one child runs with 2 threads, the other with 1.
  const auto result = run_cli(run_args(workflow, scratch.path / "out", "--jobs 2 --threads 3"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("encounters: 4 in 2 processes at once, 1-2 threads each"), std::string::npos) << result.out;
  for (int k = 1; k <= 4; ++k) EXPECT_NE(result.out.find(fmt::format("[{}/4] M", k)), std::string::npos) << result.out;
  for (const auto& name : sweep_names)  // the final summary names every encounter, as a sequential run does
    EXPECT_NE(result.out.find("  " + name + ": "), std::string::npos) << result.out;
  EXPECT_EQ(final_hashes(scratch.path / "out"), expected);
}

TEST(RunJobs, OnlyRunsTheNamedEncountersInParallel) {
  const auto& expected = sequential_hashes();
  const ScratchFolder scratch("jobs_only");
  const auto out = scratch.path / "out";
  const auto result = run_cli(run_args(sweep_workflow(scratch.path), out,
                                       "--quiet --jobs 3 --only M1_q1.6_V1.8 --only M0.5_q1.9_V1.8"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_FALSE(fs::exists(out / "M0.5_q1.6_V1.8"));
  EXPECT_FALSE(fs::exists(out / "M1_q1.9_V1.8"));
  const auto hashes = final_hashes(out);
  for (const auto& name : {"M1_q1.6_V1.8", "M0.5_q1.9_V1.8"}) {
    const std::string file = std::string(name) + "/encounter.h5";
    ASSERT_TRUE(hashes.count(file)) << file;
    EXPECT_EQ(hashes.at(file), expected.at(file)) << file;
  }
}

TEST(RunJobs, FailedEncounterIsNamedAndTheOthersFinish) {
  const ScratchFolder scratch("jobs_failure");
  const auto workflow = sweep_workflow(scratch.path);
  const auto out = scratch.path / "out";
  // This process computes "other values" of one encounter: its child is refused (exit 2).
  fs::create_directories(out / "M1_q1.6_V1.8");
  const LockAttempt held = try_lock_stage(out / "M1_q1.6_V1.8" / "encounter.h5", "0123456789abcdef");
  ASSERT_TRUE(held.lock);
  const auto result = run_cli(run_args(workflow, out, "--quiet --jobs 2"));
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("[M1_q1.6_V1.8] tidalcrust run: error:"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("1 of 4 encounters failed: M1_q1.6_V1.8 (exit 2)"), std::string::npos) << result.err;
  for (const auto& name : sweep_names)
    EXPECT_EQ(fs::exists(out / name / "encounter.h5"), name != "M1_q1.6_V1.8") << name;
}

TEST(RunJobs, SigtermStopsEveryChildAndRerunResumesBitIdentically) {
  const auto& expected = sequential_hashes();
  const ScratchFolder scratch("jobs_sigterm");
  const auto workflow = sweep_workflow(scratch.path);
  const auto out = scratch.path / "out";
  // The body first, so that only the children step; each child is held after the 20th step of its
  // encounter (io/test_points.hpp) and SIGTERM reaches the parent while both compute, on any
  // machine at any load.
  ASSERT_EQ(run_cli(run_args(workflow, out, "--quiet --body-only")).exit_code, 0);
  const fs::path hold = scratch.path / "held";
  BackgroundCli running(run_args(workflow, out, "--quiet --jobs 2 --threads 2"), hold_at_step(20, hold));
  ASSERT_TRUE(wait_while_running(running.pid(), [&] { return count_lines(read_file(hold)) == 2; }));
  kill(running.pid(), SIGTERM);
  const auto stopped = running.finish();
  EXPECT_EQ(stopped.exit_code, 130) << stopped.err;
  EXPECT_NE(stopped.err.find("rerun the same command to resume"), std::string::npos) << stopped.err;
  EXPECT_FALSE(fs::exists(out / sweep_names.back() / "encounter.h5")) << "no new encounter starts after the stop";
  const auto resumed = run_cli(run_args(workflow, out, "--jobs 2"));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(final_hashes(out), expected);
}

TEST(RunJobs, BadJobCountIsOneLineErrorAndWritesNothing) {
  const ScratchFolder scratch("jobs_bad");
  const auto workflow = sweep_workflow(scratch.path);
  for (const std::string value : {"0", "-2", "257", "two"}) {
    const auto result = run_cli(run_args(workflow, scratch.path / "out", "--jobs " + value));
    EXPECT_EQ(result.exit_code, 2) << value;
    EXPECT_EQ(count_lines(result.err), 1) << result.err;
    EXPECT_NE(result.err.find("jobs"), std::string::npos) << result.err;
    EXPECT_FALSE(fs::exists(scratch.path / "out")) << value;
  }
}

// The children of `run --jobs` run the very binary the parent started (issue 28): the file at
// the program's path is replaced (rebuilt or reinstalled) while the parent relaxes the body, and
// every encounter still runs and finishes. The parent is held after its 5th step until the file
// is replaced; the children, which inherit the hold, are released as they arrive.
TEST(RunJobs, ChildrenRunTheBinaryTheParentStartedAfterItsFileIsReplaced) {
  const ScratchFolder scratch("jobs_replaced_binary");
  const auto workflow = sweep_workflow(scratch.path);
  const auto out = scratch.path / "out";
  const fs::path program = scratch.path / "bin" / "tidalcrust";
  fs::create_directories(program.parent_path());
  fs::copy_file(TIDALCRUST_EXE, program);
  const fs::path hold = scratch.path / "held";
  const std::string command = fmt::format(
      "exec env TIDALCRUST_TEST_HOLD_AT=step:5 TIDALCRUST_TEST_HOLD_FILE={} {} {} >{} 2>{} </dev/null", quoted(hold),
      quoted(program), run_args(workflow, out, "--quiet --jobs 2 --threads 2"), quoted(scratch.path / "out.txt"),
      quoted(scratch.path / "err.txt"));
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  ASSERT_TRUE(wait_while_running(pid, [&] { return count_lines(read_file(hold)) == 1; }));
  const fs::path replacement = scratch.path / "bin" / "new";
  std::ofstream(replacement) << "#!/bin/sh\nexit 99\n";
  fs::permissions(replacement, fs::perms::owner_all);
  fs::rename(replacement, program);  // as `install` or a linker replaces a binary
  while (is_running(pid)) {
    std::error_code ec;
    fs::remove(hold, ec);  // releases the parent, then each child at its 5th step
    ::usleep(2000);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << read_file(scratch.path / "err.txt");
  for (const auto& name : sweep_names) EXPECT_TRUE(fs::exists(out / name / "encounter.h5")) << name;
}
