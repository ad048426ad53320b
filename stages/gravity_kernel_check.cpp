#include "stages/gravity_kernel_check.hpp"

#include <fmt/format.h>

#include "base/errors.hpp"
#include "forces/force_field.hpp"

namespace tidalcrust {

void continue_under_gravity_kernel(Checkpoint& checkpoint, const Config& config, bool allow_change,
                                   const std::string& source) {
  const std::string current = gravity_kernel_label(config.gravity.kernel);
  const std::string recorded = checkpoint.stage.gravity_kernel;
  if (!recorded.empty() && !same_gravity_bits(recorded, current)) {
    if (!allow_change)
      throw InputError(fmt::format(
          "{}: was computed by the {} gravity kernel, but this run uses {}; continuing would give bits that "
          "neither kernel reproduces (use [gravity] kernel = the same one, or --allow-kernel-change to continue "
          "anyway, recorded in the checkpoint)",
          source, recorded, current));
    StageInfo& stage = checkpoint.stage;
    stage.gravity_kernel_changes += fmt::format("{}step {}: {} -> {} (--allow-kernel-change)",
                                                stage.gravity_kernel_changes.empty() ? "" : "; ",
                                                checkpoint.state.step, recorded, current);
  }
  checkpoint.stage.gravity_kernel = current;
  if (checkpoint.config_toml.empty()) return;
  Config stored = parse_config(checkpoint.config_toml, source + ":/parameters/config");
  if (stored.gravity.kernel == config.gravity.kernel) return;
  stored.gravity.kernel = config.gravity.kernel;
  checkpoint.config_toml = to_toml(stored);
}

}  // namespace tidalcrust
