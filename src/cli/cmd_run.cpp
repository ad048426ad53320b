// `tidalcrust run WORKFLOW.toml`: reads and checks the options, then runs the restart-driven
// workflow (stages/workflow.hpp) and prints its summary.
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "base/errors.hpp"
#include "cli/cli_options.hpp"
#include "cli/commands.hpp"
#include "stages/encounter_stage.hpp"
#include "stages/workflow.hpp"

namespace tidalcrust {

namespace fs = std::filesystem;

int command_run(int argc, char** argv) {
  cxxopts::Options options("tidalcrust run", "Run a whole workflow; rerun the same command to resume.");
  options.positional_help("WORKFLOW.toml");
  options.add_options()("workflow", "workflow TOML file", cxxopts::value<std::string>())(
      "out", "output root (default checkpoints/<workflow name>)", cxxopts::value<std::string>())(
      "threads", "number of threads (results do not depend on it)", cxxopts::value<int>()->default_value("0"))(
      "dt-factor", "run the encounters at dt times this factor, into a separate folder",
      cxxopts::value<double>()->default_value("1.0"))(
      "only", "run only this encounter (repeatable)", cxxopts::value<std::vector<std::string>>())(
      "body-only", "run only the body chain (build, stretch, relax), no encounter")(
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
  Config config = workflow_config(parsed);
  const KernelOptions kernel = read_kernel_options(parsed);
  kernel.apply(config);
  const double dt_factor = parsed["dt-factor"].as<double>();
  if (!std::isfinite(dt_factor) || dt_factor <= 0)
    throw InputError(fmt::format("--dt-factor must be a number > 0, got {}", dt_factor));
  const int threads = checked_thread_count(parsed["threads"].as<int>());
  std::vector<Encounter> encounters = config.encounters;
  if (parsed.count("body-only")) {
    // The first job of `submit --slurm`: the shared body, before the encounters' job array.
    if (parsed.count("only")) throw InputError("--body-only and --only exclude each other");
    encounters.clear();
  } else if (parsed.count("only")) {
    encounters.clear();
    for (const auto& name : parsed["only"].as<std::vector<std::string>>())
      encounters.push_back(config.find_encounter(name));
  }
  // Every encounter to run must be resolved by its time step (dt times --dt-factor), checked
  // here too so that an unresolvable one is refused before the body is built.
  Config encounter_config = config;
  if (dt_factor != 1.0) scale_time_step(encounter_config, dt_factor);
  for (const auto& spec : encounters) check_encounter(encounter_config, spec);
  WorkflowOptions workflow_options;
  workflow_options.root = parsed.count("out") ? fs::path(parsed["out"].as<std::string>())
                                              : fs::path("checkpoints") / config.workflow.name;
  workflow_options.quiet = parsed.count("quiet") > 0;
  workflow_options.dt_factor = dt_factor;
  workflow_options.allow_kernel_change = kernel.allow_change;
  workflow_options.encounters = std::move(encounters);
  apply_thread_count(threads);
  const WorkflowResult result = run_workflow(config, workflow_options);
  if (result.interrupted) return exit_interrupted;

  fmt::print("\nworkflow {} finished: checkpoints in {}\n", config.workflow.name, workflow_options.root.string());
  if (result.relaxed && result.relaxed->probe_runs > 0)
    fmt::print("relaxed body: stability probe {} failures, largest shell strain {:.2e}\n",
               result.relaxed->probe_failures, result.relaxed->probe_max_shell_strain);
  for (const auto& e : result.encounters) fmt::print("  {}\n    figures: {}\n", e.summary, e.analysis.string());
  return exit_ok;
}

}  // namespace tidalcrust
