// `tidalcrust run` as a user meets it: killed (SIGKILL) at random steps and in the middle of
// file writes and rerun, it ends with checkpoints bit-identical to an uninterrupted run and never
// leaves a corrupt file under a final name; a finished workflow reruns as a no-op; a changed value reruns exactly the
// stages it affects; bad input exits 2 and touches nothing.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <string>

#include "io/checkpoint_file.hpp"
#include "io/state_hash.hpp"
#include "support/quick_workflow.hpp"
#include "support/bad_checkpoints.hpp"
#include "support/cli_runner.hpp"
#include "support/files.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

/// The quick body with short stages, frequent mid-stage checkpoints and two encounters.
fs::path small_workflow(const fs::path& dir) {
  const auto file = dir / "small.toml";
  std::ofstream(file) << small_body_toml("small") << R"(checkpoint_interval = 15
[encounter]
failure_rule = "paper"
start_distance = 2.2
end_distance = 2.2
checkpoint_interval = 15
[[encounters]]
name = "A"
perturber_mass = 1.0
pericenter = 1.5
pericenter_speed = 1.6
[[encounters]]
name = "B"
perturber_mass = 0.5
pericenter = 1.8
pericenter_speed = 1.7
)";
  return file;
}

/// Every .h5 below root, by relative path, with its state_hash; fails on an invalid one.
std::map<std::string, std::string> hashes_below(const fs::path& root) {
  std::map<std::string, std::string> hashes;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (entry.path().extension() != ".h5") continue;
    const std::string rel = fs::relative(entry.path(), root).string();
    EXPECT_TRUE(is_valid_checkpoint(entry.path())) << rel;
    if (rel.find(".mid.") != std::string::npos) continue;  // mid files are shortcuts, not results
    hashes[rel] = state_hash(read_checkpoint(entry.path()).state);
  }
  return hashes;
}

/// Starts `tidalcrust ARGS` as a child process with its output discarded; `kill_at` (if not
/// empty) is its TIDALCRUST_TEST_KILL_AT (io/test_points.hpp).
pid_t start_cli(const std::vector<std::string>& args, const std::string& kill_at = "") {
  const pid_t pid = fork();
  if (pid == 0) {
    int devnull = ::open("/dev/null", O_WRONLY);
    dup2(devnull, 1);
    dup2(devnull, 2);
    if (!kill_at.empty()) setenv("TIDALCRUST_TEST_KILL_AT", kill_at.c_str(), 1);
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(TIDALCRUST_EXE));
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(TIDALCRUST_EXE, argv.data());
    _exit(127);
  }
  return pid;
}

enum class Ending { finished, killed, other };

/// Runs `tidalcrust ARGS` with the kill point `kill_at` ("step:N" or "write:N"): finished (exit
/// 0) before reaching it, killed there by SIGKILL, or anything else.
Ending run_with_kill_point(const std::vector<std::string>& args, const std::string& kill_at) {
  const pid_t pid = start_cli(args, kill_at);
  int status = 0;
  waitpid(pid, &status, 0);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return Ending::finished;
  if (WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) return Ending::killed;
  return Ending::other;
}

/// Half-written temporaries (`<file>.tmp-<pid>`) below root.
int temporaries_below(const fs::path& root) {
  int count = 0;
  for (const auto& entry : fs::recursive_directory_iterator(root))
    count += entry.path().filename().string().find(".tmp-") != std::string::npos;
  return count;
}

}  // namespace

