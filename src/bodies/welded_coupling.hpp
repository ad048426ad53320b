#pragma once
// The welded crust (cross.coupling = "welded", docs/crust-support.md, "The welded coupling"):
// shell nodes joined into the interior network so that the layer under the crust has the
// interior's elastic moduli. An interior node near the surface of the ball it fills lacks the
// springs it would have to nodes beyond that surface (an interior continuing to the crust);
// every ray leaving the node through the surface carries those missing springs, and the welded
// spring to the shell node the ray reaches replaces them with their summed weight k L. Springs
// that cross a depth transmit k L (n . eps . n) n across it, so the traction the layer carries per
// strain, sum k L n n n per area (the crossing form of eq. 15), is then the interior's at every
// depth below the surface: in compression, in shear and in-plane. Units R, G M^2/R^3.
#include <array>
#include <cstdint>
#include <vector>

#include "base/vec3.hpp"
#include "bodies/interior_builder.hpp"

namespace tidalcrust {

/// The interior the welded springs continue.
struct WeldedInterior {
  double radius = 0;           ///< r_I, the sphere the interior nodes fill (R)
  double spring_distance = 0;  ///< d_I, the interior's longest spring (R)
  double spring_constant = 0;  ///< k_I of the springs near the surface (the mantle's), G M^2/R^3
  double node_density = 0;     ///< n, interior nodes per volume: N_I / ((4/3) pi r_I^3), R^-3
  /// The network's pairs against uncorrelated nodes at density n (interior_pair_factor): the
  /// missing springs are counted as the network has them, not as an ideal gas would.
  double pair_factor = 1;
};

/// sum_j L_ij^2 over the springs of the interior nodes whose whole d_I neighbourhood lies inside
/// r_I (|x_i| + d_I < r_I), averaged, over its value 4 pi n d_I^5 / 5 for nodes placed without
/// correlation at density n = N_I / ((4/3) pi r_I^3) (each pair within d_I joined). Below 1 when
/// the random sequential addition packs the nodes more evenly (measured 0.85 on welded-L4), or
/// when fewer nodes than asked fill the ball. 1 when no node's neighbourhood is complete.
double interior_pair_factor(const std::vector<Vec3>& nodes, const std::vector<std::array<std::int32_t, 2>>& springs,
                            double radius, double spring_distance);

struct WeldedSpring {
  std::int32_t interior = 0;  ///< index into the interior nodes
  std::int32_t shell = 0;     ///< index into the shell nodes
  double stiffness = 0;       ///< G M^2/R^3
};

/// The interior of a welded body: a random network cut out of a larger ball. Random sequential
/// addition piles nodes up against the wall of the ball it fills (measured on welded-L4: 1.9 times
/// the mean density within 0.025 R of the wall, 0.9 times it deeper), which no continuum has; so
/// the nodes are placed in the ball of radius r_I + d_IS at the same packing (count scaled by the
/// volume) and those outside r_I dropped with their springs. The kept nodes keep their order.
InteriorNetwork welded_interior(const InteriorConfig& interior, std::uint64_t seed);

/// The summed weight k L of the springs an interior node at `node` (|node| < r_I) lacks along
/// `direction` (a unit vector), per solid angle: an interior continuing past r_I would have nodes
/// at density n_I along the ray from where it leaves the sphere r_I (L_min) out to d_I, each with a
/// spring k_I of length L, so sum k L = n_I k_I integral_{L_min}^{d_I} L^3 dL
/// = n_I k_I (d_I^4 - L_min^4) / 4 (0 when L_min >= d_I), times interior.pair_factor,
/// G M^2/R^2 per steradian.
double missing_spring_weight(const WeldedInterior& interior, const Vec3& node, const Vec3& direction);

/// Directions the welded builder casts from every interior node: max(1000, 16 d_I^2 N_S) on the
/// sphere, so that the farthest shell node a spring reaches (at d_I, solid angle 4 pi / (N_S d_I^2))
/// gets about 4 of them.
int welded_ray_count(double spring_distance, std::size_t shell_nodes);

/// The welded springs. For every interior node within d_I of the surface r_I, rays in
/// welded_ray_count directions (a Fibonacci lattice, equal solid angles): each ray carries the
/// missing_spring_weight of its direction to the shell node nearest to where it meets the shell
/// sphere (the mean radius of the shell nodes), and that node's one spring of length l to the
/// interior node gets k = (sum of the weights it received) / l, so that sum k L over the node's
/// welded springs equals that over the springs it lacks, direction by direction to the shell's
/// resolution. A node right under a shell node thus gets a short, stiff spring (k L fixed). In
/// interior index order and, for each interior node, shell index order. Deterministic.
std::vector<WeldedSpring> welded_springs(const WeldedInterior& interior, const std::vector<Vec3>& interior_nodes,
                                         const std::vector<Vec3>& shell_nodes);

}  // namespace tidalcrust
