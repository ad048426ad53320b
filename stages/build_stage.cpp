#include "stages/build_stage.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "base/errors.hpp"
#include "forces/hinge_geometry.hpp"
#include "bodies/cross_support.hpp"
#include "bodies/icosphere.hpp"
#include "bodies/interior_builder.hpp"
#include "bodies/material_body.hpp"
#include "model/derived_quantities.hpp"
#include "bodies/neighbor_grid.hpp"
#include "bodies/shell_hinges.hpp"
#include "bodies/welded_coupling.hpp"

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

/// The constants the springs and hinges are built with: the printed ones, or for a [material]
/// body those derived from the material on this network (docs/material.md).
struct BuildConstants {
  double interior = 0;        ///< k_I of a mantle spring, G M^2/R^3
  double shell = 0;           ///< k_S
  double bending = 0;         ///< k_e, G M^2/R^2
  double cross = 0;           ///< k_C
  double cross_distance = 0;  ///< d_C, R
};

bool inside_core(const Config& config, const Vec3& p) { return config.core.present() && p.norm() < *config.core.radius; }

/// The stiffness factor of interior spring (i, j): core.modulus_ratio when its midpoint lies in the core.
double core_stiffness_factor(const Config& config, const Vec3& a, const Vec3& b) {
  return inside_core(config, 0.5 * (a + b)) ? config.core.modulus_ratio.value_or(1.0) : 1.0;
}

}  // namespace

Checkpoint build_stage(const Config& config) {
  check_buildable(config);
  const bool welded = config.shell.enabled && config.cross.coupling == CrossCoupling::welded;
  const InteriorNetwork interior = welded ? welded_interior(config.interior, config.workflow.seed)
                                          : build_interior(config.interior, config.workflow.seed);
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
  if (config.core.present()) {
    // Core nodes are density_ratio times heavier (nodes fill core and mantle equally densely);
    // the interior keeps its mass 1 - M_S.
    const double ratio = config.core.density_ratio.value_or(1.0);
    double weights = 0;
    for (std::size_t i = 0; i < n_interior; ++i) weights += inside_core(config, interior.nodes[i]) ? ratio : 1.0;
    for (std::size_t i = 0; i < n_interior; ++i)
      body.mass[i] = (1.0 - shell_mass) * (inside_core(config, interior.nodes[i]) ? ratio : 1.0) / weights;
  }
  BuildConstants k{config.interior.spring_constant, config.shell.spring_constant, config.shell.bending_constant,
                   config.cross.spring_constant, config.cross.distance};
  if (config.from_material()) {
    // eq. 15 exact on this network: the mantle's springs (outside the core) over its volume. A
    // welded body restores the springs the network lacks near its surface, so its modulus is that
    // of the complete network: eq. 15 over the springs deeper than d_I (midpoints inside r_I - d_I).
    const double r_c = config.core.present() ? *config.core.radius : 0.0;
    const double r_i = welded ? std::max(config.interior.radius - config.interior.spring_distance, r_c)
                              : config.interior.radius;
    double sum_length2 = 0;
    for (const auto& [i, j] : interior.springs) {
      const Vec3& a = interior.nodes[static_cast<std::size_t>(i)];
      const Vec3& b = interior.nodes[static_cast<std::size_t>(j)];
      if (welded && (0.5 * (a + b)).norm() >= r_i) continue;
      if (!inside_core(config, 0.5 * (a + b))) sum_length2 += (a - b).squaredNorm();
    }
    const double mantle_volume = 4.0 / 3.0 * std::numbers::pi * (r_i * r_i * r_i - r_c * r_c * r_c);
    if (!(sum_length2 > 0))
      throw InputError("[material]: the interior network has no springs; raise resolution.interior_count");
    k.interior = spring_constant_for_modulus(*config.material.youngs_modulus, mantle_volume, sum_length2);
    if (config.shell.enabled) {
      k.cross_distance =
          cross_distance_for(interior.nodes, shell.nodes, config.resolution.cross_per_shell_node.value_or(2.33));
      k.bending = hinge_constant_for_rigidity(material_flexural_rigidity(config.material));
    }
  }

  state.time = 0;
  state.step = 0;
  state.position.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i) set_vec3(state.position, i, positions[i]);
  state.velocity.assign(3 * n, 0.0);

  for (const auto& [i, j] : interior.springs) {
    double stiffness = k.interior;
    if (config.core.present())
      stiffness *= core_stiffness_factor(config, interior.nodes[static_cast<std::size_t>(i)],
                                         interior.nodes[static_cast<std::size_t>(j)]);
    add_spring(body, state, i, j, SpringKind::interior, stiffness);
  }
  for (const auto& [i, j] : shell.edges)
    add_spring(body, state, shell_offset + i, shell_offset + j, SpringKind::shell, k.shell);
  if (welded) {
    // The shell joined into the interior network (bodies/welded_coupling.hpp): the mantle's k_I.
    const double r_i = config.interior.radius;
    const WeldedInterior weld{r_i, config.interior.spring_distance, k.interior,
                              static_cast<double>(n_interior) / (4.0 / 3.0 * std::numbers::pi * r_i * r_i * r_i),
                              interior_pair_factor(interior.nodes, interior.springs, r_i, config.interior.spring_distance)};
    for (const auto& w : welded_springs(weld, interior.nodes, shell.nodes))
      add_spring(body, state, w.interior, shell_offset + w.shell, SpringKind::cross, w.stiffness);
    if (body.count_springs(SpringKind::cross) == 0)
      throw InputError("cross.coupling = \"welded\": no interior node lies within interior.spring_distance of the "
                       "shell, so the shell is unsupported");
  } else if (config.shell.enabled) {
    NeighborGrid shell_grid(Vec3(-1, -1, -1), Vec3(1, 1, 1), k.cross_distance);
    for (const auto& p : shell.nodes) shell_grid.insert(p);
    std::vector<std::array<std::int32_t, 2>> cross;  // (interior, shell) pairs
    for (std::size_t i = 0; i < n_interior; ++i)
      for (std::int32_t s : shell_grid.closer_than(interior.nodes[i], k.cross_distance))
        cross.push_back({static_cast<std::int32_t>(i), s});
    const auto extra = supplementary_cross_springs(interior.nodes, shell.nodes, cross,
                                                   static_cast<int>(config.cross.min_per_shell_node));
    cross.insert(cross.end(), extra.begin(), extra.end());
    if (config.from_material() && !cross.empty()) {
      // eq. 25 exact on this network: V_Co = coupling_speed_ratio * V_IP (eq. 16).
      double lengths = 0;
      for (const auto& [i, s] : cross)
        lengths += (interior.nodes[static_cast<std::size_t>(i)] - shell.nodes[static_cast<std::size_t>(s)]).norm();
      const double count = static_cast<double>(cross.size());
      const double speed = config.material.coupling_speed_ratio.value_or(1.0) *
                           p_wave_speed(*config.material.youngs_modulus);
      k.cross = cross_constant_for_speed(speed, lengths / count, shell_mass, count);
    }
    for (const auto& [i, s] : cross)
      add_spring(body, state, i, shell_offset + s, SpringKind::cross, k.cross);
    if (body.count_springs(SpringKind::cross) == 0)
      throw InputError(fmt::format(
          "cross.distance = {}: no interior node lies that close to the shell, so the shell is unsupported",
          k.cross_distance));
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
    body.hinge_stiffness.push_back(k.bending);
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