TEST(RunWorkflow, KilledAtRandomStepsAndMidWriteEndsBitIdenticalToStraightRun) {
  const ScratchFolder scratch("run_kill");
  const fs::path& dir = scratch.path;
  const auto workflow = small_workflow(dir);
  const auto straight = run_cli("run " + quoted(workflow) + " --quiet --out " + quoted(dir / "straight"));
  ASSERT_EQ(straight.exit_code, 0) << straight.err;
  const auto expected = hashes_below(dir / "straight");
  for (const char* final_file : {"body/build.h5", "body/stretch.h5", "body/relax.h5", "A/encounter.h5", "B/encounter.h5"})
    EXPECT_EQ(expected.count(final_file), 1u) << final_file;

  // SIGKILL at points counted in steps and in file writes (io/test_points.hpp), drawn at random
  // but fixed by the seed: the same kills on any machine at any load. Each rerun resumes from what
  // the killed one left. The ranges widen with each attempt, so pieces that are not checkpointed
  // (the stability probe, the analysis) are also passed.
  std::mt19937_64 random(12345);
  const std::vector<std::string> args = {"run", workflow.string(), "--quiet", "--out", (dir / "killed").string()};
  int step_kills = 0, write_kills = 0, half_written = 0;
  bool finished = false;
  for (int attempt = 0; attempt < 40 && !finished; ++attempt) {
    const bool mid_write = attempt % 2 == 1;
    const auto n = 1 + random() % static_cast<unsigned>(mid_write ? 4 + attempt : 20 + 10 * attempt);
    const std::string kill_at = fmt::format("{}:{}", mid_write ? "write" : "step", n);
    const int temporaries_before = fs::exists(dir / "killed") ? temporaries_below(dir / "killed") : 0;
    const Ending ending = run_with_kill_point(args, kill_at);
    ASSERT_NE(ending, Ending::other) << kill_at;
    finished = ending == Ending::finished;
    if (ending == Ending::killed) {
      ++(mid_write ? write_kills : step_kills);
      // A kill mid-write leaves its temporary half written, never a file under a final name
      // (the killed run may have removed those of earlier kills first).
      if (mid_write) {
        EXPECT_GE(temporaries_below(dir / "killed"), 1) << kill_at;
        EXPECT_LE(temporaries_below(dir / "killed"), temporaries_before + 1) << kill_at;
        ++half_written;
      }
    }
    // No corrupt or half-written file under a final name, ever.
    if (fs::exists(dir / "killed")) hashes_below(dir / "killed");
  }
  EXPECT_GE(step_kills, 5);
  EXPECT_GE(write_kills, 5);
  EXPECT_EQ(half_written, write_kills);
  if (!finished) {  // the rest without kills
    ASSERT_EQ(run_with_kill_point(args, ""), Ending::finished);
  }
  EXPECT_EQ(hashes_below(dir / "killed"), expected);
  // Issue 28: the temporaries of the killed processes do not outlive the run that finishes.
  EXPECT_EQ(temporaries_below(dir / "killed"), 0);
}

