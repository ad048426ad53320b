#include "bodies/material_body.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>

#include "base/errors.hpp"
#include "base/invariant.hpp"
#include "bodies/neighbor_grid.hpp"

namespace tidalcrust {

double cross_distance_for(const std::vector<Vec3>& interior, const std::vector<Vec3>& shell, double per_shell_node) {
  const auto wanted = static_cast<std::size_t>(std::llround(per_shell_node * static_cast<double>(shell.size())));
  if (interior.empty() || shell.empty() || wanted == 0) return 0.0;
  // Gather the pair distances below a cap, doubling the cap until enough pairs lie inside.
  double cap = 0.1;
  std::vector<double> distances;
  while (true) {
    NeighborGrid grid(Vec3(-1, -1, -1), Vec3(1, 1, 1), cap);
    for (const Vec3& p : interior) grid.insert(p);
    distances.clear();
    for (const Vec3& s : shell)
      for (std::int32_t i : grid.closer_than(s, cap)) distances.push_back((s - grid.point(i)).norm());
    if (distances.size() > wanted || cap > 4) break;
    cap *= 2;
  }
  std::sort(distances.begin(), distances.end());
  if (distances.size() <= wanted) return distances.back() * (1 + 1e-9);
  return 0.5 * (distances[wanted - 1] + distances[wanted]);
}

SpringConstants printed_spring_constants(const Config& config) {
  return {config.interior.spring_constant, config.shell.spring_constant, config.shell.bending_constant,
          config.cross.spring_constant, config.cross.distance};
}

SpringConstants material_spring_constants(const Config& config, const BodyType& body,
                                          const std::vector<Vec3>& interior_nodes,
                                          const std::vector<std::array<std::int32_t, 2>>& interior_springs,
                                          const std::vector<Vec3>& shell, bool welded) {
  SpringConstants k = printed_spring_constants(config);
  const double r_c = body.mantle_inner_radius(config);
  const double r_i = welded ? std::max(config.interior.radius - config.interior.spring_distance, r_c)
                            : config.interior.radius;
  double sum_length2 = 0;
  for (const auto& [i, j] : interior_springs) {
    const Vec3& a = interior_nodes[static_cast<std::size_t>(i)];
    const Vec3& b = interior_nodes[static_cast<std::size_t>(j)];
    const double r_mid = (0.5 * (a + b)).norm();
    if (welded && r_mid >= r_i) continue;
    if (!(r_mid < r_c)) sum_length2 += (a - b).squaredNorm();
  }
  const double mantle_volume = 4.0 / 3.0 * std::numbers::pi * (r_i * r_i * r_i - r_c * r_c * r_c);
  if (!(sum_length2 > 0))
    throw InputError("[material]: the interior network has no springs; raise resolution.interior_count");
  k.interior = spring_constant_for_modulus(*config.material.youngs_modulus, mantle_volume, sum_length2);
  if (!shell.empty()) {
    const double per_shell_node = config.resolution.cross_per_shell_node.value_or(2.33);
    k.cross_distance = cross_distance_for(interior_nodes, shell, per_shell_node);
    if (!welded && !(k.cross_distance > 0))  // a welded body's shell is held by its welded springs
      throw InputError(fmt::format("resolution.cross_per_shell_node = {} gives no cross spring to the {} shell nodes",
                                   per_shell_node, shell.size()));
    k.bending = hinge_constant_for_rigidity(material_flexural_rigidity(config.material));
  }
  return k;
}

double material_cross_constant(const Config& config, const std::vector<Vec3>& interior_nodes,
                               const std::vector<Vec3>& shell,
                               const std::vector<std::array<std::int32_t, 2>>& cross, double shell_mass) {
  TIDALCRUST_ASSERT(!cross.empty(), "material_cross_constant needs the built cross springs");
  double lengths = 0;
  for (const auto& [i, s] : cross)
    lengths += (interior_nodes[static_cast<std::size_t>(i)] - shell[static_cast<std::size_t>(s)]).norm();
  const double count = static_cast<double>(cross.size());
  const double speed =
      config.material.coupling_speed_ratio.value_or(1.0) * p_wave_speed(*config.material.youngs_modulus);
  return cross_constant_for_speed(speed, lengths / count, shell_mass, count);
}

}  // namespace tidalcrust
