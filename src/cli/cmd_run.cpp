// `tidalcrust run WORKFLOW.toml`: reads and checks the options, then runs the restart-driven
// workflow (stages/workflow.hpp) and prints its summary.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <utility>

#include "base/errors.hpp"
#include "cli/child_jobs.hpp"
#include "cli/cli_options.hpp"
#include "cli/commands.hpp"
#include "io/stop_signal.hpp"
#include "stages/encounter_stage.hpp"
#include "stages/workflow.hpp"

namespace tidalcrust {

namespace fs = std::filesystem;

namespace {

/// Largest --jobs: one process per encounter at most, and never more than threads allowed.
constexpr int max_jobs = max_threads;

/// What every child process of `run --jobs` is given.
struct ParallelEncounters {
  fs::path workflow;
  fs::path root;
  double dt_factor = 1.0;
  std::vector<std::string> overrides;  ///< --set, passed on unchanged
  int threads = 0;                     ///< all children together (0: the OpenMP default)
  int jobs = 1;
  bool quiet = false;
  bool allow_kernel_change = false;  ///< --allow-kernel-change, passed on
};

/// The line a child printed about its encounter ("NAME: 12 failed shell springs ..."), else
/// "NAME: done".
std::string child_summary(const std::string& out, const std::string& name) {
  const std::string key = name + ": ";
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    const auto first = line.find_first_not_of(' ');
    if (first != std::string::npos && line.compare(first, key.size(), key) == 0) return line.substr(first);
  }
  return name + ": done";
}

/// Runs each encounter as `run WORKFLOW --only NAME --threads T` in a child process, p.jobs at
/// once (the stage locks make them safe side by side, and the body chain is already relaxed), and
/// prints one line per finished encounter. exit_ok when all finished; exit_interrupted after a
/// stop (each child wrote its mid-stage checkpoint: a rerun resumes); else the failure's exit
/// code, with one line naming every failed encounter.
int run_encounters_in_parallel(const ParallelEncounters& p, const std::vector<Encounter>& encounters) {
  const std::size_t slots = std::min<std::size_t>(static_cast<std::size_t>(p.jobs), encounters.size());
  if (slots == 0) return exit_ok;
  const std::vector<int> slot_threads = split_threads(p.threads > 0 ? p.threads : omp_get_max_threads(), slots);
  std::vector<std::string> names;
  for (const auto& e : encounters) names.push_back(e.name);
  const auto arguments = [&](std::size_t job, std::size_t slot) {
    std::vector<std::string> args = {"run",     p.workflow.string(), "--out",     p.root.string(),
                                     "--quiet", "--only",            names[job], "--threads",
                                     std::to_string(slot_threads[slot])};
    if (p.dt_factor != 1.0) args.insert(args.end(), {"--dt-factor", fmt::format("{}", p.dt_factor)});
    for (const auto& assignment : p.overrides) args.insert(args.end(), {"--set", assignment});
    if (p.allow_kernel_change) args.push_back("--allow-kernel-change");
    return args;
  };
  if (!p.quiet)
    fmt::print("encounters: {} in {} processes at once, {} threads each\n", names.size(), slots,
               slot_threads.front() == slot_threads.back() ? fmt::format("{}", slot_threads.front())
                                                           : fmt::format("{}-{}", slot_threads.back(), slot_threads.front()));
  std::fflush(stdout);
  std::vector<std::string> failed;
  bool interrupted = false, bad_input_only = true;
  const auto on_finished = [&](const ChildOutcome& o, std::size_t finished) {
    const std::string& name = names[o.job];
    const std::string counter = fmt::format("[{}/{}]", finished, names.size());
    if (o.exit_code == exit_ok) {
      if (!p.quiet) fmt::print("{} {}\n", counter, child_summary(o.out, name));
    } else if (o.exit_code == exit_interrupted ||
               (stop_requested() && (o.exit_code == 128 + SIGTERM || o.exit_code == 128 + SIGINT))) {
      // A child stopped by the signal before it set up its handlers (still starting) ended
      // without a checkpoint of its own: nothing of it is lost or damaged, a rerun starts it.
      interrupted = true;
      if (!p.quiet) fmt::print("{} {}: stopped (a rerun resumes it)\n", counter, name);
    } else {
      failed.push_back(fmt::format("{} (exit {})", name, o.exit_code));
      bad_input_only = bad_input_only && o.exit_code == exit_bad_input;
      fmt::print(stderr, "{} {}: failed with exit code {} (its messages above start with [{}])\n", counter, name,
                 o.exit_code, name);
    }
    std::fflush(stdout);
  };
  const auto outcomes = run_child_jobs(own_executable(), names, slots, arguments, on_finished);
  if (!failed.empty()) {
    fmt::print(stderr, "tidalcrust run: {} of {} encounters failed: {}\n", failed.size(), names.size(),
               fmt::join(failed, ", "));
    return bad_input_only ? exit_bad_input : exit_simulation_failure;
  }
  if (interrupted || outcomes.size() < names.size()) {
    fmt::print(stderr, "tidalcrust run: stopped with {} of {} encounters finished; rerun the same command to resume\n",
               std::count_if(outcomes.begin(), outcomes.end(), [](const ChildOutcome& o) { return o.exit_code == exit_ok; }),
               names.size());
    return exit_interrupted;
  }
  return exit_ok;
}

}  // namespace