TEST(RunWorkflow, RerunIsNoOpAndChangedValueRerunsOnlyWhatItAffects) {
  const ScratchFolder scratch("run_rerun");
  const fs::path& dir = scratch.path;
  const auto workflow = small_workflow(dir);
  const auto out = dir / "out";
  ASSERT_EQ(run_cli("run " + quoted(workflow) + " --quiet --out " + quoted(out)).exit_code, 0);
  const std::string relax_bytes = read_file(out / "body" / "relax.h5");
  const std::string a_bytes = read_file(out / "A" / "encounter.h5");

  const auto again = run_cli("run " + quoted(workflow) + " --out " + quoted(out));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  for (const char* stage : {"build: up to date", "stretch: up to date", "relax: up to date", "encounter A: up to date",
                            "encounter B: up to date", "analyze A: up to date"})
    EXPECT_NE(again.out.find(stage), std::string::npos) << again.out;
  EXPECT_EQ(read_file(out / "A" / "encounter.h5"), a_bytes);
  // The summary ends with the peak memory, what a batch job has to request.
  const auto peak = again.out.rfind("\npeak memory: ");
  ASSERT_NE(peak, std::string::npos) << again.out;
  const double megabytes = std::stod(again.out.substr(peak + 14));
  EXPECT_GT(megabytes, 1.0) << again.out;
  EXPECT_LT(megabytes, 4096.0) << again.out;
  EXPECT_EQ(again.out.substr(again.out.find('\n', peak + 1)), "\n") << "the last line";
  const std::string status = read_file(out / "status.json");
  EXPECT_NE(status.find("\"stage\": \"workflow small\""), std::string::npos) << status;
  EXPECT_NE(status.find("\"state\": \"done\""), std::string::npos) << status;

  // A changed encounter value reruns the encounters only.
  const auto changed = run_cli("run " + quoted(workflow) + " --set encounter.damping=0.02 --out " + quoted(out));
  ASSERT_EQ(changed.exit_code, 0) << changed.err;
  EXPECT_NE(changed.out.find("relax: up to date"), std::string::npos) << changed.out;
  EXPECT_EQ(changed.out.find("encounter A: up to date"), std::string::npos) << changed.out;
  EXPECT_EQ(read_file(out / "body" / "relax.h5"), relax_bytes);
  EXPECT_NE(read_file(out / "A" / "encounter.h5"), a_bytes);

  // Half dt: encounters into their own folder, branching from the same relaxed body.
  const auto half = run_cli("run " + quoted(workflow) + " --quiet --dt-factor 0.5 --only A --out " + quoted(out));
  ASSERT_EQ(half.exit_code, 0) << half.err;
  const auto half_dt = read_checkpoint(out / "dt0.5" / "A" / "encounter.h5");
  EXPECT_DOUBLE_EQ(half_dt.stage.clock.dt, 0.0025);
  EXPECT_EQ(half_dt.stage.parent_hash, state_hash(read_checkpoint(out / "body" / "relax.h5").state));
  EXPECT_FALSE(fs::exists(out / "dt0.5" / "B"));
  EXPECT_TRUE(fs::exists(out / "A" / "analysis" / "summary.json"));
  EXPECT_TRUE(fs::exists(out / "A" / "analysis" / "fracture_map.png"));
}

TEST(RunWorkflow, WithoutFiguresTheSummaryIsWrittenAndTheFiguresAreDrawnWhenAskedFor) {
  const ScratchFolder scratch("run_no_figures");
  const auto workflow = small_workflow(scratch.path);
  const auto out = scratch.path / "out", analysis = out / "A" / "analysis";
  const auto without = run_cli("run " + quoted(workflow) + " --only A --set analysis.figures=false --out " + quoted(out));
  ASSERT_EQ(without.exit_code, 0) << without.err;
  EXPECT_NE(without.out.find("analyze A: summary.json in"), std::string::npos) << without.out;
  EXPECT_NE(without.out.find("    summary.json: "), std::string::npos) << without.out;
  for (const char* file : {"summary.json", "cracks.json", "figure_data.json"}) EXPECT_TRUE(fs::exists(analysis / file)) << file;
  std::size_t drawn = 0;
  for (const auto& entry : fs::directory_iterator(analysis))
    drawn += entry.path().extension() == ".png" || entry.path().extension() == ".svg";
  EXPECT_EQ(drawn, 0u);
  const std::string summary = read_file(analysis / "summary.json");
  EXPECT_NE(summary.find("\"figures\": []"), std::string::npos) << summary;
  const std::string a_bytes = read_file(out / "A" / "encounter.h5");

  // Without figures again: up to date. With them: the encounter stays, the analysis is redone.
  const auto again = run_cli("run " + quoted(workflow) + " --only A --set analysis.figures=false --out " + quoted(out));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("analyze A: up to date"), std::string::npos) << again.out;
  const auto with = run_cli("run " + quoted(workflow) + " --only A --out " + quoted(out));
  ASSERT_EQ(with.exit_code, 0) << with.err;
  EXPECT_NE(with.out.find("encounter A: up to date"), std::string::npos) << with.out;
  EXPECT_NE(with.out.find("analyze A: figures and summary.json in"), std::string::npos) << with.out;
  EXPECT_TRUE(fs::exists(analysis / "fracture_map.png"));
  EXPECT_TRUE(fs::exists(analysis / "fracture_map.svg"));
  EXPECT_EQ(read_file(out / "A" / "encounter.h5"), a_bytes);
  // Figures drawn count as an analysis without them too (nothing is removed to match the setting).
  const auto later = run_cli("run " + quoted(workflow) + " --only A --set analysis.figures=false --out " + quoted(out));
  ASSERT_EQ(later.exit_code, 0) << later.err;
  EXPECT_NE(later.out.find("analyze A: up to date"), std::string::npos) << later.out;
  EXPECT_TRUE(fs::exists(analysis / "fracture_map.png"));
}

