#pragma once
// The random isotropic interior (paper section 2.2, Kot 2015): random sequential addition of
// nodes with a minimum separation, springs between every pair closer than a distance.
#include <array>
#include <cstdint>
#include <vector>

#include "model/config.hpp"
#include "base/vec3.hpp"

namespace tidalcrust {

struct InteriorNetwork {
  std::vector<Vec3> nodes;                          ///< positions in R, in order of acceptance
  std::vector<std::array<std::int32_t, 2>> springs; ///< i < j, sorted lexicographically
  std::int64_t trials = 0;                          ///< candidate points tried (inside the ball)
};

/// Random sequential addition: candidates uniform in the ball of radius interior.radius
/// (rejection from the enclosing cube, draws outside the ball are not counted as trials),
/// accepted only if no accepted node is closer than interior.min_separation. Stops at
/// interior.count nodes or after interior.max_trials trials; falling short is not an error
/// (the caller reports nodes.size() and trials). Then one spring per pair of nodes closer than
/// interior.spring_distance. The same seed gives the same bits.
InteriorNetwork build_interior(const InteriorConfig& interior, std::uint64_t seed);

}  // namespace tidalcrust
