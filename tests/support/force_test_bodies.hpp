#pragma once
// Small bodies for the force and integrator tests: the real builder at shell level 2 and ~200
// interior nodes, optionally shaken (random displacements and velocities) so every force is
// non-zero, or with every force law switched on; and a hand-made random cluster of 9 particles
// with every kind of element.
#include <array>
#include <cstdint>

#include "forces/force_field.hpp"
#include "stages/build_stage.hpp"
#include "model/config.hpp"
#include "base/random.hpp"
#include "forces/force_field.hpp"
#include "forces/hinge_geometry.hpp"

namespace tidalcrust::test_support {

/// The small body of the force and build tests, with the paper's cross springs, crust support and
/// failure rule named (the defaults are others since issue 27), so its bits are those of before.
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
min_per_shell_node = 0
[integrator]
dt = 0.003
softening_fraction = 0.01
[relax]
crust_support = "paper"
[encounter]
failure_rule = "paper"
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

/// The small body with every force law at work: shaken, hinges bent away from rest (rest angles
/// times 0.9) and a perturber at (2, 1, -0.5) R. Use it with every_law_options(): damping 3 on
/// every spring and a small eq. 26 strain scale that softens some cross springs.
inline Checkpoint every_law_body(std::uint64_t seed) {
  Checkpoint c = small_body();
  shake(c.state, 5e-3, 0.05, seed);
  for (double& r : c.state.hinges.rest_angle) r *= 0.9;
  c.state.perturber = {true, 0.5, {2.0, 1.0, -0.5}, {0.0, -1.0, 0.0}};
  return c;
}

inline ForceOptions every_law_options() {
  ForceOptions options = damped(3.0);
  options.cross_nonlinear = true;
  options.cross_strain_scale = 0.01;
  return options;
}

/// A small random configuration with every force law at work: an octahedral shell (6 particles,
/// 8 faces, 12 shell springs, 12 hinges) around 3 interior particles (3 interior springs, 6
/// cross springs), randomly displaced, random masses, strains in [-0.04, 0.06] (so softened
/// cross springs fall in all three regimes of eq. 26 with eps_C = 0.03, F_Ck = 0.1), hinges
/// up to 0.2 rad from rest, random velocities, damping 0, and a perturber of mass 0.5.
inline Checkpoint random_cluster(std::uint64_t seed) {
  Random random(seed);
  Checkpoint c;
  Body& body = c.body;
  State& state = c.state;
  const double axes[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const auto& a : axes)
    for (int k = 0; k < 3; ++k) state.position.push_back(0.9 * a[k] + random.uniform(-0.05, 0.05));
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) state.position.push_back(random.uniform(-0.3, 0.3));
  for (int i = 0; i < 9; ++i) {
    body.mass.push_back(random.uniform(0.05, 0.15));
    body.species.push_back(i < 6 ? 1 : 0);
    for (int k = 0; k < 3; ++k) state.velocity.push_back(random.uniform(-0.05, 0.05));
  }
  body.softening = 0.05;
  // Faces outward counter-clockwise: (+x, +y, +z) = (0, 2, 4) and the other octants.
  body.faces = {{0, 2, 4}, {0, 4, 3}, {1, 4, 2}, {1, 3, 4}, {0, 5, 2}, {0, 3, 5}, {1, 2, 5}, {1, 5, 3}};
  auto add_spring = [&](std::int32_t i, std::int32_t j, SpringKind kind) {
    body.springs.push_back({i, j});
    body.spring_kind.push_back(static_cast<std::uint8_t>(kind));
  };
  // Hinge {wing_1, wing_2, edge_a, edge_b}: the face with the directed edge a->b holds wing_1, the
  // face with b->a holds wing_2.
  for (const auto& f : body.faces)
    for (int e = 0; e < 3; ++e) {
      const std::int32_t a = f[e], b = f[(e + 1) % 3], wing = f[(e + 2) % 3];
      if (a > b) continue;
      for (const auto& g : body.faces)
        for (int r = 0; r < 3; ++r)
          if (g[r] == b && g[(r + 1) % 3] == a) body.hinges.push_back({wing, g[(r + 2) % 3], a, b});
      add_spring(a, b, SpringKind::shell);
    }
  add_spring(6, 7, SpringKind::interior);
  add_spring(7, 8, SpringKind::interior);
  add_spring(6, 8, SpringKind::interior);
  for (std::int32_t i = 0; i < 6; ++i) add_spring(i, 6 + i % 3, SpringKind::cross);
  for (std::size_t s = 0; s < body.spring_count(); ++s) {
    const Vec3 d = vec3_at(state.position, static_cast<std::size_t>(body.springs[s][0])) -
                   vec3_at(state.position, static_cast<std::size_t>(body.springs[s][1]));
    state.springs.rest_length.push_back(d.norm() / (1 + random.uniform(-0.04, 0.06)));
    const auto kind = static_cast<SpringKind>(body.spring_kind[s]);
    state.springs.stiffness.push_back(kind == SpringKind::shell ? 0.06 : kind == SpringKind::interior ? 0.1 : 0.05);
    state.springs.failed.push_back(0);
  }
  body.strength_factor.assign(body.spring_count(), 1.0);  // a uniform crust
  for (const auto& h : body.hinges) {
    const double theta = hinge_angle(vec3_at(state.position, static_cast<std::size_t>(h[0])),
                                     vec3_at(state.position, static_cast<std::size_t>(h[1])),
                                     vec3_at(state.position, static_cast<std::size_t>(h[2])),
                                     vec3_at(state.position, static_cast<std::size_t>(h[3])));
    state.hinges.rest_angle.push_back(theta - random.uniform(-0.2, 0.2));
    body.hinge_stiffness.push_back(0.01);
  }
  state.perturber = {true, 0.5, {2.0, 1.0, -0.5}, {0.0, -1.0, 0.2}};
  c.stage.clock = StepClock{state.time, state.step, 0.003};
  return c;
}

}  // namespace tidalcrust::test_support
