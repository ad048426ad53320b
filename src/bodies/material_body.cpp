#include "bodies/material_body.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

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

}  // namespace tidalcrust