TEST(RunWorkflow, BadInputExitsTwoAndTouchesNothing) {
  const ScratchFolder scratch("run_bad");
  const fs::path& dir = scratch.path;
  const auto workflow = small_workflow(dir);
  const auto out = dir / "out";
  ASSERT_EQ(run_cli("run " + quoted(workflow) + " --quiet --only B --out " + quoted(out)).exit_code, 0);
  const std::string build_bytes = read_file(out / "body" / "build.h5");

  const auto unknown = dir / "unknown.toml";
  std::ofstream(unknown) << "[workflow]\nname = \"small\"\n[relax]\ndamping = 50.0\ndampnig = 1.0\n";
  const auto malformed = dir / "malformed.toml";
  std::ofstream(malformed) << "[workflow\nname = 1\n";
  struct Case {
    std::string args, expected;
  } cases[] = {
      {"run " + quoted(unknown) + " --out " + quoted(out), "relax.dampnig"},
      {"run " + quoted(malformed) + " --out " + quoted(out), "malformed.toml:1"},
      {"run " + quoted(workflow) + " --dt-factor -0.5 --out " + quoted(out), "--dt-factor"},
      {"run " + quoted(workflow) + " --only Z --out " + quoted(out), "unknown encounter 'Z'"},
      {"run " + quoted(workflow) + " --set workflow.seed=4 --out " + quoted(out), "different body"},
      {"run " + quoted(dir / "missing.toml") + " --out " + quoted(out), "missing.toml"},
      // An encounter the time step cannot resolve (issue 10, item 6), refused before the body
      // is built (in a fresh folder: nothing created), naming the workflow, the encounter and dt.
      {"run " + quoted(workflow) + " --set encounters.B.perturber_mass=1e9 --set encounters.B.pericenter_speed=33100"
           " --out " + quoted(dir / "fresh"), workflow.string() + ": encounter 'B' (M2 = 1e+09"},
      {"run " + quoted(workflow) + " --set encounters.B.perturber_mass=1e9 --set encounters.B.pericenter_speed=33100"
           " --out " + quoted(dir / "fresh"), "is not resolved by dt = "},
      // The gravity method (issue 13): unknown method, force_error outside (0, 0.5].
      {"run " + quoted(workflow) + " --set gravity.method=fmm --out " + quoted(out), "gravity.method = \"fmm\""},
      {"run " + quoted(workflow) + " --set gravity.force_error=0 --out " + quoted(out), "gravity.force_error = 0"},
      {"run " + quoted(workflow) + " --set gravity.force_error=1.0 --out " + quoted(out), "gravity.force_error = 1"},
      {"build --config " + quoted(workflow) + " --set gravity.force_error=-1e-4 --out " + quoted(dir / "fresh.h5"),
       "gravity.force_error"},
  };
  for (const auto& c : cases) {
    const auto r = run_cli(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
  }
  EXPECT_EQ(read_file(out / "body" / "build.h5"), build_bytes);
  EXPECT_FALSE(fs::exists(out / "A"));
  EXPECT_FALSE(fs::exists(dir / "fresh"));
  EXPECT_FALSE(fs::exists(dir / "fresh.h5"));
}

// Issue 10 item 2: one interior mass of body/relax.h5 changed with an HDF5 tool kept its
// state_hash; `run` called relax up to date and branched a different encounter with exit 0.
// Now every edited dataset or attribute is refused by `run` and `inspect` (exit 2, one line
// naming the file and the object) and the folder's results are left as they were.
TEST(RunWorkflow, CheckpointEditedAfterWritingIsRefusedNamingTheObject) {
  const ScratchFolder scratch("run_edited");
  const fs::path& dir = scratch.path;
  const auto workflow = small_workflow(dir);
  const auto out = dir / "out";
  ASSERT_EQ(run_cli("run " + quoted(workflow) + " --quiet --only B --out " + quoted(out)).exit_code, 0);
  const fs::path relax = out / "body" / "relax.h5", encounter = out / "B" / "encounter.h5";
  const std::string relax_bytes = read_file(relax), encounter_bytes = read_file(encounter);
  const Checkpoint relaxed = read_checkpoint(relax);
  ASSERT_EQ(relaxed.body.species[0], 0) << "particle 0 is an interior node";
  const double mass = relaxed.body.mass[0], damping = relaxed.stage.as<RelaxRecord>().damping;
  const std::int32_t end = relaxed.body.springs[4][1];
  struct Case {
    std::string object;
    std::function<void(hid_t)> edit;
  } cases[] = {
      {"/particles/body/mass", [&](hid_t f) { overwrite_element(f, "/particles/body/mass", 0, mass * 1.01); }},
      {"/checkpoint/record@damping",
       [&](hid_t f) { overwrite_attribute(f, "/checkpoint/record", "damping", damping / 2); }},
      {"/checkpoint@softening", [&](hid_t f) { overwrite_attribute(f, "/checkpoint", "softening", 0.02); }},
      {"/connectivity/springs",
       [&](hid_t f) { overwrite_element<std::int32_t>(f, "/connectivity/springs", 9, end == 0 ? 1 : 0); }},
  };
  for (const auto& c : cases) {
    write_file(relax, relax_bytes);
    edit_in_place(relax, c.edit);
    const std::string expected =
        relax.string() + ": " + c.object + " changed since the file was written (content hash mismatch)";
    for (const std::string& args : {"run " + quoted(workflow) + " --quiet --only B --out " + quoted(out),
                                    "inspect " + quoted(relax)}) {
      const auto r = run_cli(args);
      EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
      EXPECT_EQ(count_lines(r.err), 1) << r.err;
      EXPECT_NE(r.err.find(expected), std::string::npos) << args << "\n" << r.err;
    }
    EXPECT_EQ(read_file(encounter), encounter_bytes) << c.object;
  }
  write_file(relax, relax_bytes);
  EXPECT_EQ(run_cli("run " + quoted(workflow) + " --quiet --only B --out " + quoted(out)).exit_code, 0);
  EXPECT_EQ(read_file(encounter), encounter_bytes);
}

TEST(RunWorkflow, CtrlCStopsWithCheckpointAndResumeToleratesUnrelatedChanges) {
  const ScratchFolder scratch("run_sigint");
  const fs::path& dir = scratch.path;
  const auto workflow = small_workflow(dir);
  const auto out = dir / "out";
  // Ctrl-C inside the relaxation: the run is held after its 20th step (io/test_points.hpp), so the
  // signal lands there on any machine.
  const std::string args = "run " + quoted(workflow) + " --quiet --out " + quoted(out) + " --set relax.duration=1.0";
  const fs::path hold = dir / "held";
  BackgroundCli running(args, hold_at_step(20, hold));
  ASSERT_TRUE(wait_while_running(running.pid(), [&] { return fs::exists(hold); }));
  kill(running.pid(), SIGINT);
  EXPECT_EQ(running.finish().exit_code, 130);  // clean stop, its checkpoint written
  const auto mid = out / "body" / "relax.mid.h5";
  const Checkpoint stopped = read_checkpoint(mid);
  EXPECT_FALSE(stopped.stage.complete);
  EXPECT_EQ(stopped.state.step - stopped.stage.clock.start_step, 20);
  // Rerun with a value the relaxation does not read changed: it resumes, it does not restart.
  const auto resumed = run_cli("run " + quoted(workflow) + " --out " + quoted(out) +
                               " --set relax.duration=1.0 --set encounter.damping=0.02 --only A");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.out.find("relax: resuming from"), std::string::npos) << resumed.out;
  EXPECT_FALSE(fs::exists(mid));
}

