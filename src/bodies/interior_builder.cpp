#include "bodies/interior_builder.hpp"

#include "bodies/neighbor_grid.hpp"
#include "base/random.hpp"

namespace tidalcrust {

InteriorNetwork build_interior(const InteriorConfig& interior, std::uint64_t seed) {
  const double r = interior.radius;
  const Vec3 lo(-r, -r, -r), hi(r, r, r);
  Random random(seed);
  InteriorNetwork network;

  NeighborGrid accepted(lo, hi, interior.min_separation);
  const auto target = static_cast<std::size_t>(interior.count);
  while (network.nodes.size() < target && network.trials < interior.max_trials) {
    // Three draws per cube point, x then y then z, so the sequence is fixed by the seed.
    const double x = random.uniform(-r, r);
    const double y = random.uniform(-r, r);
    const double z = random.uniform(-r, r);
    const Vec3 candidate(x, y, z);
    if (candidate.squaredNorm() > r * r) continue;
    ++network.trials;
    if (accepted.any_closer_than(candidate, interior.min_separation)) continue;
    accepted.insert(candidate);
    network.nodes.push_back(candidate);
  }

  NeighborGrid all(lo, hi, interior.spring_distance);
  for (const auto& p : network.nodes) all.insert(p);
  for (std::size_t i = 0; i < network.nodes.size(); ++i) {
    const auto id = static_cast<std::int32_t>(i);
    for (std::int32_t j : all.closer_than(network.nodes[i], interior.spring_distance))
      if (j > id) network.springs.push_back({id, j});
  }
  return network;
}

}  // namespace tidalcrust
