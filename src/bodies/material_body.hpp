#pragma once
// What a body described by its material (issue 12, [material] in a workflow) needs from its
// built geometry: the cross-spring distance d_C that gives a number of cross springs per shell
// node, and the spring constants that meet the material's targets exactly on this network
// (docs/material.md). Units: G = M = R = 1.
#include <array>
#include <cstdint>
#include <vector>

#include "base/vec3.hpp"
#include "bodies/body_type.hpp"
#include "model/config.hpp"
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

/// The constants a body is built with (G = M = R = 1).
struct SpringConstants {
  double interior = 0;        ///< k_I of a mantle spring, G M^2/R^3
  double shell = 0;           ///< k_S
  double bending = 0;         ///< k_e, G M^2/R^2
  double cross = 0;           ///< k_C (a [material] body's comes from material_cross_constant)
  double cross_distance = 0;  ///< d_C, R
};

/// The constants as the configuration prints them (interior, shell, cross spring constants,
/// shell.bending_constant, cross.distance).
SpringConstants printed_spring_constants(const Config& config);

/// The constants of a [material] body on its built network (docs/material.md): k_I that makes
/// eq. 15 exact over the mantle's springs (midpoints between body.mantle_inner_radius and the
/// interior radius; a welded body restores the springs the network lacks near its surface, so
/// only those deeper than d_I count, inside r_I - d_I), and with a shell d_C for
/// resolution.cross_per_shell_node cross springs per shell node and k_e for the crust's flexural
/// rigidity. k_S and k_C as printed (k_C: see material_cross_constant). interior.nodes [N_I],
/// springs as built; shell [N_S] or empty. Throws InputError when the network has no spring.
SpringConstants material_spring_constants(const Config& config, const BodyType& body,
                                          const std::vector<Vec3>& interior_nodes,
                                          const std::vector<std::array<std::int32_t, 2>>& interior_springs,
                                          const std::vector<Vec3>& shell, bool welded);

/// k_C that makes eq. 25 exact on the built cross springs: V_Co = material.coupling_speed_ratio
/// V_IP (eq. 16) over their mean length. cross: (interior index, shell index) pairs, not empty.
double material_cross_constant(const Config& config, const std::vector<Vec3>& interior_nodes,
                               const std::vector<Vec3>& shell,
                               const std::vector<std::array<std::int32_t, 2>>& cross, double shell_mass);

}  // namespace tidalcrust
