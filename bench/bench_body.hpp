#pragma once
// The body the micro-benchmarks run on: the paper-T body (4431 particles, ~36000 springs,
// 7680 hinges) from workflows/paper-T.toml when run from the source folder (make bench),
// otherwise from the built-in defaults, which are the same T-series parameters. Shaken a
// little, with encounter damping and a perturber, so every force path does real work.
#include <filesystem>

#include "stages/build_stage.hpp"
#include "forces/force_field.hpp"
#include "model/config.hpp"
#include "base/random.hpp"

namespace tidalcrust::bench {

inline const Checkpoint& paper_t_body() {
  static const Checkpoint body = [] {
    const std::filesystem::path file = "workflows/paper-T.toml";
    Config config = std::filesystem::exists(file) ? load_config(file) : Config{};
    Checkpoint c = build_stage(config);
    Random random(42);
    for (double& x : c.state.position) x += random.uniform(-1e-3, 1e-3);
    for (double& v : c.state.velocity) v += random.uniform(-1e-2, 1e-2);
    c.state.perturber = {true, 0.5, {config.encounter.start_distance, 0.0, 0.0}, {0.0, 1.0, 0.0}};
    return c;
  }();
  return body;
}

/// Every force path switched on: the T-series encounter damping (1/t_grav).
inline ForceOptions damped() {
  ForceOptions options;
  options.damping = 0.01;
  return options;
}

}  // namespace tidalcrust::bench
