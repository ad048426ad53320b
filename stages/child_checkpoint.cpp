#include "stages/child_checkpoint.hpp"

#include "io/state_hash.hpp"

namespace tidalcrust {

Checkpoint child_checkpoint(const Checkpoint& parent, const std::string& stage, const Config& config) {
  Checkpoint child;
  child.body = parent.body;
  child.state = parent.state;
  child.stage.stage = stage;
  child.stage.complete = false;
  child.stage.start_step = parent.state.step;
  child.stage.end_step = parent.state.step;
  child.stage.parent_hash = state_hash(parent.state);
  child.config_toml = to_toml(config);
  return child;
}

}  // namespace tidalcrust
