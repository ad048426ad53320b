#include "bodies/build_body.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string_view>
#include <vector>

#include "base/errors.hpp"
#include "bodies/body_type.hpp"
#include "bodies/cross_support.hpp"
#include "bodies/icosphere.hpp"
#include "bodies/interior_builder.hpp"
#include "bodies/material_body.hpp"
#include "bodies/neighbor_grid.hpp"
#include "bodies/shell_hinges.hpp"
#include "bodies/ocean_layer.hpp"
#include "bodies/welded_coupling.hpp"
#include "forces/hinge_geometry.hpp"
#include "model/crust_field.hpp"

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

void add_spring(BuiltBody& out, std::int32_t i, std::int32_t j, SpringKind kind, double stiffness) {
  out.body.springs.push_back({i, j});
  out.body.spring_kind.push_back(static_cast<std::uint8_t>(kind));
  out.state.springs.rest_length.push_back((vec3_at(out.state.position, static_cast<std::size_t>(i)) -
                                           vec3_at(out.state.position, static_cast<std::size_t>(j)))
                                              .norm());
  out.state.springs.stiffness.push_back(stiffness);
}

/// Masses, species and positions at rest: interior nodes (1 - M_S) w / sum w with the body
/// type's weights w, shell nodes M_S / N_S each.
void place_particles(BuiltBody& out, const Config& config, const BodyType& type, const std::vector<Vec3>& interior,
                     const std::vector<Vec3>& shell) {
  const double shell_mass = config.shell.enabled ? config.shell.mass : 0.0;
  const std::size_t n = interior.size() + shell.size();
  Body& body = out.body;
  body.mass.resize(n);
  body.species.resize(n);
  double weights = 0;
  for (const Vec3& p : interior) weights += type.node_mass_weight(config, p);
  for (std::size_t i = 0; i < interior.size(); ++i) {
    body.mass[i] = (1.0 - shell_mass) * type.node_mass_weight(config, interior[i]) / weights;
    body.species[i] = static_cast<std::uint8_t>(Species::interior);
  }
  for (std::size_t s = 0; s < shell.size(); ++s) {
    body.mass[interior.size() + s] = shell_mass / static_cast<double>(shell.size());
    body.species[interior.size() + s] = static_cast<std::uint8_t>(Species::shell);
  }
  State& state = out.state;
  state.time = 0;
  state.step = 0;
  state.position.resize(3 * n);
  for (std::size_t i = 0; i < interior.size(); ++i) set_vec3(state.position, i, interior[i]);
  for (std::size_t s = 0; s < shell.size(); ++s) set_vec3(state.position, interior.size() + s, shell[s]);
  state.velocity.assign(3 * n, 0.0);
}

/// The springs that hold the shell on the interior, appended as SpringKind::cross.
void add_cross_springs(BuiltBody& out, const Config& config, const InteriorNetwork& interior,
                       const Icosphere& shell, const SpringConstants& k) {
  const auto shell_offset = static_cast<std::int32_t>(interior.nodes.size());
  if (config.cross.coupling == CrossCoupling::welded) {
    // The shell joined into the interior network (bodies/welded_coupling.hpp): the mantle's k_I.
    const double r_i = config.interior.radius;
    const WeldedInterior weld{
        r_i, config.interior.spring_distance, k.interior,
        static_cast<double>(interior.nodes.size()) / (4.0 / 3.0 * std::numbers::pi * r_i * r_i * r_i),
        interior_pair_factor(interior.nodes, interior.springs, r_i, config.interior.spring_distance)};
    for (const auto& w : welded_springs(weld, interior.nodes, shell.nodes))
      add_spring(out, w.interior, shell_offset + w.shell, SpringKind::cross, w.stiffness);
    if (out.body.count_springs(SpringKind::cross) == 0)
      throw InputError("cross.coupling = \"welded\": no interior node lies within interior.spring_distance of the "
                       "shell, so the shell is unsupported");
    return;
  }
  const auto cross = cross_springs_within(interior.nodes, shell.nodes, k.cross_distance,
                                          static_cast<int>(config.cross.min_per_shell_node));
  const double k_cross = config.from_material() && !cross.empty()
                             ? material_cross_constant(config, interior.nodes, shell.nodes, cross, config.shell.mass)
                             : k.cross;
  for (const auto& [i, s] : cross) add_spring(out, i, shell_offset + s, SpringKind::cross, k_cross);
  if (cross.empty())
    throw InputError(fmt::format(
        "cross.distance = {}: no interior node lies that close to the shell, so the shell is unsupported",
        k.cross_distance));
}

/// The shell's triangles and one bending hinge per shell edge, at its built dihedral angle.
void add_shell_hinges(BuiltBody& out, const Icosphere& shell, std::int32_t shell_offset, double bending) {
  for (const auto& f : shell.faces)
    out.body.faces.push_back({shell_offset + f[0], shell_offset + f[1], shell_offset + f[2]});
  for (const auto& h : make_hinges(shell.edges, shell.faces)) {
    const std::array<std::int32_t, 4> hinge{shell_offset + h[0], shell_offset + h[1], shell_offset + h[2],
                                            shell_offset + h[3]};
    out.body.hinges.push_back(hinge);
    const auto at = [&](int c) { return vec3_at(out.state.position, static_cast<std::size_t>(hinge[c])); };
    out.state.hinges.rest_angle.push_back(hinge_angle(at(0), at(1), at(2), at(3)));
    out.body.hinge_stiffness.push_back(bending);
  }
}

