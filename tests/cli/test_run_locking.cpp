// Runs that cannot collide and outputs that cannot be stale (issue 10, items 4 and 5): two `run`s
// on one folder computing different versions of one encounter cannot both succeed; two `run`s of
// different encounters share the body chain (computed once) and run side by side; a stale lock is
// taken over; a held one makes the single-stage commands refuse; after a changed value no
// snapshot, figure or summary of the superseded encounter remains or is used.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/checkpoint_file.hpp"
#include "io/checkpoint_names.hpp"
#include "io/json.hpp"
#include "io/stage_lock.hpp"
#include "io/state_hash.hpp"
#include "support/cli_runner.hpp"
#include "support/files.hpp"
#include "support/processes.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

/// quick.toml with a shorter relaxation and encounter, no stability probe (the locking does not
/// depend on them) and one thread (two processes share the cores), into `out`.
std::string quick_run(const fs::path& out, const fs::path& workflow = workflow_file("quick.toml")) {
  return "run " + quoted(workflow) + " --out " + quoted(out) +
         " --threads 1 --set relax.duration=1.5 --set relax.settle_duration=0.5 --set relax.stability_probe=false"
         " --set encounter.start_distance=2.4 --set encounter.end_distance=2.4";
}

/// quick.toml with a second, weaker encounter "weak".
fs::path two_encounter_workflow(const fs::path& dir) {
  const fs::path file = dir / "two.toml";
  std::ofstream(file) << read_file(workflow_file("quick.toml"))
                      << "\n[[encounters]]\nname = \"weak\"\nperturber_mass = 0.3\npericenter = 2.0\n"
                         "pericenter_speed = 1.7\n";
  return file;
}

/// Everything in an encounter folder belongs to its encounter.h5: each snapshot has its
/// fingerprint and parent, summary.json its state_hash and only snapshots that are there and
/// belong to it.
void expect_consistent_encounter(const fs::path& dir) {
  const fs::path file = dir / "encounter.h5";
  const Checkpoint encounter = read_checkpoint(file);
  const auto snapshots = find_snapshots(file);
  EXPECT_FALSE(snapshots.empty());
  for (const auto& s : snapshots) {
    const Checkpoint snapshot = read_checkpoint(s.file);
    EXPECT_EQ(snapshot.stage.fingerprint, encounter.stage.fingerprint) << s.file;
    EXPECT_EQ(snapshot.stage.parent_hash, encounter.stage.parent_hash) << s.file;
    EXPECT_LE(s.step, encounter.state.step) << s.file;
  }
  const Json summary = Json::parse(read_file(dir / "analysis" / "summary.json"));
  EXPECT_EQ(summary["state_hash"], state_hash(encounter.state));
  ASSERT_FALSE(summary["snapshots"].empty());
  for (const auto& listed : summary["snapshots"]) {
    const fs::path snapshot = listed["file"].get<std::string>();
    ASSERT_TRUE(fs::exists(snapshot)) << snapshot;
    const Checkpoint c = read_checkpoint(snapshot);
    EXPECT_EQ(c.stage.fingerprint, encounter.stage.fingerprint) << snapshot;
    EXPECT_EQ(c.stage.parent_hash, encounter.stage.parent_hash) << snapshot;
  }
  EXPECT_FALSE(fs::exists(dir / "encounter.mid.h5"));
  EXPECT_FALSE(fs::exists(lock_path(file)));
}

// Every `run` (each `--jobs` child, each Slurm task) first checks the encounter folders for
// ones branched from another body, holding each one's lock for a moment with an empty identity.
// A sibling starting that encounter meanwhile waits for it instead of calling it "other values"
// (seen in a 60-encounter `--jobs 2` sweep before the fix).
TEST(RunLocking, AnotherProcessCheckingTheFolderIsWaitedFor) {
  const ScratchFolder scratch("lock_scan");
  const fs::path out = scratch.path / "out";
  ASSERT_EQ(run_cli(quick_run(out) + " --quiet --body-only").exit_code, 0);
  const fs::path encounter = out / "strong" / "encounter.h5";
  fs::create_directories(encounter.parent_path());
  LockAttempt scan = try_lock_stage(encounter, "");
  ASSERT_TRUE(scan.lock);
  // The lock is released only once the run says it waits for it (stdout line-buffered, so the
  // line shows while it runs): the wait is tested on any machine.
  BackgroundCli run(quick_run(out) + " --only strong", "stdbuf -oL");
  const std::string waiting = ": waiting for pid " + std::to_string(getpid()) + " on host " + this_host();
  EXPECT_TRUE(wait_while_running(run.pid(), [&] { return read_file(run.out_file()).find(waiting) != std::string::npos; }));
  scan.lock.reset();
  const CliResult result = run.finish();
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err.find("other values"), std::string::npos) << result.err;
  EXPECT_TRUE(fs::exists(encounter));
}

}  // namespace

