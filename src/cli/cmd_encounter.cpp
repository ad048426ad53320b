// `tidalcrust encounter`
#include <fmt/format.h>

#include <filesystem>

#include "io/checkpoint_file.hpp"
#include "cli/cli_options.hpp"
#include "cli/commands.hpp"
#include "stages/encounter_stage.hpp"
#include "base/errors.hpp"
#include "cli/stage_command.hpp"
#include "stages/gravity_kernel_check.hpp"

namespace tidalcrust {

int command_encounter(int argc, char** argv) {
  cxxopts::Options options("tidalcrust encounter", "Tidal encounter with crust failure (paper sections 2.6, 2.9).");
  options.add_options()("encounter", "name of an encounter of the configuration", cxxopts::value<std::string>())(
      "m2", "perturber mass M2 (M)", cxxopts::value<double>())("q", "pericenter distance (R)", cxxopts::value<double>())(
      "vq", "speed at pericenter (sqrt(GM/R))", cxxopts::value<double>())(
      "failure-strain", "eps_S for this encounter", cxxopts::value<double>());
  auto in = read_stage_input(options, argc, argv,
                             "input relax or encounter checkpoint (or a mid-stage encounter to resume)", true,
                             {"relax", "encounter"}, "encounter");
  if (!in) return exit_ok;
  auto& [parsed, common, from, out, input] = *in;
  const bool resuming = std::holds_alternative<EncounterRecord>(input.stage.record) && !input.stage.complete;
  const bool by_name = parsed.count("encounter") > 0;
  const bool by_values = parsed.count("m2") || parsed.count("q") || parsed.count("vq");
  if (resuming) {
    if (by_name || by_values)
      throw InputError(fmt::format("{}: is a mid-stage encounter; it resumes its own encounter "
                                   "(drop --encounter/--m2/--q/--vq)", from.string()));
  } else if (by_name == by_values) {
    throw InputError("give either --encounter NAME or all of --m2 M --q Q --vq V");
  }
  if (std::holds_alternative<RelaxRecord>(input.stage.record) && !input.stage.complete)
    throw InputError(fmt::format("{}: relaxation is not complete; finish it with 'tidalcrust relax'", from.string()));
  Config config = stage_config(input, from, common, resuming);
  apply_thread_count(common.threads);
  Checkpoint checkpoint;
  if (resuming) {
    checkpoint = std::move(input);
  } else {
    Encounter spec;
    if (by_name) {
      spec = config.find_encounter(parsed["encounter"].as<std::string>());
    } else {
      if (!(parsed.count("m2") && parsed.count("q") && parsed.count("vq")))
        throw InputError("--m2, --q and --vq must be given together");
      spec.name = "custom";
      spec.perturber_mass = parsed["m2"].as<double>();
      spec.pericenter = parsed["q"].as<double>();
      spec.pericenter_speed = parsed["vq"].as<double>();
    }
    if (parsed.count("failure-strain")) spec.failure_strain = parsed["failure-strain"].as<double>();
    Config checked = config;
    checked.encounters = {spec};
    validate(checked, "encounter options");  // NaN, negative mass, q inside the body -> exit 2
    checkpoint = begin_encounter(input, config, spec);
  }
  continue_under_gravity_kernel(checkpoint, config, common.kernel.allow_change, from.string());
  const StageLock lock = lock_output(out, from, resuming);
  StepLoopOptions loop = loop_options_for(parsed, out, "encounter " + checkpoint.stage.as<EncounterRecord>().encounter.name,
                                          config.encounter.checkpoint_interval);
  return finish_stage(run_encounter(checkpoint, config, loop, out), checkpoint, out, loop);
}

}  // namespace tidalcrust
