#pragma once
// Small bodies for the force and integrator tests: the real builder at shell level 2 and ~200
// interior nodes, optionally shaken (random displacements and velocities) so every force is
// non-zero.
#include <cstdint>

#include "forces/force_field.hpp"
#include "stages/build_stage.hpp"
#include "model/config.hpp"
#include "base/random.hpp"

namespace tidalcrust::test_support {

inline Config small_body_config() {
  return parse_config(R"(
[workflow]
name = "small"
seed = 3
[interior]
count = 200
radius = 0.85
min_separation = 0.16
spring_distance = 0.36
spring_constant = 0.1
[shell]
level = 2
mass = 0.1
spring_constant = 0.06
bending_constant = 0.01
[cross]
distance = 0.3
spring_constant = 0.007
[integrator]
dt = 0.003
softening_fraction = 0.01
)",
                      "small.toml");
}

inline Checkpoint small_body() { return build_stage(small_body_config()); }

/// The quick workflow's body (~1000 particles, ~7000 springs, ~2000 hinges): big enough that
/// every kernel splits into several parallel work items.
inline Checkpoint quick_body() { return build_stage(load_config(TIDALCRUST_SOURCE_DIR "/workflows/quick.toml")); }

/// Adds uniform random displacements in [-dx, dx] and velocities in [-dv, dv] per component.
inline void shake(State& state, double dx, double dv, std::uint64_t seed) {
  Random random(seed);
  for (double& x : state.position) x += random.uniform(-dx, dx);
  for (double& v : state.velocity) v += random.uniform(-dv, dv);
}

/// Force options with every spring damped at rate gamma (1/t_grav).
inline ForceOptions damped(double gamma) {
  ForceOptions options;
  options.damping = gamma;
  return options;
}

/// A clock that starts at the state's step and time with time step dt (t_grav).
inline StepClock clock_at(const State& state, double dt) { return StepClock{state.time, state.step, dt}; }

}  // namespace tidalcrust::test_support