namespace {

/// Every file and folder below `root`, by relative path, with the bytes of each file.
std::map<std::string, std::string> tree_of(const fs::path& root) {
  std::map<std::string, std::string> tree;
  for (const auto& entry : fs::recursive_directory_iterator(root))
    tree[fs::relative(entry.path(), root).string()] = entry.is_regular_file() ? read_file(entry.path()) : "/";
  return tree;
}

}  // namespace

// Issue 28: an encounter named ".." wrote encounter.h5 and snapshots outside --out and deleted
// the sibling folder analysis/; workflow.name = "../../x" wrote outside the output root; a NUL
// in a name left an empty folder and a truncated message. Every name that becomes a path is
// refused before anything runs: exit 2, one line, nothing created or removed anywhere.
TEST(RunWorkflow, NamesThatWouldLeaveTheOutputFolderAreRefusedBeforeAnythingRuns) {
  const ScratchFolder scratch("run_names");
  const fs::path& dir = scratch.path;
  fs::create_directories(dir / "work" / "analysis");
  write_file(dir / "work" / "analysis" / "notes.txt", "the user's notes\n");
  auto workflow_with = [&](const std::string& file, const std::string& workflow_name,
                           const std::string& encounter_name) {
    std::string text = small_body_toml("small");
    text.replace(text.find("name = \"small\""), 14, "name = \"" + workflow_name + "\"");
    text += "[[encounters]]\nname = \"" + encounter_name + "\"\nperturber_mass = 0.5\npericenter = 1.8\n"
            "pericenter_speed = 1.7\n";
    write_file(dir / file, text);
    return dir / file;
  };
  const std::map<std::string, std::string> before = tree_of(dir);
  struct Case {
    fs::path workflow;
    std::string extra, expected;
  } cases[] = {
      {workflow_with("dotdot.toml", "small", ".."), " --out " + quoted(dir / "work" / "out"),
       "encounter name '..' names a folder itself"},
      {workflow_with("dot.toml", "small", "."), " --out " + quoted(dir / "work" / "out"), "encounter name '.'"},
      {workflow_with("slash.toml", "small", "../analysis"), " --out " + quoted(dir / "work" / "out"),
       "may only use letters"},
      {workflow_with("reserved.toml", "small", "body"), " --out " + quoted(dir / "work" / "out"), "reserved"},
      {workflow_with("up.toml", "../../x", "A"), "", "workflow.name '../../x'"},
      {workflow_with("nul.toml", "a\\u0000b", "A"), "", "workflow.name 'a\\x00b'"},
      {workflow_with("nul_encounter.toml", "small", "A\\u0000B"), " --out " + quoted(dir / "work" / "out"),
       "encounter name 'A\\x00B'"},
      {workflow_with("long.toml", std::string(300, 'w'), "A"), "", "300 bytes long (at most 200)"},
      {workflow_with("ok.toml", "small", "A"), " --only .. --out " + quoted(dir / "work" / "out"),
       "encounter name '..'"},
      {workflow_with("ok.toml", "small", "A"), " --out " + quoted(dir / "work" / std::string(300, 'o')),
       "is 300 bytes long (at most 200)"},
      {workflow_with("ok.toml", "small", "A"), " --out " + quoted(dir / "work" / "o\tut"), "control character 0x09"},
      {workflow_with("ok.toml", "small", "A"), " --set 'workflow.name=\"../x\"'", "workflow.name '../x'"},
  };
  const std::map<std::string, std::string> with_workflows = tree_of(dir);
  for (const auto& c : cases) {
    // Without --out the root is checkpoints/<workflow name> below the current folder.
    const std::string args = "run " + quoted(c.workflow) + " --quiet" + c.extra;
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(tree_of(dir), with_workflows) << args;
    EXPECT_FALSE(fs::exists("checkpoints/small")) << args;
    EXPECT_FALSE(fs::exists("../x")) << args;
  }
  EXPECT_EQ(read_file(dir / "work" / "analysis" / "notes.txt"), "the user's notes\n");
  (void)before;
}

