#include "bodies/welded_coupling.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "base/sphere_crossings.hpp"
#include "bodies/neighbor_grid.hpp"

namespace tidalcrust {

InteriorNetwork welded_interior(const InteriorConfig& interior, std::uint64_t seed) {
  InteriorConfig larger = interior;
  larger.radius = interior.radius + interior.min_separation;
  const double scale = std::pow(larger.radius / interior.radius, 3);
  larger.count = std::llround(static_cast<double>(interior.count) * scale);
  larger.max_trials = static_cast<std::int64_t>(std::ceil(static_cast<double>(interior.max_trials) * scale));
  const InteriorNetwork all = build_interior(larger, seed);
  InteriorNetwork kept;
  kept.trials = all.trials;
  std::vector<std::int32_t> index(all.nodes.size(), -1);
  for (std::size_t i = 0; i < all.nodes.size(); ++i)
    if (all.nodes[i].norm() < interior.radius) {
      index[i] = static_cast<std::int32_t>(kept.nodes.size());
      kept.nodes.push_back(all.nodes[i]);
    }
  for (const auto& [i, j] : all.springs) {
    const std::int32_t a = index[static_cast<std::size_t>(i)], b = index[static_cast<std::size_t>(j)];
    if (a >= 0 && b >= 0) kept.springs.push_back({a, b});
  }
  return kept;
}

double missing_spring_weight(const WeldedInterior& interior, const Vec3& node, const Vec3& direction) {
  const std::vector<double> exits = sphere_crossings(node, direction, interior.radius);
  const double l_min = exits.empty() ? 0.0 : exits.back();
  const double reach = interior.spring_distance;
  if (!(l_min < reach)) return 0.0;
  const double reach2 = reach * reach, l_min2 = l_min * l_min;
  return interior.pair_factor * interior.node_density * interior.spring_constant * (reach2 * reach2 - l_min2 * l_min2) /
         4;
}

double interior_pair_factor(const std::vector<Vec3>& nodes, const std::vector<std::array<std::int32_t, 2>>& springs,
                            double radius, double spring_distance) {
  std::vector<double> sum(nodes.size(), 0.0);
  for (const auto& [i, j] : springs) {
    const double l2 = (nodes[static_cast<std::size_t>(i)] - nodes[static_cast<std::size_t>(j)]).squaredNorm();
    sum[static_cast<std::size_t>(i)] += l2;
    sum[static_cast<std::size_t>(j)] += l2;
  }
  double total = 0;
  std::int64_t complete = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].norm() + spring_distance < radius) total += sum[i], ++complete;
  if (complete == 0) return 1.0;
  const double density = static_cast<double>(nodes.size()) / (4.0 / 3.0 * std::numbers::pi * radius * radius * radius);
  const double ideal = 4 * std::numbers::pi * density * std::pow(spring_distance, 5) / 5;
  return total / static_cast<double>(complete) / ideal;
}

int welded_ray_count(double spring_distance, std::size_t shell_nodes) {
  return std::max(1000, static_cast<int>(std::ceil(16 * spring_distance * spring_distance *
                                                   static_cast<double>(shell_nodes))));
}

std::vector<WeldedSpring> welded_springs(const WeldedInterior& interior, const std::vector<Vec3>& interior_nodes,
                                         const std::vector<Vec3>& shell_nodes) {
  std::vector<WeldedSpring> out;
  if (shell_nodes.empty() || interior_nodes.empty()) return out;
  double shell_radius = 0;
  for (const Vec3& p : shell_nodes) shell_radius += p.norm();
  shell_radius /= static_cast<double>(shell_nodes.size());
  // Nearest shell node to a point on the shell: a grid of cells about twice the mean spacing.
  const double spacing = std::sqrt(4 * std::numbers::pi * shell_radius * shell_radius / static_cast<double>(shell_nodes.size()));
  NeighborGrid grid(Vec3(-1, -1, -1) * shell_radius, Vec3(1, 1, 1) * shell_radius, 2 * spacing);
  for (const Vec3& p : shell_nodes) grid.insert(p);
  const auto nearest_shell_node = [&](const Vec3& p) {
    for (double r = 2 * spacing;; r *= 2) {
      std::int32_t best = -1;
      double best_d2 = 0;
      for (std::int32_t s : grid.closer_than(p, r)) {
        const double d2 = (shell_nodes[static_cast<std::size_t>(s)] - p).squaredNorm();
        if (best < 0 || d2 < best_d2) best = s, best_d2 = d2;  // ids ascend: ties go to the lower
      }
      if (best >= 0) return best;
    }
  };
  // Directions: a Fibonacci lattice on the unit sphere (equal solid angles 4 pi / M).
  const int rays = welded_ray_count(interior.spring_distance, shell_nodes.size());
  const double golden_angle = std::numbers::pi * (3 - std::sqrt(5.0));
  std::vector<Vec3> directions(static_cast<std::size_t>(rays));
  for (int k = 0; k < rays; ++k) {
    const double z = 1 - (2 * k + 1.0) / rays, rho = std::sqrt(std::max(0.0, 1 - z * z));
    directions[static_cast<std::size_t>(k)] = Vec3(rho * std::cos(golden_angle * k), rho * std::sin(golden_angle * k), z);
  }
  const double solid_angle = 4 * std::numbers::pi / rays;
  std::vector<double> weight(shell_nodes.size(), 0.0);
  std::vector<std::int32_t> touched;
  for (std::size_t i = 0; i < interior_nodes.size(); ++i) {
    const Vec3& x = interior_nodes[i];
    if (x.norm() + interior.spring_distance <= interior.radius) continue;  // no spring of it is missing
    for (const Vec3& d : directions) {
      const double w = missing_spring_weight(interior, x, d);
      if (w == 0.0) continue;
      const std::vector<double> hits = sphere_crossings(x, d, shell_radius);
      if (hits.empty()) continue;
      const std::int32_t s = nearest_shell_node(x + hits.back() * d);
      if (weight[static_cast<std::size_t>(s)] == 0.0) touched.push_back(s);
      weight[static_cast<std::size_t>(s)] += w * solid_angle;
    }
    std::sort(touched.begin(), touched.end());
    for (std::int32_t s : touched) {
      const double length = (shell_nodes[static_cast<std::size_t>(s)] - x).norm();
      out.push_back({static_cast<std::int32_t>(i), s, weight[static_cast<std::size_t>(s)] / length});
      weight[static_cast<std::size_t>(s)] = 0.0;
    }
    touched.clear();
  }
  return out;
}

}  // namespace tidalcrust