int command_run(int argc, char** argv) {
  cxxopts::Options options = command_options("run");
  options.positional_help("WORKFLOW.toml");
  options.add_options()("workflow", "workflow TOML file", cxxopts::value<std::string>())(
      "out", "output root (default checkpoints/<workflow name>)", cxxopts::value<std::string>())(
      "threads", "number of threads (results do not depend on it)", cxxopts::value<int>()->default_value("0"))(
      "dt-factor", "run the encounters at dt times this factor, into a separate folder",
      cxxopts::value<double>()->default_value("1.0"))(
      "only", "run only this encounter, or every member of this ensemble encounter (repeatable)", cxxopts::value<std::vector<std::string>>())(
      "body-only", "run only the body chain (build, stretch, relax), no encounter")(
      "jobs", "run this many encounters at once, each in a process of its own, the threads split among them",
      cxxopts::value<int>()->default_value("1"))(
      "set", "override one value: section.key=value (repeatable)", cxxopts::value<std::vector<std::string>>())(
      "quiet", "no progress lines")("h,help", "show this help");
  add_kernel_options(options);
  options.parse_positional({"workflow"});
  auto parsed = parse_arguments(options, argc, argv);
  if (parsed.count("help")) return fmt::print("{}\n", options.help()), exit_ok;
  // Line-buffered stdout: in a log file (a Slurm job's) the stage lines stay in order with the
  // progress lines on stderr.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);

  // Everything is checked before anything is written.
  WorkflowArguments w = read_workflow_arguments(parsed);
  const KernelOptions kernel = read_kernel_options(parsed);
  kernel.apply(w.config);
  // --jobs children get the same kernel choice as --set assignments.
  if (kernel.gravity_kernel) w.overrides.push_back("gravity.kernel=" + *kernel.gravity_kernel);
  const Config& config = w.config;
  const double dt_factor = w.dt_factor;
  const int threads = checked_thread_count(parsed["threads"].as<int>());
  const int jobs = parsed["jobs"].as<int>();
  if (jobs < 1 || jobs > max_jobs) throw InputError(fmt::format("--jobs must be between 1 and {}, got {}", max_jobs, jobs));
  std::vector<Encounter> encounters = config.encounters;
  // A workflow without encounters would build and relax its body (the paper-size one by default)
  // and stop without a word: say so before anything runs, and name the way to ask for it.
  if (config.encounters.empty() && !parsed.count("body-only"))
    throw InputError(fmt::format("{}: the workflow has no encounters (no [[encounters]] table, no [sweep]); add one, "
                                 "or pass --body-only to build and relax the body alone",
                                 w.file.string()));
  if (parsed.count("body-only")) {
    // The first job of `submit --slurm`: the shared body, before the encounters' job array.
    if (parsed.count("only")) throw InputError("--body-only and --only exclude each other");
    encounters.clear();
  } else if (parsed.count("only")) {
    encounters.clear();
    for (const auto& name : parsed["only"].as<std::vector<std::string>>())
      for (Encounter& e : config.encounters_named(name)) encounters.push_back(std::move(e));
  }
  // Every encounter to run must be resolved by its time step (dt times --dt-factor), checked
  // here too so that an unresolvable one is refused before the body is built.
  Config encounter_config = config;
  if (dt_factor != 1.0) scale_time_step(encounter_config, dt_factor);
  for (const auto& spec : encounters) check_encounter(encounter_config, spec, w.file.string());
  WorkflowOptions workflow_options;
  workflow_options.root = w.root;
  workflow_options.quiet = parsed.count("quiet") > 0;
  workflow_options.dt_factor = dt_factor;
  workflow_options.allow_kernel_change = kernel.allow_change;
  workflow_options.config_file = w.file;
  workflow_options.encounters = std::move(encounters);
  apply_thread_count(threads);
  if (jobs > 1) {
    // The body chain here, then the encounters in child processes; a failed or interrupted one
    // ends the command here, else the rerun below finds everything up to date and summarises.
    const std::vector<Encounter> wanted = std::exchange(workflow_options.encounters, {});
    if (run_workflow(config, workflow_options).interrupted) return exit_interrupted;
    ParallelEncounters parallel{w.file, workflow_options.root, dt_factor, w.overrides, threads, jobs,
                                workflow_options.quiet, kernel.allow_change};
    if (const int code = run_encounters_in_parallel(parallel, wanted); code != exit_ok) return code;
    workflow_options.encounters = wanted;
    workflow_options.quiet = true;
  }
  const WorkflowResult result = run_workflow(config, workflow_options);
  if (result.interrupted) return exit_interrupted;

  fmt::print("\nworkflow {} finished: checkpoints in {}\n", config.workflow.name, workflow_options.root.string());
  if (result.relaxed && result.relaxed->probe_runs > 0)
    fmt::print("relaxed body: largest |shell strain| {:.2e} (tension {:.2e}); stability probe at eps_S = {:.2g}: "
               "{} failures, largest tension {:.2e}\n",
               result.relaxed->max_shell_strain, result.relaxed->max_shell_tension,
               result.relaxed->probe_failure_strain, result.relaxed->probe_failures,
               result.relaxed->probe_max_shell_strain);
  for (const auto& e : result.encounters) {
    fmt::print("  {}\n    {}: {}\n", e.summary, config.analysis.figures ? "figures" : "summary.json", e.analysis.string());
    if (!e.warning.empty()) fmt::print("  warning: {}\n", e.warning);
  }
  // What a batch job must request (the level-6 T5 run: 567 MB with its analysis figures).
  fmt::print("peak memory: {:.0f} MB{}\n", peak_memory_mb(true), jobs > 1 ? " (largest process)" : "");
  return exit_ok;
}

}  // namespace tidalcrust