// Issue 28: a read-only output folder gave "internal error", exit 1. A folder that cannot be
// made or written is one line naming the path, exit 2 (as root, whom permissions do not stop,
// a regular file in the way of the folder shows the same).
TEST(RunWorkflow, AnOutputFolderThatCannotBeMadeOrWrittenIsExit2NamingIt) {
  const ScratchFolder scratch("run_unwritable");
  const fs::path& dir = scratch.path;
  const auto workflow = small_workflow(dir);
  write_file(dir / "a-file", "not a folder\n");
  std::vector<std::pair<fs::path, std::string>> outs = {{dir / "a-file" / "out", "Not a directory"}};
  if (geteuid() != 0) {
    fs::create_directories(dir / "read-only");
    fs::permissions(dir / "read-only", fs::perms::owner_read | fs::perms::owner_exec);
    outs.push_back({dir / "read-only" / "out", "Permission denied"});
    outs.push_back({dir / "read-only", "Permission denied"});
  }
  for (const auto& [out, reason] : outs) {
    const auto r = run_cli("run " + quoted(workflow) + " --quiet --out " + quoted(out));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(out.string()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(reason), std::string::npos) << r.err;
  }
  if (geteuid() != 0) fs::permissions(dir / "read-only", fs::perms::owner_all);
}

