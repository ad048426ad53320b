#include "bodies/ocean_layer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "base/errors.hpp"
#include "bodies/neighbor_grid.hpp"
#include "forces/liquid_pressure.hpp"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

namespace tidalcrust {

namespace {

/// The Delaunay tetrahedra of the liquid particles, the crust's nodes and the interior nodes within
/// 1.5 mean liquid spacings of a liquid particle (the floor), those with a liquid or crust corner
/// (not inside the solid interior) and no edge longer than 3 spacings (not across the interior), in
/// a canonical order (corners sorted, then tetrahedra sorted) and positively oriented.
std::vector<std::array<std::int32_t, 4>> liquid_tetrahedra(const Body& body, const State& state, double floor_radius) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Vertex = CGAL::Triangulation_vertex_base_with_info_3<std::int32_t, Kernel>;
  using Data = CGAL::Triangulation_data_structure_3<Vertex>;
  using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Data>;
  const auto liquid = static_cast<std::uint8_t>(Species::liquid);
  const std::size_t n = body.particle_count();
  std::size_t liquid_count = 0;
  double top = floor_radius;
  for (std::size_t i = 0; i < n; ++i)
    if (body.species[i] == liquid) {
      ++liquid_count;
      top = std::max(top, vec3_at(state.position, i).norm());
    }
  const double spacing = std::cbrt(4.0 / 3.0 * std::numbers::pi * (top * top * top - floor_radius * floor_radius * floor_radius) /
                                   static_cast<double>(liquid_count));
  NeighborGrid grid(Vec3::Constant(-1.5), Vec3::Constant(1.5), spacing);
  for (std::size_t i = 0; i < n; ++i)
    if (body.species[i] == liquid) grid.insert(vec3_at(state.position, i));
  std::vector<std::pair<Kernel::Point_3, std::int32_t>> points;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 x = vec3_at(state.position, i);
    if (body.species[i] != static_cast<std::uint8_t>(Species::interior) || grid.any_closer_than(x, 1.5 * spacing))
      points.emplace_back(Kernel::Point_3(x.x(), x.y(), x.z()), static_cast<std::int32_t>(i));
  }
  const Delaunay delaunay(points.begin(), points.end());
  std::vector<std::array<std::int32_t, 4>> tets;
  for (auto cell = delaunay.finite_cells_begin(); cell != delaunay.finite_cells_end(); ++cell) {
    std::array<std::int32_t, 4> t{};
    bool in_layer = false;
    for (int v = 0; v < 4; ++v) {
      t[static_cast<std::size_t>(v)] = cell->vertex(v)->info();
      in_layer = in_layer || body.species[static_cast<std::size_t>(t[static_cast<std::size_t>(v)])] !=
                                 static_cast<std::uint8_t>(Species::interior);
    }
    if (!in_layer) continue;
    // Not across the empty core below the floor's outer nodes: no edge longer than 3 spacings.
    bool long_edge = false;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        long_edge = long_edge || (vec3_at(state.position, static_cast<std::size_t>(t[static_cast<std::size_t>(a)])) -
                                  vec3_at(state.position, static_cast<std::size_t>(t[static_cast<std::size_t>(b)])))
                                         .norm() > 3 * spacing;
    if (long_edge) continue;
    std::sort(t.begin(), t.end());
    const double* p = state.position.data();
    if (tetrahedron_volume(p + 3 * t[0], p + 3 * t[1], p + 3 * t[2], p + 3 * t[3]) < 0) std::swap(t[2], t[3]);
    tets.push_back(t);
  }
  std::sort(tets.begin(), tets.end());
  return tets;
}

}  // namespace

void add_ocean(BuiltBody& built, double thickness, double bulk_modulus, double shear_fraction) {
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

  // A spring with a liquid end becomes a liquid spring (shear_fraction of its stiffness: the
  // volumetric energy carries the pressure); a cross spring between the crust and a solid node below the ocean
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
    state.springs.stiffness[kept] = wet ? shear_fraction * state.springs.stiffness[s] : state.springs.stiffness[s];
    state.springs.failed[kept] = state.springs.failed[s];
    ++kept;
  }
  body.springs.resize(kept);
  body.spring_kind.resize(kept);
  if (factors) body.strength_factor.resize(kept);
  state.springs.rest_length.resize(kept);
  state.springs.stiffness.resize(kept);
  state.springs.failed.resize(kept);

  // The tetrahedra of the layer: the Delaunay tetrahedra of the liquid particles and the solid
  // ones within reach of them (CGAL, exact predicates: unique for points in general position, so
  // independent of the order of insertion) that have a liquid corner, oriented positively.
  body.liquid.bulk_modulus = bulk_modulus;
  body.liquid.tetrahedra = liquid_tetrahedra(body, state, floor_radius);
  std::vector<std::uint8_t> covered(n, 0);
  for (const auto& t : body.liquid.tetrahedra)
    for (const std::int32_t i : t) covered[static_cast<std::size_t>(i)] = 1;
  for (std::size_t i = 0; i < n; ++i)
    if (body.species[i] == liquid && !covered[i])
      throw InputError(fmt::format("ocean: liquid particle {} at r = {:.3f} lies in no tetrahedron of the layer", i,
                                   vec3_at(state.position, i).norm()));
  // The liquid's mass lumped onto the corners of the tetrahedra in the shares that own volume
  // (V_t / 4 each, density the liquid's mass over the layer's volume): the consistent lumping of a
  // linear tetrahedron, so that the pressure's push on every node, the crust's and the floor's too,
  // matches the weight of the liquid it carries (docs/ocean.md). Sums in tetrahedron order.
  std::vector<double> tet_volume(body.liquid.tetrahedra.size());
  double liquid_mass = 0, layer_volume = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (body.species[i] == liquid) {
      liquid_mass += body.mass[i];
      body.mass[i] = 0;
    }
  const double* p = state.position.data();
  for (std::size_t t = 0; t < tet_volume.size(); ++t) {
    const auto& c = body.liquid.tetrahedra[t];
    tet_volume[t] = tetrahedron_volume(p + 3 * c[0], p + 3 * c[1], p + 3 * c[2], p + 3 * c[3]);
    layer_volume += tet_volume[t];
  }
  const double density = liquid_mass / layer_volume;
  for (std::size_t t = 0; t < tet_volume.size(); ++t)
    for (const std::int32_t i : body.liquid.tetrahedra[t]) body.mass[static_cast<std::size_t>(i)] += 0.25 * density * tet_volume[t];
  // Zero pressure as built; the stretch stage sets the hydrostatic rest volumes.
  state.liquid_rest_volume = LiquidPressure(body).volumes(state.position.data());
}

}  // namespace tidalcrust
