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
// Damping: each spring's Kelvin-Voigt term (paper eq. 14) damps the relative motion of its ends
// along it at the rate gamma, i.e. adds the block gamma mu n n^T (mu the reduced mass) to a damping
// matrix C built like K. For one mode x'' = -omega^2 x - c x', this drift-kick-drift (kick with
// the start-of-step velocity) is stable iff omega^2 dt^2 + 2 c dt <= 4 (amplification matrix;
// docs/material.md), so with Gershgorin bounds lambda_K and lambda_C on B and on
// M^{-1/2} C M^{-1/2}: safe dt = (sqrt(lambda_C^2 + 4 lambda_K) - lambda_C) / lambda_K. At
// gamma = 50 and a spring-limited step this is several times below the undamped bound (a
// material-L4 relax at 0.8 x the undamped bound blew up at step 12).
// Left out: self-gravity (G m / r^3, orders of magnitude below the springs), tension's
// geometric stiffness (T/L, strains ~1e-3).
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
  double safe_dt = 0;      ///< Gershgorin bound with damping (2 / sqrt(lambda_K) without): stable below it, t_grav
  double undamped_safe_dt = 0;  ///< 2 / sqrt(lambda_K): the same bound without damping, t_grav
  double damping = 0;      ///< the spring damping rate gamma it was computed for, 1/t_grav
  double damping_rate = 0; ///< lambda_C, the Gershgorin bound of M^{-1/2} C M^{-1/2}, 1/t_grav
  double unstable_dt = 0;  ///< 2 / sqrt(largest one-node Rayleigh quotient): unstable above it, t_grav
  LimitingNode safe_limit;      ///< the node of the Gershgorin maximum
  LimitingNode unstable_limit;  ///< the node of the largest one-node quotient
};

/// Both bounds at the state's positions and stiffnesses (failed springs with their reduced k),
/// the safe one for springs damped at the rate `damping` (gamma, 1/t_grav, >= 0; the unstable
/// one is undamped: damping only shrinks the stable region). 0 for a body without springs or
/// hinges.
StabilityBound stability_bound(const Body& body, const State& state, double damping = 0.0);

/// The time step chosen when a workflow gives none: this fraction of the safe bound (room for
/// the hinges' stiffening under strain; docs/material.md).
inline constexpr double chosen_dt_fraction = 0.8;

}  // namespace tidalcrust