// Issue 28, item 6: two workflows with different bodies started on one empty folder. The first
// stalls between its check of the folder's body and the lock of its first stage (as on a file
// system that hangs for seconds); the second builds its body meanwhile. The first then finds the
// other body under the lock and refuses (exit 2, one line naming the folder and both bodies);
// the second's files are as it wrote them.
TEST(RunLocking, TwoBodiesOnOneEmptyFolderCannotBothWin) {
  const ScratchFolder scratch("lock_bodies");
  const fs::path out = scratch.path / "out";
  const fs::path hold = scratch.path / "held";
  const std::string stall = "env TIDALCRUST_TEST_HOLD_AT=body-check:1 TIDALCRUST_TEST_HOLD_FILE=" + quoted(hold);
  BackgroundCli first(quick_run(out) + " --quiet --body-only", stall);
  ASSERT_TRUE(wait_while_running(first.pid(), [&] { return fs::exists(hold); }));
  const CliResult second = run_cli(quick_run(out) + " --quiet --body-only --set workflow.seed=4");
  ASSERT_EQ(second.exit_code, 0) << second.err;
  std::vector<std::string> written;
  for (const char* name : {"build.h5", "stretch.h5", "relax.h5"}) written.push_back(read_file(out / "body" / name));
  fs::remove(hold);
  const CliResult loser = first.finish();
  EXPECT_EQ(loser.exit_code, 2) << loser.err;
  EXPECT_EQ(count_lines(loser.err), 1) << loser.err;
  const std::string build_state = state_hash(read_checkpoint(out / "body" / "build.h5").state);
  EXPECT_NE(loser.err.find((out / "body" / "build.h5").string() + ": the output folder holds checkpoints of a different "
                           "body: the body of workflow 'quick' (build state " + build_state + "), not the body of "
                           "workflow 'quick' this run builds (first difference 'workflow.seed = 4' -> 'workflow.seed = 7')"),
            std::string::npos)
      << loser.err;
  int i = 0;
  for (const char* name : {"build.h5", "stretch.h5", "relax.h5"})
    EXPECT_TRUE(read_file(out / "body" / name) == written[i++]) << name << " was changed";
}

// Issue 28, item 7: on a file system without flock (NFS `nolock`; injected: flock fails with
// ENOLCK) every stage used to wait 10 s for its own lock file and then "take over the stale lock
// of a process that has not named itself". Now each stage holds the lock file it creates.
TEST(RunLocking, WithoutFlockARunHoldsItsOwnLockFiles) {
  const ScratchFolder scratch("lock_noflock_run");
  const fs::path out = scratch.path / "out";
  const CliResult result = run_cli(quick_run(out) + " --set relax.duration=0.5 --set relax.settle_duration=0.2",
                                   "TIDALCRUST_TEST_FLOCK_ERROR=ENOLCK");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err.find("took over"), std::string::npos) << result.err;
  EXPECT_EQ(result.out.find("waiting for"), std::string::npos) << result.out;
  for (const auto& entry : fs::recursive_directory_iterator(out))
    EXPECT_EQ(entry.path().string().find(".lock"), std::string::npos) << entry.path();
}

TEST(RunLocking, ConcurrentRunsWithOtherValuesOfOneEncounterCannotBothWin) {
  const ScratchFolder scratch("lock_clash");
  const fs::path out = scratch.path / "out";
  ASSERT_EQ(run_cli(quick_run(out) + " --quiet --body-only").exit_code, 0);
  // The first run is held after the 5th step of its encounter (io/test_points.hpp) while the
  // second, with other values of that encounter, starts: the clash happens on any machine.
  const fs::path hold = scratch.path / "held";
  BackgroundCli first(quick_run(out), hold_at_step(5, hold));
  ASSERT_TRUE(wait_while_running(first.pid(), [&] { return fs::exists(hold); }));
  const std::string other_values = quick_run(out) + " --set encounters.strong.pericenter_speed=1.9";
  const CliResult loser = run_cli(other_values);
  fs::remove(hold);
  const CliResult winner = first.finish();
  EXPECT_EQ(winner.exit_code, 0) << winner.err;
  // The loser refused with one line naming the holder and what it computes.
  EXPECT_EQ(loser.exit_code, 2) << loser.err;
  EXPECT_EQ(count_lines(loser.err), 1) << loser.err;
  EXPECT_NE(loser.err.find("encounter strong is being computed with other values by pid " + std::to_string(first.pid()) +
                           " on host " + this_host() + " (since "),
            std::string::npos)
      << loser.err;
  expect_consistent_encounter(out / "strong");
  // One after the other, the second recomputes the encounter with its values.
  const std::string first_bytes = read_file(out / "strong" / "encounter.h5");
  const CliResult after = run_cli(other_values + " --quiet");
  EXPECT_EQ(after.exit_code, 0) << after.err;
  EXPECT_NE(read_file(out / "strong" / "encounter.h5"), first_bytes);
  expect_consistent_encounter(out / "strong");
  EXPECT_FALSE(fs::exists(lock_path(out / "body" / "relax.h5")));
}