/// The [crust] field sampled into the body (docs/crust.md). Thickness: t at each shell node, divided
/// by its mean over the nodes (so that the crust's mass stays M_S and its mean thickness h_S),
/// scales the node's mass (rho_S h); t at a shell spring's midpoint its stiffness (k_S = (sqrt 3 / 2)
/// E_S h, eq. 20); t^3 at the midpoint of a hinge's edge its k_e (4 D_F, D_F ~ E_S h^3, eq. 23).
/// Strength: the factor at a shell spring's midpoint (directions from the origin, the built body's
/// centre). Every other spring keeps factor 1; a uniform crust changes nothing else.
void vary_crust(BuiltBody& out, const Config& config) {
  Body& body = out.body;
  body.strength_factor.assign(body.spring_count(), 1.0);
  if (!config.crust.given()) return;
  const CrustField field = make_crust_field(config.crust, "crust");
  const auto at = [&](std::int32_t i) { return vec3_at(out.state.position, static_cast<std::size_t>(i)); };
  const auto positive = [](double value, const Vec3& where, const char* what, const char* keys) {
    if (value > 0) return value;
    throw InputError(fmt::format("{}: the crust's {} factor is {:g} <= 0 at lon {:.1f}, lat {:.1f} deg", keys, what, value,
                                 std::atan2(where.y(), where.x()) * 180 / std::numbers::pi,
                                 std::asin(where.normalized().z()) * 180 / std::numbers::pi));
  };
  constexpr const char* thickness_keys = "crust.thickness_harmonics (with crust.map_file)";
  constexpr const char* strength_keys = "crust.strength_harmonics (with crust.map_file, crust.weak_lines)";
  const auto thickness = [&](const Vec3& x) { return positive(field.thickness_factor(x), x, "thickness", thickness_keys); };
  if (field.thickness_varies()) {
    double sum = 0;
    std::size_t nodes = 0;
    for (std::size_t i = 0; i < body.particle_count(); ++i)
      if (body.species[i] == static_cast<std::uint8_t>(Species::shell))
        sum += thickness(at(static_cast<std::int32_t>(i))), ++nodes;
    const double mean = sum / static_cast<double>(nodes);
    for (std::size_t i = 0; i < body.particle_count(); ++i)
      if (body.species[i] == static_cast<std::uint8_t>(Species::shell))
        body.mass[i] *= thickness(at(static_cast<std::int32_t>(i))) / mean;
    for (std::size_t n = 0; n < body.spring_count(); ++n)
      if (body.spring_kind[n] == static_cast<std::uint8_t>(SpringKind::shell))
        out.state.springs.stiffness[n] *= thickness(0.5 * (at(body.springs[n][0]) + at(body.springs[n][1]))) / mean;
    for (std::size_t h = 0; h < body.hinge_count(); ++h) {
      const double t = thickness(0.5 * (at(body.hinges[h][2]) + at(body.hinges[h][3]))) / mean;
      body.hinge_stiffness[h] *= t * t * t;
    }
  }
  for (std::size_t n = 0; n < body.spring_count(); ++n)
    if (body.spring_kind[n] == static_cast<std::uint8_t>(SpringKind::shell)) {
      const Vec3 mid = 0.5 * (at(body.springs[n][0]) + at(body.springs[n][1]));
      body.strength_factor[n] = positive(field.strength_factor(mid), mid, "strength", strength_keys);
    }
}

/// The keys that set the stiffness of each spring kind and of the hinges, and of the node
/// masses, as messages name them.
std::string stiffness_keys(const Config& config, std::string_view element) {
  const char* material = config.from_material() ? " (derived from [material])" : "";
  if (element == "interior") return fmt::format("interior.spring_constant{}", material);
  if (element == "shell") return fmt::format("shell.spring_constant{}", material);
  if (element == "cross") return fmt::format("cross.spring_constant{}", material);
  return fmt::format("shell.bending_constant{}", material);
}

