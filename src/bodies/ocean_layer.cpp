#include "bodies/ocean_layer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "base/errors.hpp"

namespace tidalcrust {

void add_ocean(BuiltBody& built, double thickness, double bulk_modulus) {
  Body& body = built.body;
  State& state = built.state;
  const std::size_t n = body.particle_count();
  const double floor_radius = 1.0 - thickness;
  const auto liquid = static_cast<std::uint8_t>(Species::liquid);
  std::size_t liquid_count = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (body.species[i] == static_cast<std::uint8_t>(Species::interior) && vec3_at(state.position, i).norm() > floor_radius) {
      body.species[i] = liquid;
      ++liquid_count;
    }
  if (liquid_count == 0)
    throw InputError(fmt::format("ocean.thickness = {}: no interior node lies above the ocean floor at r = {}", thickness,
                                 floor_radius));

  // A spring with a liquid end becomes a liquid spring (stiffness 0 in the spring law; the
  // volumetric energy instead); a cross spring between the crust and a solid node below the ocean
  // would cross it and goes. Order and everything stored per spring are kept.
  std::size_t kept = 0;
  const bool factors = !body.strength_factor.empty();
  for (std::size_t s = 0; s < body.spring_count(); ++s) {
    const auto [i, j] = body.springs[s];
    const bool wet = body.species[static_cast<std::size_t>(i)] == liquid || body.species[static_cast<std::size_t>(j)] == liquid;
    if (!wet && body.spring_kind[s] == static_cast<std::uint8_t>(SpringKind::cross)) continue;
    body.springs[kept] = body.springs[s];
    body.spring_kind[kept] = wet ? static_cast<std::uint8_t>(SpringKind::liquid) : body.spring_kind[s];
    if (factors) body.strength_factor[kept] = body.strength_factor[s];
    state.springs.rest_length[kept] = state.springs.rest_length[s];
    state.springs.stiffness[kept] = wet ? 0.0 : state.springs.stiffness[s];
    state.springs.failed[kept] = state.springs.failed[s];
    ++kept;
  }
  body.springs.resize(kept);
  body.spring_kind.resize(kept);
  if (factors) body.strength_factor.resize(kept);
  state.springs.rest_length.resize(kept);
  state.springs.stiffness.resize(kept);
  state.springs.failed.resize(kept);

  // Each liquid particle's share of the layer, from the floor to the crust's mean radius.
  double crust = 0;
  std::size_t crust_nodes = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (body.species[i] == static_cast<std::uint8_t>(Species::shell)) {
      crust += vec3_at(state.position, i).norm();
      ++crust_nodes;
    }
  crust = crust_nodes ? crust / static_cast<double>(crust_nodes) : 1.0;
  const double volume = 4.0 / 3.0 * std::numbers::pi * (crust * crust * crust - floor_radius * floor_radius * floor_radius);
  body.liquid.bulk_modulus = bulk_modulus;
  body.liquid.node_volume.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    if (body.species[i] == liquid) body.liquid.node_volume[i] = volume / static_cast<double>(liquid_count);
  for (std::size_t i = 0; i < n; ++i)
    if (body.species[i] == liquid && std::none_of(body.springs.begin(), body.springs.end(), [&](const auto& ends) {
          return static_cast<std::size_t>(ends[0]) == i || static_cast<std::size_t>(ends[1]) == i;
        }))
      throw InputError(fmt::format("ocean: liquid particle {} at r = {:.3f} has no spring; the interior network does "
                                   "not reach it (interior.spring_distance)", i, vec3_at(state.position, i).norm()));
}

}  // namespace tidalcrust
