#pragma once
// Extra cross springs for a crust that can carry no load (relax.crust_support = "balanced",
// docs/crust-support.md). With the paper's rule (every shell-interior pair closer than d_C) some
// shell nodes get no cross spring and many get one or two, so only the crust can hold them in
// place. Here every shell node gets at least `minimum` cross springs, to its nearest interior
// nodes; from three on, the spring directions must span space (every direction can be balanced).
#include <array>
#include <cstdint>
#include <vector>

#include "base/vec3.hpp"

namespace tidalcrust {

/// Smallest eigenvalue of sum_n u_n u_n^T over the unit vectors u_n (the directions of a node's
/// springs): 0 when they lie in a plane, 1 for three orthogonal ones. How well the springs can
/// push the node in its worst direction.
double weakest_direction_support(const std::vector<Vec3>& directions);

/// The smallest support weakest_direction_support() a node with >= 3 springs must reach.
inline constexpr double min_direction_support = 0.05;

/// Cross springs to add so that every shell node has at least `minimum` (0 to 12) of them.
/// interior [N_I] and shell [N_S] positions (R); existing: (interior index, shell index) of the
/// cross springs already built. For each shell node in index order the nearest interior nodes
/// (distance, then index) that are not yet joined to it are added until it has `minimum`
/// springs and, if minimum >= 3, their directions reach min_direction_support; at most 12 per
/// node. Returns the added (interior index, shell index) pairs in that order. Deterministic.
/// The nearest nodes come from a NeighborGrid in rings of doubling radius, each sorted by
/// (squared distance, index): the same order as sorting all N_I nodes, at a cost that grows
/// with how far a node must look, not with N_I (a level-6 body builds in under a second).
std::vector<std::array<std::int32_t, 2>> supplementary_cross_springs(
    const std::vector<Vec3>& interior, const std::vector<Vec3>& shell,
    const std::vector<std::array<std::int32_t, 2>>& existing, int minimum);

/// The cross springs of the paper (section 2.5): every (interior, shell) pair closer than
/// `distance` (R), in interior-index order and for each in the grid's order, then the
/// supplementary springs of supplementary_cross_springs(..., minimum). Returns (interior index,
/// shell index) pairs; empty when no interior node lies that close to the shell.
std::vector<std::array<std::int32_t, 2>> cross_springs_within(const std::vector<Vec3>& interior,
                                                              const std::vector<Vec3>& shell, double distance,
                                                              int minimum);

}  // namespace tidalcrust