/// InputError naming the keys unless every spring and hinge of the built body oscillates at a
/// finite omega^2 that some allowed time step resolves (omega^2 dt^2 <= 4 with dt >= the smallest
/// integrator.dt): valid-looking keys can give derived quantities that overflow or underflow
/// (shell.mass = 1e-320 gives shell nodes of 6e-323 M; a spring constant of 1e308 an omega^2 of
/// inf), which no stage can integrate. omega^2 of a spring k (1/m_i + 1/m_j); of a hinge k_e over
/// the lightest node's mass and its shortest side (k_e is a force: k_e/L a stiffness).
void check_body_scales(const BuiltBody& built, const Config& config) {
  constexpr double limit = 4.0 / (min_time_step * min_time_step);
  const Body& body = built.body;
  const auto refuse = [&](std::string_view element, double omega2, double k, double mass) {
    throw InputError(fmt::format(
        "{} = {:g} and node masses of {:g} M (shell.mass = {:g}, interior.count = {}) give {} springs omega^2 = {:g} "
        "1/t_grav^2, which no time step resolves (integrator.dt >= {:g} needs omega^2 <= {:g})",
        stiffness_keys(config, element), k, mass, config.shell.mass, config.interior.count,
        element == "bending" ? "the shell's hinges (bending)" : fmt::format("the {}", element), omega2, min_time_step,
        limit));
  };
  for (std::size_t i = 0; i < body.particle_count(); ++i)
    if (!std::isnormal(body.mass[i]))
      throw InputError(fmt::format("shell.mass = {:g} and interior.count = {} give {} nodes of {:g} M, not a normal "
                                   "number (the arithmetic of every step would lose it)",
                                   config.shell.mass, config.interior.count,
                                   body.species[i] == static_cast<std::uint8_t>(Species::shell) ? "shell" : "interior",
                                   body.mass[i]));
  for (std::size_t s = 0; s < body.spring_count(); ++s) {
    const auto [i, j] = body.springs[s];
    const double mi = body.mass[static_cast<std::size_t>(i)], mj = body.mass[static_cast<std::size_t>(j)];
    const double k = built.state.springs.stiffness[s];
    const double omega2 = k * (1.0 / mi + 1.0 / mj);
    if (!(omega2 <= limit)) {
      const auto kind = static_cast<SpringKind>(body.spring_kind[s]);
      refuse(kind == SpringKind::interior ? "interior" : kind == SpringKind::shell ? "shell" : "cross", omega2, k,
             std::min(mi, mj));
    }
  }
  for (std::size_t h = 0; h < body.hinge_count(); ++h) {
    const auto& v = body.hinges[h];
    double mass = std::numeric_limits<double>::infinity(), side2 = mass;
    for (int a = 0; a < 4; ++a) {
      const auto i = static_cast<std::size_t>(v[a]);
      mass = std::min(mass, body.mass[i]);
      for (int b = a + 1; b < 4; ++b)
        side2 = std::min(side2, (vec3_at(built.state.position, i) -
                                 vec3_at(built.state.position, static_cast<std::size_t>(v[b])))
                                    .squaredNorm());
    }
    const double omega2 = body.hinge_stiffness[h] / (mass * std::sqrt(side2));  // k_e/L: a stiffness
    if (!(omega2 <= limit)) refuse("bending", omega2, body.hinge_stiffness[h], mass);
  }
}

}  // namespace

BuiltBody build_body(const Config& config) {
  check_buildable(config);
  const BodyType& type = body_type(config);
  const bool welded = config.shell.enabled && config.cross.coupling == CrossCoupling::welded;
  const InteriorNetwork interior = welded ? welded_interior(config.interior, config.workflow.seed)
                                          : build_interior(config.interior, config.workflow.seed);
  Icosphere shell;
  if (config.shell.enabled) shell = make_icosphere(static_cast<int>(config.shell.level));
  const auto shell_offset = static_cast<std::int32_t>(interior.nodes.size());

  BuiltBody out;
  place_particles(out, config, type, interior.nodes, shell.nodes);
  const SpringConstants k = config.from_material()
                                ? material_spring_constants(config, type, interior.nodes, interior.springs,
                                                            shell.nodes, welded)
                                : printed_spring_constants(config);
  for (const auto& [i, j] : interior.springs) {
    const Vec3 midpoint = 0.5 * (interior.nodes[static_cast<std::size_t>(i)] + interior.nodes[static_cast<std::size_t>(j)]);
    add_spring(out, i, j, SpringKind::interior, k.interior * type.spring_stiffness_factor(config, midpoint));
  }
  for (const auto& [i, j] : shell.edges) add_spring(out, shell_offset + i, shell_offset + j, SpringKind::shell, k.shell);
  if (config.shell.enabled) add_cross_springs(out, config, interior, shell, k);
  out.state.springs.failed.assign(out.body.spring_count(), 0);
  add_shell_hinges(out, shell, shell_offset, k.bending);
  vary_crust(out, config);
  if (config.ocean.present())
    add_ocean(out, *config.ocean.thickness,
              config.ocean.bulk_modulus ? *config.ocean.bulk_modulus : *config.material.youngs_modulus / 1.5,
              config.ocean.shear_fraction.value_or(OceanConfig::default_shear_fraction));
  if (config.ocean.present()) out.body.liquid.maxwell_time = config.ocean.maxwell_time.value_or(0.0);

  std::vector<Vec3> positions(interior.nodes);
  positions.insert(positions.end(), shell.nodes.begin(), shell.nodes.end());
  out.min_spacing = min_pair_distance(positions);
  out.body.softening = config.integrator.softening_fraction * out.min_spacing;
  out.interior_trials = interior.trials;
  check_body_scales(out, config);
  return out;
}

}  // namespace tidalcrust