// Issue 28: a symbolic link planted as OUT/body/build.h5.lock had its target truncated and
// overwritten with the lock's text; the temporaries FILE.tmp-PID followed links the same way.
TEST(RunWorkflow, ALinkPlantedAsALockOrATemporaryIsRefusedAndItsTargetKept) {
  const ScratchFolder scratch("run_links");
  const fs::path& dir = scratch.path;
  const auto workflow = small_workflow(dir);
  write_file(dir / "precious.txt", "the user's data\n");
  fs::create_directories(dir / "out" / "body");
  fs::create_symlink(dir / "precious.txt", dir / "out" / "body" / "build.h5.lock");
  const auto r = run_cli("run " + quoted(workflow) + " --quiet --only A --out " + quoted(dir / "out"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("build.h5.lock: the lock file is a symbolic link; refusing"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(dir / "precious.txt"), "the user's data\n");
  EXPECT_FALSE(fs::exists(dir / "out" / "body" / "build.h5"));
}

// Issue 28, item 4: one transient EIO while reading a valid relax.mid.h5 on resume dropped it
// silently; the stage restarted from step 0 and overwrote it (a format-5 mid the same). Now a
// transient read error is tried again (the testing aid TIDALCRUST_TEST_READ_EIO=N:K fails read
// attempts N to N+K-1 with EIO), a persistent one is one line naming the file, exit 2, and a mid
// that cannot be read is kept as it is.
TEST(RunWorkflow, AnUnreadableCheckpointIsRetriedThenReportedNeverTakenForAbsent) {
  const ScratchFolder scratch("run_unreadable");
  const fs::path& dir = scratch.path;
  const auto workflow = small_workflow(dir);
  const auto straight = run_cli("run " + quoted(workflow) + " --quiet --body-only --out " + quoted(dir / "straight"));
  ASSERT_EQ(straight.exit_code, 0) << straight.err;
  const std::string relaxed = state_hash(read_checkpoint(dir / "straight" / "body" / "relax.h5").state);
  const std::vector<std::string> args = {"run", workflow.string(), "--body-only", "--out", (dir / "base").string()};
  ASSERT_EQ(run_with_kill_point(args, "step:40"), Ending::killed);
  const fs::path mid = dir / "base" / "body" / "relax.mid.h5";
  ASSERT_TRUE(fs::exists(mid));
  const std::string mid_bytes = read_file(mid);
  const auto copy_of_base = [&](const std::string& name) {
    fs::copy(dir / "base", dir / name, fs::copy_options::recursive);
    return dir / name;
  };

  // Each of the first read attempts fails once (the fourth is the mid's): retried, resumed.
  for (int attempt = 1; attempt <= 5; ++attempt) {
    const fs::path out = copy_of_base(fmt::format("transient{}", attempt));
    const auto r = run_cli(fmt::format("run {} --body-only --out {}", quoted(workflow), quoted(out)),
                           fmt::format("TIDALCRUST_TEST_READ_EIO={}:1", attempt));
    EXPECT_EQ(r.exit_code, 0) << attempt << ": " << r.err;
    EXPECT_NE(r.out.find("resuming from " + (out / "body" / "relax.mid.h5").string()), std::string::npos)
        << attempt << ": " << r.out;
    EXPECT_EQ(state_hash(read_checkpoint(out / "body" / "relax.h5").state), relaxed) << attempt;
  }

  // Failing for good: one line naming the file and the cause, nothing changed.
  const fs::path persistent = copy_of_base("persistent");
  const auto tree_before = tree_of(persistent);
  const auto failing = run_cli(fmt::format("run {} --body-only --out {}", quoted(workflow), quoted(persistent)),
                               "TIDALCRUST_TEST_READ_EIO=1:1000");
  EXPECT_EQ(failing.exit_code, 2) << failing.err;
  EXPECT_EQ(count_lines(failing.err), 1) << failing.err;
  EXPECT_NE(failing.err.find("build.h5: cannot read checkpoint: Input/output error (4 attempts)"), std::string::npos)
      << failing.err;
  EXPECT_EQ(tree_of(persistent), tree_before);

  // A mid of a format this program does not read (or damaged) is refused and kept, never
  // replaced by a stage begun again.
  const fs::path newer = copy_of_base("newer");
  edit_in_place(newer / "body" / "relax.mid.h5",
                [](hid_t f) { overwrite_attribute<std::int64_t>(f, "/checkpoint", "format_version", checkpoint_format_version + 1); });
  const std::string newer_bytes = read_file(newer / "body" / "relax.mid.h5");
  const auto refused = run_cli("run " + quoted(workflow) + " --body-only --out " + quoted(newer));
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  // One error line (after the note that the killed run's lock was taken over).
  EXPECT_EQ(count_lines(refused.err.substr(refused.err.find("error:"))), 1) << refused.err;
  EXPECT_NE(refused.err.find(fmt::format("relax.mid.h5: written by a newer tidalcrust (format {})", checkpoint_format_version + 1)), std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("kept; remove it to begin relax again"), std::string::npos) << refused.err;
  EXPECT_EQ(read_file(newer / "body" / "relax.mid.h5"), newer_bytes);
  EXPECT_FALSE(fs::exists(newer / "body" / "relax.h5"));
  EXPECT_EQ(read_file(mid), mid_bytes);
}

// Issue 27 item 6: a workflow without encounters is refused before anything runs (one line naming
// the file and the way to run the body alone), not relaxed and left silently.
TEST(CmdRun, AWorkflowWithoutEncountersIsRefusedNamingBodyOnly) {
  const ScratchFolder scratch("run_no_encounters");
  const fs::path workflow = scratch.path / "bare.toml";
  std::ofstream(workflow) << "[workflow]\nname = \"bare\"\n";
  const auto r = run_cli("run " + quoted(workflow) + " --out " + quoted(scratch.path / "out"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(workflow.string() + ": the workflow has no encounters"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--body-only"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(scratch.path / "out" / "body"));
}