TEST(RunLocking, ConcurrentRunsOfTwoEncountersShareTheBodyAndRunSideBySide) {
  const ScratchFolder scratch("lock_side");
  const fs::path workflow = two_encounter_workflow(scratch.path);
  const fs::path out = scratch.path / "out", sequential = scratch.path / "sequential";
  // "strong" is held after the 5th step of its relaxation (io/test_points.hpp) until "weak" says
  // it waits for it (stdout line-buffered): one computes the body, the other waits, on any machine.
  const fs::path hold = scratch.path / "held";
  BackgroundCli strong(quick_run(out, workflow) + " --only strong", hold_at_step(5, hold));
  ASSERT_TRUE(wait_while_running(strong.pid(), [&] { return fs::exists(hold); }));
  BackgroundCli weak(quick_run(out, workflow) + " --only weak", "stdbuf -oL");
  const std::string waiting = ": waiting for pid " + std::to_string(strong.pid()) + " on host ";
  EXPECT_TRUE(wait_while_running(weak.pid(), [&] { return read_file(weak.out_file()).find(waiting) != std::string::npos; }));
  fs::remove(hold);
  const CliResult a = strong.finish(), b = weak.finish();
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  // The body chain was computed once: one process built it, the other waited for it (one line
  // naming the holder) and then found it up to date.
  const bool a_built = a.out.find("build: building the body") != std::string::npos;
  const bool b_built = b.out.find("build: building the body") != std::string::npos;
  EXPECT_NE(a_built, b_built) << a.out << b.out;
  const std::string& waiter = a_built ? b.out : a.out;
  const pid_t builder = a_built ? strong.pid() : weak.pid();
  EXPECT_NE(waiter.find(": waiting for pid " + std::to_string(builder) + " on host "), std::string::npos) << waiter;
  EXPECT_NE(waiter.find("relax: up to date"), std::string::npos) << waiter;

  const CliResult straight = run_cli(quick_run(sequential, workflow) + " --quiet");
  ASSERT_EQ(straight.exit_code, 0) << straight.err;
  for (const char* name : {"strong", "weak"}) {
    const fs::path file = fs::path(name) / "encounter.h5";
    EXPECT_EQ(state_hash(read_checkpoint(out / file).state), state_hash(read_checkpoint(sequential / file).state))
        << name;
    expect_consistent_encounter(out / name);
  }
}

