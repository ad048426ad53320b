#include "stages/build_stage.hpp"

#include <fmt/format.h>

#include <cmath>

#include "base/errors.hpp"
#include "forces/hinge_geometry.hpp"
#include "bodies/cross_support.hpp"
#include "bodies/icosphere.hpp"
#include "bodies/interior_builder.hpp"
#include "bodies/neighbor_grid.hpp"
#include "bodies/shell_hinges.hpp"

namespace tidalcrust {
namespace {

/// Relations between keys that validate() does not know about because only building needs them.
void check_buildable(const Config& config) {
  if (!config.shell.enabled) return;
  if (config.interior.radius >= 1.0)
    throw InputError(fmt::format(
        "interior.radius = {} must be < 1 when shell.enabled = true (the interior must lie inside the shell "
        "of radius R = 1)",
        config.interior.radius));
  if (!(config.shell.mass > 0))
    throw InputError("shell.mass must be > 0 when shell.enabled = true (massless shell nodes)");
  const double gap = 1.0 - config.interior.radius;
  if (config.cross.distance <= gap)
    throw InputError(fmt::format(
        "cross.distance = {} must exceed the gap 1 - interior.radius = {} or no cross spring can reach the shell",
        config.cross.distance, gap));
}

void add_spring(Body& body, State& state, std::int32_t i, std::int32_t j, SpringKind kind, double stiffness) {
  body.springs.push_back({i, j});
  body.spring_kind.push_back(static_cast<std::uint8_t>(kind));
  state.springs.rest_length.push_back((vec3_at(state.position, static_cast<std::size_t>(i)) -
                                       vec3_at(state.position, static_cast<std::size_t>(j)))
                                          .norm());
  state.springs.stiffness.push_back(stiffness);
}

}  // namespace

Checkpoint build_stage(const Config& config) {
  check_buildable(config);
  const InteriorNetwork interior = build_interior(config.interior, config.workflow.seed);
  Icosphere shell;
  if (config.shell.enabled) shell = make_icosphere(static_cast<int>(config.shell.level));

  const std::size_t n_interior = interior.nodes.size();
  const std::size_t n_shell = shell.nodes.size();
  const std::size_t n = n_interior + n_shell;
  const auto shell_offset = static_cast<std::int32_t>(n_interior);

  Checkpoint out;
  Body& body = out.body;
  State& state = out.state;
  std::vector<Vec3> positions(interior.nodes);
  positions.insert(positions.end(), shell.nodes.begin(), shell.nodes.end());

  const double shell_mass = config.shell.enabled ? config.shell.mass : 0.0;
  body.mass.resize(n);
  body.species.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const bool in_shell = i >= n_interior;
    body.mass[i] = in_shell ? shell_mass / static_cast<double>(n_shell)
                            : (1.0 - shell_mass) / static_cast<double>(n_interior);
    body.species[i] = static_cast<std::uint8_t>(in_shell ? Species::shell : Species::interior);
  }

  state.time = 0;
  state.step = 0;
  state.position.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i) set_vec3(state.position, i, positions[i]);
  state.velocity.assign(3 * n, 0.0);

  for (const auto& [i, j] : interior.springs)
    add_spring(body, state, i, j, SpringKind::interior, config.interior.spring_constant);
  for (const auto& [i, j] : shell.edges)
    add_spring(body, state, shell_offset + i, shell_offset + j, SpringKind::shell, config.shell.spring_constant);
  if (config.shell.enabled) {
    NeighborGrid shell_grid(Vec3(-1, -1, -1), Vec3(1, 1, 1), config.cross.distance);
    for (const auto& p : shell.nodes) shell_grid.insert(p);
    std::vector<std::array<std::int32_t, 2>> cross;  // (interior, shell) pairs
    for (std::size_t i = 0; i < n_interior; ++i)
      for (std::int32_t s : shell_grid.closer_than(interior.nodes[i], config.cross.distance))
        cross.push_back({static_cast<std::int32_t>(i), s});
    const auto extra = supplementary_cross_springs(interior.nodes, shell.nodes, cross,
                                                   static_cast<int>(config.cross.min_per_shell_node));
    cross.insert(cross.end(), extra.begin(), extra.end());
    for (const auto& [i, s] : cross)
      add_spring(body, state, i, shell_offset + s, SpringKind::cross, config.cross.spring_constant);
    if (body.count_springs(SpringKind::cross) == 0)
      throw InputError(fmt::format(
          "cross.distance = {}: no interior node lies that close to the shell, so the shell is unsupported",
          config.cross.distance));
  }
  const std::size_t n_springs = body.spring_count();
  state.springs.failed.assign(n_springs, 0);

  for (const auto& f : shell.faces) body.faces.push_back({shell_offset + f[0], shell_offset + f[1], shell_offset + f[2]});
  for (const auto& h : make_hinges(shell.edges, shell.faces)) {
    const std::array<std::int32_t, 4> hinge{shell_offset + h[0], shell_offset + h[1], shell_offset + h[2],
                                            shell_offset + h[3]};
    body.hinges.push_back(hinge);
    state.hinges.rest_angle.push_back(hinge_angle(positions[static_cast<std::size_t>(hinge[0])],
                                                  positions[static_cast<std::size_t>(hinge[1])],
                                                  positions[static_cast<std::size_t>(hinge[2])],
                                                  positions[static_cast<std::size_t>(hinge[3])]));
    body.hinge_stiffness.push_back(config.shell.bending_constant);
  }

  const double min_spacing = min_pair_distance(positions);
  body.softening = config.integrator.softening_fraction * min_spacing;

  out.stage.record = BuildRecord{static_cast<std::int64_t>(n_interior), interior.trials, min_spacing};
  out.stage.complete = true;
  // The body is built for this time step; instant stages keep it, stepping stages set their own.
  out.stage.clock = StepClock{0.0, 0, config.integrator.dt};
  out.stage.end_step = 0;
  out.config_toml = to_toml(config);
  return out;
}

}  // namespace tidalcrust
