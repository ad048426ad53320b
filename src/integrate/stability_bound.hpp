#pragma once
// The leapfrog stability bound of a body with springs AND hinges and unequal node masses (issue
// 12; eq. 13 of the paper generalised). Derivation (docs/material.md#the-time-step):
// linearised about the current positions, the undamped equations are m x'' = -K x with K the
// stiffness matrix (3N x 3N) of the springs (block k n n^T for each spring end pair) and hinges
// (the Hessian of E_h = k_e C (theta - theta_rest)^2 / 4: (k_e C / 2) u_a u_b^T for the hinge's
// vertices a, b with u the gradients of theta of hinge_force.hpp). Leapfrog (drift-kick-drift)
// is stable for omega dt < 2 on every mode, omega^2 the eigenvalues of B = M^{-1/2} K M^{-1/2}.
//  - safe:     block Gershgorin, lambda_max(B) <= max_i sum_j ||K_ij|| / sqrt(m_i m_j) (the
//              3x3 block norms bounded by the sum of the element terms). Every dt < 2/sqrt of
//              it is stable. Exact for two equal masses on one spring (2 k/m).
//  - unstable: a Rayleigh quotient of B on one node, lambda_max(B) >= lambda_max(K_ii) / m_i:
//              every dt > 2/sqrt(max_i lambda_max(K_ii)/m_i) is certainly unstable.
// Left out: self-gravity (G m / r^3, orders of magnitude below the springs), tension's
// geometric stiffness (T/L, strains ~1e-3), damping (gamma dt << 1 at the paper's values).
// Units: t_grav.
#include <cstddef>
#include <string>

#include "model/body.hpp"
#include "model/state.hpp"

namespace tidalcrust {

/// What bounds the step at one node: its index and how its stiffness/mass divides into kinds.
struct LimitingNode {
  std::size_t node = 0;
  double omega2 = 0;     ///< the bound's omega^2 at this node, 1/t_grav^2
  double springs = 0;    ///< fraction of omega2 from interior and shell springs
  double cross = 0;      ///< fraction from cross springs
  double hinges = 0;     ///< fraction from hinges
  /// "shell node 812 (r = 1.000 R; 71% hinges, 25% springs, 4% cross springs)".
  std::string describe(const Body& body, const State& state) const;
};

struct StabilityBound {
  double safe_dt = 0;      ///< 2 / sqrt(Gershgorin bound): leapfrog is stable below it, t_grav
  double unstable_dt = 0;  ///< 2 / sqrt(largest one-node Rayleigh quotient): unstable above it, t_grav
  LimitingNode safe_limit;      ///< the node of the Gershgorin maximum
  LimitingNode unstable_limit;  ///< the node of the largest one-node quotient
};

/// Both bounds at the state's positions and stiffnesses (failed springs with their reduced k).
/// 0 for a body without springs or hinges.
StabilityBound stability_bound(const Body& body, const State& state);

/// The time step chosen when a workflow gives none: this fraction of the safe bound (room for
/// the hinges' stiffening under strain and for damping; docs/material.md).
inline constexpr double chosen_dt_fraction = 0.8;

}  // namespace tidalcrust