TEST(RunLocking, StaleLocksAreTakenOverAndHeldOnesRefused) {
  const ScratchFolder scratch("lock_stale");
  const fs::path out = scratch.path / "out";
  fs::create_directories(out / "body");
  const long dead = dead_pid();
  write_file(lock_path(out / "body" / "build.h5"),
             "pid=" + std::to_string(dead) + "\nhost=" + this_host() + "\nsince=2026-01-01T00:00:00Z\nidentity=x\n");
  write_file(lock_path(out / "body" / "relax.h5"), "");  // a lock file that names nobody
  const CliResult run = run_cli(quick_run(out) + " --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("build.h5.lock: took over the stale lock of pid " + std::to_string(dead) + " on host " +
                         this_host() + " (since 2026-01-01T00:00:00Z), which no longer runs"),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("relax.h5.lock: took over the stale lock of a process that has not named itself"),
            std::string::npos)
      << run.err;
  for (const char* file : {"body/build.h5", "body/stretch.h5", "body/relax.h5", "strong/encounter.h5"})
    EXPECT_FALSE(fs::exists(lock_path(out / file))) << file;

  // A lock held by a living process: `run` computing another version of the stage and the
  // single-stage commands refuse with exit 2 naming it, and change nothing.
  const fs::path relax = out / "body" / "relax.h5";
  const std::string relax_bytes = read_file(relax);
  LockAttempt held = try_lock_stage(relax, "another version");
  ASSERT_TRUE(held.lock);
  const std::string holder = "pid " + std::to_string(getpid()) + " on host " + this_host();
  const CliResult refused = run_cli(quick_run(out) + " --set relax.damping=40");
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_EQ(count_lines(refused.err), 1) << refused.err;
  EXPECT_NE(refused.err.find("relax is being computed with other values by " + holder), std::string::npos)
      << refused.err;
  const CliResult single = run_cli("relax --from " + quoted(out / "body" / "stretch.h5") + " --out " + quoted(relax));
  EXPECT_EQ(single.exit_code, 2);
  EXPECT_EQ(count_lines(single.err), 1) << single.err;
  EXPECT_NE(single.err.find("relax.h5: is being computed by " + holder), std::string::npos) << single.err;
  EXPECT_EQ(read_file(relax), relax_bytes);
  held.lock->release();

  // A single-stage command takes a stale lock over too.
  const fs::path built = scratch.path / "b.h5";
  write_file(lock_path(built), "pid=" + std::to_string(dead) + "\nhost=" + this_host() + "\nsince=s\nidentity=\n");
  const CliResult build = run_cli("build --config " + quoted(workflow_file("quick.toml")) + " --out " + quoted(built));
  ASSERT_EQ(build.exit_code, 0) << build.err;
  EXPECT_NE(build.err.find("took over the stale lock of pid " + std::to_string(dead)), std::string::npos) << build.err;
  EXPECT_FALSE(fs::exists(lock_path(built)));
}

TEST(RunLocking, ChangedEncounterValueLeavesNoStaleOutputs) {
  const ScratchFolder scratch("lock_rerun");
  const fs::path out = scratch.path / "out";
  ASSERT_EQ(run_cli(quick_run(out) + " --quiet").exit_code, 0);
  const auto old_snapshots = find_snapshots(out / "strong" / "encounter.h5");
  ASSERT_FALSE(old_snapshots.empty());
  const std::string old_snapshot_bytes = read_file(old_snapshots.front().file);

  // A faster pericenter passage: a shorter encounter with other snapshot steps.
  const CliResult changed = run_cli(quick_run(out) + " --quiet --set encounters.strong.pericenter_speed=2.2");
  ASSERT_EQ(changed.exit_code, 0) << changed.err;
  expect_consistent_encounter(out / "strong");  // every old snapshot is gone or overwritten

  // A snapshot of the superseded encounter put back beside the new one is not used by analyze.
  const fs::path intruder = snapshot_path(out / "strong" / "encounter.h5", 1);
  write_file(intruder, old_snapshot_bytes);
  const fs::path again = scratch.path / "again";
  const CliResult analyze =
      run_cli("analyze --from " + quoted(out / "strong" / "encounter.h5") + " --out " + quoted(again));
  ASSERT_EQ(analyze.exit_code, 0) << analyze.err;
  EXPECT_NE(analyze.err.find("belongs to another run of the encounter"), std::string::npos) << analyze.err;
  const Json summary = Json::parse(read_file(again / "summary.json"));
  for (const auto& listed : summary["snapshots"]) EXPECT_NE(listed["file"].get<std::string>(), intruder.string());

}

TEST(RunLocking, RerunAtHalfTimeStepAndSingleStageEncounterLeaveNoStaleSnapshots) {
  const ScratchFolder scratch("lock_rerun_dt");
  const fs::path out = scratch.path / "out";
  // At half the time step, into dt0.5/, with a changed value between the two runs.
  ASSERT_EQ(run_cli(quick_run(out) + " --quiet --dt-factor 0.5").exit_code, 0);
  const CliResult half = run_cli(quick_run(out) + " --quiet --dt-factor 0.5 --set encounter.fail_interval=2");
  ASSERT_EQ(half.exit_code, 0) << half.err;
  expect_consistent_encounter(out / "dt0.5" / "strong");

  // The single-stage encounter command begun anew removes the snapshots of its output's earlier run.
  const fs::path single = scratch.path / "e.h5";
  const std::string relax = quoted(out / "body" / "relax.h5");
  const std::string shorter = " --quiet --threads 1 --set encounter.start_distance=2.4 --set encounter.end_distance=2.4";
  ASSERT_EQ(run_cli("encounter" + shorter + " --from " + relax + " --out " + quoted(single) + " --encounter strong")
                .exit_code,
            0);
  const auto first_single = find_snapshots(single);
  ASSERT_FALSE(first_single.empty());
  ASSERT_EQ(run_cli("encounter" + shorter + " --from " + relax + " --out " + quoted(single) +
                    " --m2 0.5 --q 1.84 --vq 2.2").exit_code,
            0);
  const Checkpoint fresh = read_checkpoint(single);
  for (const auto& s : find_snapshots(single))
    EXPECT_EQ(read_checkpoint(s.file).stage.as<EncounterRecord>().encounter.pericenter_speed, 2.2) << s.file;
  EXPECT_EQ(fresh.stage.as<EncounterRecord>().encounter.pericenter_speed, 2.2);
}

