#pragma once
// A liquid layer as a spring network whose energy depends on volume alone (docs/ocean.md). Each
// liquid particle a has the volumetric strain of its springs,
//   theta_a = (3 / n_a) sum_{s at a} eps_s,   eps_s = L_s / L0_s - 1,
// (for an affine strain e of an isotropic neighbourhood theta = tr e: a uniform compression gives
// -dV/V, a shear 0), and the energy E = sum_a (K V_a / 2) theta_a^2 with K the bulk modulus and V_a
// the particle's share of the layer's volume. A deformation that keeps every theta_a costs nothing:
// N constraints on 3N coordinates leave 2N directions free, so after the particles move the layer
// carries no static shear, and its connectivity is fixed, so the liquid cannot leak through the
// crust or into the solid network below (a particle liquid with density sums does: docs/ocean.md).
// The springs of the layer (SpringKind::liquid) have stiffness 0 in the spring law; it damps them
// as every spring (eq. 14), and this class adds the volumetric force.
// Units: G = M = R = 1. Lengths R, K e_g = G M^2/R^4, V R^3, forces G M^2/R^2, energies G M^2/R.
//
// Determinism: the strains are computed per spring, theta per liquid particle by gathering its
// springs in index order, the force per spring, and each particle gathers its springs' forces in
// index order: bitwise the same for any thread count.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "model/body.hpp"
#include "model/state.hpp"

namespace tidalcrust {

/// The liquid layer's forces and energy for a Body with Body::liquid present. Keeps a reference to
/// the body, which must outlive it.
class LiquidPressure {
 public:
  explicit LiquidPressure(const Body& body);

  /// theta [N] of every liquid particle at positions [N*3] (R) with the rest lengths of `springs`;
  /// 0 for the other particles.
  std::vector<double> volumetric_strain(const double* position, const SpringState& springs) const;

  /// Forces [N*3] (G M^2/R^2) of the volumetric energy at positions [N*3] (R), into forces() (0
  /// for a particle without liquid springs).
  void compute(const double* position, const SpringState& springs, bool parallel);
  const std::vector<double>& forces() const { return force_; }

  /// sum_a (K V_a / 2) theta_a^2 (G M^2/R), in index order.
  double energy(const double* position, const SpringState& springs) const;

  /// Pressure -K theta_a of each liquid particle (e_g), 0 for the others.
  std::vector<double> pressure(const double* position, const SpringState& springs) const;

 private:
  /// eps_s of every liquid spring (indexed like liquid_springs_) and their lengths.
  void spring_strains(const double* position, const SpringState& springs, bool parallel) const;
  /// theta_a from the strains of spring_strains().
  double theta_of(std::size_t a) const;

  const Body& body_;
  std::vector<std::int32_t> liquid_springs_;  ///< indices of SpringKind::liquid springs, increasing
  std::vector<std::int32_t> liquid_;          ///< liquid particles, increasing
  // For each particle p, entries [offset[p], offset[p+1]) of `incident_`: 2k (p is spring
  // liquid_springs_[k]'s first end) or 2k+1 (its second end), in increasing k.
  std::vector<std::int32_t> offset_, incident_;
  std::vector<double> force_;               ///< [N*3]
  mutable std::vector<double> strain_;      ///< [liquid springs] eps_s
  mutable std::vector<double> length_;      ///< [liquid springs] L_s
  std::vector<double> factor_;              ///< [N] dE/dtheta_a * 3/n_a = K V_a theta_a 3/n_a (compute)
  std::vector<double> coefficient_;         ///< [liquid springs] force over d, G M^2/R^3 (compute)
};

}  // namespace tidalcrust
