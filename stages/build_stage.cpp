#include "stages/build_stage.hpp"

#include "bodies/build_body.hpp"

namespace tidalcrust {

Checkpoint build_stage(const Config& config) {
  BuiltBody built = build_body(config);
  Checkpoint out;
  out.stage.record = BuildRecord{static_cast<std::int64_t>(built.body.count_species(Species::interior)),
                                 built.interior_trials, built.min_spacing};
  out.body = std::move(built.body);
  out.state = std::move(built.state);
  out.stage.complete = true;
  // The body is built for this time step; instant stages keep it, stepping stages set their own.
  out.stage.clock = StepClock{0.0, 0, config.integrator.dt};
  out.stage.end_step = 0;
  out.config_toml = to_toml(config);
  return out;
}

}  // namespace tidalcrust