// A changed body chain supersedes every encounter branched from the old relaxed body, also those
// this run does not compute: their files are removed, not left beside the new body.
TEST(RunLocking, ChangedBodyChainRemovesEncountersOfTheOldBody) {
  const ScratchFolder scratch("lock_body");
  const fs::path workflow = two_encounter_workflow(scratch.path);
  const fs::path out = scratch.path / "out";
  ASSERT_EQ(run_cli(quick_run(out, workflow) + " --quiet").exit_code, 0);
  ASSERT_TRUE(fs::exists(out / "weak" / "analysis" / "summary.json"));
  ASSERT_FALSE(find_snapshots(out / "weak" / "encounter.h5").empty());

  const CliResult changed = run_cli(quick_run(out, workflow) + " --only strong --set relax.damping=40");
  ASSERT_EQ(changed.exit_code, 0) << changed.err;
  EXPECT_NE(changed.out.find("weak: removed the encounter, which branched from another relaxed body"),
            std::string::npos)
      << changed.out;
  EXPECT_FALSE(fs::exists(out / "weak" / "encounter.h5"));
  EXPECT_FALSE(fs::exists(out / "weak" / "analysis"));
  EXPECT_TRUE(find_snapshots(out / "weak" / "encounter.h5").empty());
  expect_consistent_encounter(out / "strong");
  EXPECT_EQ(read_checkpoint(out / "strong" / "encounter.h5").stage.parent_hash,
            state_hash(read_checkpoint(out / "body" / "relax.h5").state));
}

// Issue 28, item 9: the encounter folders are checked for ones of another body once per relaxed
// body (body/encounters-checked records it), not by every task of a sweep: a task reads no other
// encounter's files, so a sweep of N encounters costs O(N), not O(N^2). Shown with a folder of
// the old body planted after the check: a task on the same body does not look at it; once the
// record is gone (or names another body), the next run finds and removes it.
TEST(RunLocking, EncounterFoldersAreCheckedOncePerRelaxedBody) {
  const ScratchFolder scratch("lock_checked_once");
  const fs::path workflow = two_encounter_workflow(scratch.path);
  const fs::path out = scratch.path / "out", saved = scratch.path / "weak-of-the-old-body";
  ASSERT_EQ(run_cli(quick_run(out, workflow) + " --quiet").exit_code, 0);
  const fs::path record = out / "body" / "encounters-checked";
  EXPECT_EQ(read_file(record), state_hash(read_checkpoint(out / "body" / "relax.h5").state) + "\n");
  fs::copy(out / "weak", saved, fs::copy_options::recursive);

  const std::string changed = quick_run(out, workflow) + " --only strong --set relax.damping=40";
  ASSERT_EQ(run_cli(changed).exit_code, 0);
  EXPECT_FALSE(fs::exists(out / "weak" / "encounter.h5"));
  const std::string new_body = state_hash(read_checkpoint(out / "body" / "relax.h5").state);
  EXPECT_EQ(read_file(record), new_body + "\n");

  fs::remove_all(out / "weak");
  fs::copy(saved, out / "weak", fs::copy_options::recursive);
  const CliResult task = run_cli(changed);
  ASSERT_EQ(task.exit_code, 0) << task.err;
  EXPECT_EQ(task.out.find("removed the encounter"), std::string::npos) << task.out;
  EXPECT_TRUE(fs::exists(out / "weak" / "encounter.h5"));

  fs::remove(record);
  const CliResult checking = run_cli(changed);
  ASSERT_EQ(checking.exit_code, 0) << checking.err;
  EXPECT_NE(checking.out.find("weak: removed the encounter, which branched from another relaxed body"),
            std::string::npos)
      << checking.out;
  EXPECT_FALSE(fs::exists(out / "weak" / "encounter.h5"));
  EXPECT_EQ(read_file(record), new_body + "\n");
}
