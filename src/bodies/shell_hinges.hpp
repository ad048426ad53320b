#pragma once
// One bending hinge per edge of a closed triangulated surface (Bridson et al. 2003).
#include <array>
#include <cstdint>
#include <vector>

namespace tidalcrust {

/// For each edge {i, j} (in the given order) the hinge {wing_1, wing_2, edge_a = i, edge_b = j}
/// where (wing_1, i, j) and (wing_2, j, i) are the two faces next to the edge, both
/// counter-clockwise like `faces` (Body::hinges convention). InternalError (TIDALCRUST_ASSERT) if
/// an edge does not have exactly one face on each side (open or non-manifold surface).
std::vector<std::array<std::int32_t, 4>> make_hinges(const std::vector<std::array<std::int32_t, 2>>& edges,
                                                      const std::vector<std::array<std::int32_t, 3>>& faces);

}  // namespace tidalcrust
