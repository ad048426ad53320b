#pragma once
// The static elastic moduli of a spring network, measured rather than taken from eq. 15
// (docs/validation.md, "The network's own moduli"). Eq. 15, E_I = (1/6V) sum k L^2 with Poisson
// ratio 1/4, is the AFFINE estimate: every spring follows the homogeneous strain. In a random
// network the nodes can lower the energy by moving off the affine positions (non-affine
// relaxation), so its true moduli lie below eq. 15's (the affine value is an upper, Voigt-type,
// bound for a network without pre-stress). This measures them:
//
//  1. a homogeneous strain eps (six Voigt components in turn, +-h each) is applied about `center`;
//     the nodes beyond `hold_radius` are held at the affine positions x0 + eps (x0 - center);
//  2. the nodes inside relax to static equilibrium of the springs alone (no gravity, no damping:
//     the linearised problem K_ff u_f = -K_fh u_h, solved exactly by a sparse LDL^T; each spring's
//     stiffness is k n n^T + (T/l)(I - n n^T) with its tension T at x0, so the relaxed state's
//     pre-stress enters as geometric stiffness; the forces that held x0 in equilibrium, gravity in
//     the body, are taken as a fixed load);
//  3. the stress is the virial sigma = (1/V) sum_s w_s T_s r_s (x) r_s / l_s over the springs,
//     w_s the fraction of spring s inside the sphere of `measure_radius`, V its volume (tension
//     positive); (sigma(+h) - sigma(-h)) / (2h) is one column of the 6x6 stiffness C.
//
// The same is done with the affine positions everywhere (no relaxation): the affine C, whose
// isotropic (Voigt) average without pre-stress is exactly eq. 15's E with nu = 1/4. The isotropic
// moduli of a measured C are its Voigt averages (Hill 1952):
//   K = (C11 + C22 + C33 + 2 (C12 + C23 + C13)) / 9,
//   G = (C11 + C22 + C33 - (C12 + C23 + C13) + 3 (C44 + C55 + C66)) / 15,
//   E = 9 K G / (3 K + G),  nu = (3 K - 2 G) / (2 (3 K + G)).
// Units G = M = R = 1: lengths R, k in G M^2/R^3, moduli in e_g = G M^2/R^4.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "base/vec3.hpp"

namespace tidalcrust {

/// One linear spring between nodes i and j: rest length (R) and stiffness (G M^2/R^3).
struct NetworkSpring {
  std::int32_t i = 0, j = 0;
  double rest_length = 0;
  double stiffness = 0;
};

/// Isotropic moduli (e_g) of an elastic stiffness tensor, Voigt-averaged.
struct IsotropicModuli {
  double bulk = 0;     ///< K
  double shear = 0;    ///< G (mu)
  double youngs = 0;   ///< E = 9 K G / (3 K + G)
  double poisson = 0;  ///< nu = (3 K - 2 G) / (2 (3 K + G))
};

/// The Voigt isotropic average of a 6x6 stiffness matrix (Voigt order xx, yy, zz, yz, xz, xy;
/// shear columns per engineering shear strain), e_g.
IsotropicModuli voigt_isotropic_moduli(const Eigen::Matrix<double, 6, 6>& stiffness);

/// Isotropic moduli from the bulk and shear moduli (e_g). InputError unless both are > 0.
IsotropicModuli isotropic_moduli_from_bulk_shear(double bulk, double shear);

/// What measure_network_moduli finds. Stiffness matrices in e_g, Voigt order as above.
struct NetworkModuli {
  Eigen::Matrix<double, 6, 6> relaxed = Eigen::Matrix<double, 6, 6>::Zero();  ///< inner nodes relaxed
  Eigen::Matrix<double, 6, 6> affine = Eigen::Matrix<double, 6, 6>::Zero();   ///< every node affine
  IsotropicModuli relaxed_moduli;  ///< Voigt average of `relaxed`
  IsotropicModuli affine_moduli;   ///< Voigt average of `affine`
  double eq15_youngs = 0;          ///< (1/6V) sum w k l0^2 over the measured region (eq. 15), e_g
  double reference_pressure = 0;   ///< -trace(sigma(x0))/3, the pre-stress in the region, e_g
  int free_nodes = 0;              ///< nodes relaxed (inside hold_radius)
  int held_nodes = 0;              ///< nodes held at the affine positions
  double springs_in_region = 0;    ///< sum of w_s: the springs the virial counts
};

/// Measures the static moduli of the network (positions x0, R; springs) as described at the top
/// of this file: nodes with |x0 - center| > hold_radius are held, the others relax; the virial
/// is taken over the sphere of measure_radius about center; h is the strain amplitude (linear
/// response: the result does not depend on it beyond rounding, since +-h cancels the second
/// order). `with_prestress = false` measures the same geometry with every spring's rest length
/// set to its length at x0 (no tension, no geometric stiffness): the pre-stress's share.
/// InputError when no node is free or held, or the free nodes are not held in place by the
/// springs (a singular stiffness matrix): a body too small or loose for the measurement.
/// Internal error (TIDALCRUST_ASSERT) when a radius is not positive, measure_radius >
/// hold_radius or a spring index is out of range: the caller's arguments.
NetworkModuli measure_network_moduli(const std::vector<Vec3>& positions, const std::vector<NetworkSpring>& springs,
                                     const Vec3& center, double hold_radius, double measure_radius,
                                     double strain = 1e-6, bool with_prestress = true);

}  // namespace tidalcrust
