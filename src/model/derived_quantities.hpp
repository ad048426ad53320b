#pragma once
// Table 3 quantities computed from a stored body with the paper's equations 15-25.
#include <vector>

#include "model/body.hpp"
#include "model/state.hpp"

namespace tidalcrust {

struct DerivedQuantities {
  double E_I = 0;   ///< interior Young's modulus, eq. 15: (1/6V) sum k L^2 over interior springs, e_g
  double L_I = 0;   ///< mean interior rest length, R
  double k_I = 0;   ///< mean interior spring constant, G M^2/R^3
  double L_S = 0;   ///< mean shell rest length, R
  double k_S = 0;   ///< mean shell spring constant
  double M_S = 0;   ///< shell mass, M
  double L_C = 0;   ///< mean cross rest length, R
  double k_C = 0;   ///< mean cross spring constant
  double V_IP = 0;  ///< interior P-wave speed, eq. 16, sqrt(GM/R)
  double V_SP = 0;  ///< shell P-wave speed, eq. 19: sqrt(k_S 4 pi R^2 / M_S)
  double V_Co = 0;  ///< shell-interior coupling speed, eq. 25: sqrt(k_C N_C / M_S) L_C
  double h_S = 0;   ///< crust thickness from E_2D = (2/sqrt 3) k_S = E_S h_S with E_S = E_I, R
  double E_2D = 0;  ///< crust 2D Young's modulus, eq. 20: (2/sqrt 3) k_S, e_g R
  double D_F = 0;   ///< crust flexural rigidity of the hinge lattice: k_e / 4 (mean hinge k_e), e_g R^3
  double D_F_eq23 = 0;  ///< what paper eq. 23 gives, k_e L_S / 2 (not the lattice's bending: D_F), e_g R^3
  double dt_max = 0;  ///< stability bound, eq. 13: min over springs sqrt(mu / (k b)), t_grav
};

/// Flexural rigidity of a flat equilateral triangular lattice with one Bridson hinge of stiffness
/// k_e per edge (hinge_force.hpp), for small bending. Each hinge stores k_e C theta^2 / 4 with
/// C = L^2/(|N1| + |N2|) = 1/sqrt(3). Its faces are the linear interpolants of the deflection
/// w = x.K.x/2, so the dihedral angle is theta = (L/sqrt(3)) (3/2 K_mm - 1/2 K_tt), K_mm the
/// curvature across the edge and K_tt along it (the wings lie (sqrt(3)/2) L from the edge, whose
/// chord sits L^2 K_tt / 8 above the surface). For a cylindrical bend of curvature kappa in any
/// direction the three edge directions of a node give sum theta^2 = (3/4) kappa^2 L^2, i.e. the
/// energy density k_e kappa^2 / 8 over the node area (sqrt(3)/2) L^2. With D kappa^2 / 2:
/// D = k_e / 4, isotropic and independent of the spacing L (G M^2/R for k_e in G M^2/R^2, R = 1).
/// Paper eq. 23 writes D_F = k_e L_S / 2, which is 2 L_S times this; `validate` measures k_e / 4 on a
/// loaded lattice (docs/validation.md, flexure).
inline double hinge_lattice_flexural_rigidity(double hinge_stiffness) { return hinge_stiffness / 4; }

/// Young's modulus of a spring network, eq. 15: E = (1/6V) sum k L^2, for the sum of k L^2 over
/// its springs (G M^2/R) and the volume V they fill (R^3); e_g. The one home of eq. 15.
inline double network_youngs_modulus(double stiffness_length2, double volume) {
  return stiffness_length2 / (6.0 * volume);
}

/// Eq. 15 solved for a common spring constant: k = 6 V E / sum L^2 (G M^2/R^3) gives a network
/// of springs with the squared rest lengths summing to sum_length2 (R^2), filling the volume V
/// (R^3), the Young's modulus E (e_g).
inline double spring_constant_for_modulus(double youngs_modulus, double volume, double sum_length2) {
  return 6.0 * volume * youngs_modulus / sum_length2;
}

/// P-wave speed of eq. 16 for a Young's modulus E (e_g) at the mean density 3/(4 pi) and Poisson
/// ratio 1/4, in sqrt(GM/R).
double p_wave_speed(double youngs_modulus);

/// Eq. 15 over the interior springs whose midpoints lie within `radius` (R) of the centre of mass
/// (rest lengths and stiffnesses of `state`), over that ball's volume, e_g. A welded body's
/// modulus is this over the springs deeper than d_I (radius r_I - d_I): its welded springs restore
/// what the network lacks near its surface (docs/crust-support.md, "The welded coupling").
double inner_network_youngs_modulus(const Body& body, const State& state, double radius);

/// Eq. 15 per spherical shell about the centre of mass: element b is over the interior springs whose
/// midpoints lie in [outer_radii[b-1], outer_radii[b]) (from 0 for b = 0), over that shell's volume,
/// e_g. `outer_radii` must increase (R). The layered form of inner_network_youngs_modulus.
std::vector<double> interior_modulus_profile(const Body& body, const State& state,
                                             const std::vector<double>& outer_radii);

/// `interior_radius` is r_I (the volume V of eq. 15 is that of the sphere of radius r_I).
DerivedQuantities derive_quantities(const Body& body, const State& state, double interior_radius);

}  // namespace tidalcrust
