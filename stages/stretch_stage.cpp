#include "stages/stretch_stage.hpp"

#include "forces/gravity.hpp"
#include "model/derived_quantities.hpp"
#include "physics/hydrostatic_stretch.hpp"
#include "stages/child_checkpoint.hpp"

namespace tidalcrust {

Checkpoint stretch_stage(const Checkpoint& built, const Config& config) {
  require_complete<BuildRecord>(built, "stretch");
  Checkpoint out = child_checkpoint(built, StretchRecord{}, config);
  out.stage.complete = true;  // stretching takes no time steps
  auto& record = out.stage.as<StretchRecord>();
  if (!config.stretch.enabled) return out;
  // The stretch factor is found from forces that include self-gravity.
  out.stage.gravity_kernel = gravity_kernel_label(config.gravity.kernel);

  if (built.body.liquid.present()) {
    // The liquid starts at its hydrostatic pressure, and the stretch solves with it holding the crust.
    State with_liquid = built.state;
    set_hydrostatic_liquid_rest_volumes(built.body, with_liquid);
    out.state.liquid_rest_volume = with_liquid.liquid_rest_volume;
    record = stretch_springs(built.body, with_liquid, config, out.state.springs);
  } else {
    record = stretch_springs(built.body, built.state, config, out.state.springs);
  }
  record.dt_max = derive_quantities(out.body, out.state, config.interior.radius).dt_max;
  return out;
}

}  // namespace tidalcrust
