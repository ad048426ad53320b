#pragma once
// What a body described by its material (issue 12, [material] in a workflow) needs from its
// built geometry: the cross-spring distance d_C that gives a number of cross springs per shell
// node, and the spring constants that meet the material's targets exactly on this network
// (docs/material.md). Units: G = M = R = 1.
#include <vector>

#include "base/vec3.hpp"
#include "model/derived_quantities.hpp"

namespace tidalcrust {

/// d_C such that round(per_shell_node * N_S) shell-interior pairs lie closer than it: halfway
/// between that many-th smallest pair distance and the next. interior [N_I], shell [N_S]
/// positions (R); per_shell_node > 0. Deterministic (a sort of distances).
double cross_distance_for(const std::vector<Vec3>& interior, const std::vector<Vec3>& shell, double per_shell_node);

/// Cross-spring constant that makes eq. 25 exact: V_Co = sqrt(k_C N_C / M_S) L_C, so
/// k_C = (V_Co / L_C)^2 M_S / N_C (G M^2/R^3).
inline double cross_constant_for_speed(double coupling_speed, double mean_length, double shell_mass,
                                       double cross_count) {
  const double ratio = coupling_speed / mean_length;
  return ratio * ratio * shell_mass / cross_count;
}

/// Hinge constant whose lattice has the flexural rigidity D_F (e_g R^3): k_e = 4 D_F (G M^2/R^2),
/// the inverse of hinge_lattice_flexural_rigidity, the same at every shell level. Not eq. 23's
/// k_e = 2 D_F / L_S, which gives a lattice 1 / (2 L_S) times too stiff in bending (6.6x at
/// level 4, doubling per level; measured by `validate`, docs/validation.md).
inline double hinge_constant_for_rigidity(double flexural_rigidity) { return 4.0 * flexural_rigidity; }

}  // namespace tidalcrust
