#pragma once
// The crust lattice (paper section 2.4): an icosahedron whose faces are split into four,
// L times, with every new vertex projected onto the unit sphere.
#include <array>
#include <cstdint>
#include <vector>

#include "base/vec3.hpp"

namespace tidalcrust {

struct Icosphere {
  std::vector<Vec3> nodes;                           ///< 10*4^L+2 points on the unit sphere
  std::vector<std::array<std::int32_t, 2>> edges;    ///< 30*4^L unique edges, i < j, sorted
  std::vector<std::array<std::int32_t, 3>> faces;    ///< 20*4^L triangles, CCW seen from outside
};

/// Subdivision level `level` >= 0 (0 is the icosahedron). Deterministic: the 12 icosahedron
/// vertices come first, then each level's midpoints in order of first use while walking the
/// faces; face k of level L-1 becomes faces 4k..4k+3 of level L.
Icosphere make_icosphere(int level);

}  // namespace tidalcrust
