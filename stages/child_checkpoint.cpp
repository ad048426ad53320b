#include "stages/child_checkpoint.hpp"

#include "io/state_hash.hpp"

namespace tidalcrust {

Checkpoint child_checkpoint(const Checkpoint& parent, StageRecord record, const Config& config) {
  Checkpoint child;
  child.body = parent.body;
  child.state = parent.state;
  child.stage.record = std::move(record);
  child.stage.complete = false;
  child.stage.clock = StepClock{parent.state.time, parent.state.step, config.integrator.dt};
  child.stage.end_step = parent.state.step;
  child.stage.parent_hash = state_hash(parent.state);
  child.config_toml = to_toml(config);
  child.stage.gravity_kernel = parent.stage.gravity_kernel;  // the kernel of the state it starts from
  return child;
}

}  // namespace tidalcrust
