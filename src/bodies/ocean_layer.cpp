#include "bodies/ocean_layer.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "base/errors.hpp"
#include "bodies/neighbor_grid.hpp"
#include "forces/liquid_pressure.hpp"

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

  // Keep the interior and shell springs between two solid particles, in their order, with
  // everything stored per spring.
  std::size_t kept = 0;
  const bool factors = !body.strength_factor.empty();
  for (std::size_t s = 0; s < body.spring_count(); ++s) {
    const auto [i, j] = body.springs[s];
    // A cross spring crosses the ocean even where it ends on a deeper solid node: it goes too.
    if (body.species[static_cast<std::size_t>(i)] == liquid || body.species[static_cast<std::size_t>(j)] == liquid ||
        body.spring_kind[s] == static_cast<std::uint8_t>(SpringKind::cross))
      continue;
    body.springs[kept] = body.springs[s];
    body.spring_kind[kept] = body.spring_kind[s];
    if (factors) body.strength_factor[kept] = body.strength_factor[s];
    state.springs.rest_length[kept] = state.springs.rest_length[s];
    state.springs.stiffness[kept] = state.springs.stiffness[s];
    state.springs.failed[kept] = state.springs.failed[s];
    ++kept;
  }
  body.springs.resize(kept);
  body.spring_kind.resize(kept);
  if (factors) body.strength_factor.resize(kept);
  state.springs.rest_length.resize(kept);
  state.springs.stiffness.resize(kept);
  state.springs.failed.resize(kept);

  // The liquid's mean spacing over the shell it fills, from the floor to the outermost liquid node.
  double top = floor_radius;
  for (std::size_t i = 0; i < n; ++i)
    if (body.species[i] == liquid) top = std::max(top, vec3_at(state.position, i).norm());
  const double volume = 4.0 / 3.0 * std::numbers::pi * (top * top * top - floor_radius * floor_radius * floor_radius);
  const double support = liquid_support_spacings * std::cbrt(volume / static_cast<double>(liquid_count));
  body.liquid.support_radius = support;
  // Liquid particles count in the density sums; a solid particle within a contact reach of the
  // liquid as built touches it at its closest liquid particle's distance (no force as built).
  const double spacing = support / liquid_support_spacings;
  body.liquid.density_weight.assign(n, 0.0);
  body.liquid.contact_radius.assign(n, 0.0);
  body.liquid.contact_stiffness = bulk_modulus * spacing;
  NeighborGrid grid(Vec3::Constant(-1.5), Vec3::Constant(1.5), support);
  for (std::size_t i = 0; i < n; ++i)
    if (body.species[i] == liquid) {
      grid.insert(vec3_at(state.position, i));
      body.liquid.density_weight[i] = 1.0;
    }
  for (std::size_t i = 0; i < n; ++i) {
    if (body.species[i] == liquid) continue;
    const Vec3 x = vec3_at(state.position, i);
    double closest = std::numeric_limits<double>::infinity();
    for (const std::int32_t j : grid.closer_than(x, liquid_contact_reach * spacing))
      closest = std::min(closest, (grid.point(j) - x).norm());
    if (std::isfinite(closest)) body.liquid.contact_radius[i] = closest;
  }
  body.liquid.bulk_modulus = bulk_modulus;  // for the density sums below; calibrated at the end
  const LiquidPressure pressure(body);
  state.liquid_reference_density = pressure.densities(state.position.data(), false);
  // The kernel sum follows a uniform compression only to a few per cent (fixed H): the layer's
  // bulk modulus is K times the mean of d ln n / d ln rho over its particles, so K is divided by it.
  constexpr double compression = 1e-4;  // relative change of volume
  std::vector<double> compressed = state.position;
  for (double& x : compressed) x *= std::cbrt(1 - compression);
  const std::vector<double> n_compressed = pressure.densities(compressed.data(), false);
  double response = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (body.species[i] == liquid)
      response += (n_compressed[i] / state.liquid_reference_density[i] - 1) * (1 - compression) / compression;
  response /= static_cast<double>(liquid_count);
  body.liquid.bulk_modulus = bulk_modulus / response;
}

}  // namespace tidalcrust
