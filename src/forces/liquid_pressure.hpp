#pragma once
// A liquid layer whose energy depends on volume alone (docs/ocean.md): tetrahedra fill the layer
// between its particles and the solid particles around it (Body::liquid), every corner a of a
// tetrahedron (liquid, crust or floor particle) is a pressure node that owns the volume
//   V_a = sum over its tetrahedra t of V_t / 4,
// and the energy is E = sum_a (K/2) (V_a - V0_a)^2 / V0_a, its pressure P_a = -K (V_a - V0_a)/V0_a.
// This is the average-nodal-pressure tetrahedron (Bonet & Burton 1998): one constraint per node on
// three coordinates, so a deformation that keeps every V_a costs nothing and the layer carries no
// static shear, while any compression, also a non-affine one, changes real volumes. A tetrahedron
// pushes its corners with the mean of their four pressures, the value at its centroid of the linear
// field through them: with the layer's mass lumped onto the corners in the same shares (V_t / 4,
// bodies/ocean_layer.cpp) a hydrostatic pressure balances every node, the crust's included, to
// the discretisation's error (docs/ocean.md). The tetrahedra are fixed when the body is built:
// nothing leaks through the crust or the floor.
// Units: G = M = R = 1. Lengths R, volumes R^3, K and P e_g = G M^2/R^4, forces G M^2/R^2, energies G M^2/R.
//
// Determinism: volumes per tetrahedron, V_a per node gathered over its tetrahedra in
// index order, the forces of each tetrahedron's four corners into their own slots, and each
// particle gathers its slots in index order: the same bits for any thread count.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "model/body.hpp"

namespace tidalcrust {

/// Volume (R^3) of the tetrahedron (x0, x1, x2, x3), positive when x1 - x0, x2 - x0, x3 - x0 are
/// right-handed: det[x1 - x0, x2 - x0, x3 - x0] / 6.
double tetrahedron_volume(const double* x0, const double* x1, const double* x2, const double* x3);

/// The liquid layer's forces and energy for a Body with Body::liquid present. Keeps a reference
/// to the body, which must outlive it.
class LiquidPressure {
 public:
  explicit LiquidPressure(const Body& body);

  /// V_a [N] (R^3) of every pressure node (a corner of a tetrahedron) at positions [N*3] (R); 0 for
  /// the other particles.
  std::vector<double> volumes(const double* position) const;

  /// Forces [N*3] (G M^2/R^2) at positions [N*3] with rest volumes V0 [N]
  /// (State::liquid_rest_volume), plus a Maxwell liquid's support [N*3] (State::liquid_support,
  /// forces/maxwell_liquid.hpp; empty: none), into forces(); 0 for a particle of neither.
  void compute(const double* position, const std::vector<double>& rest_volume, const std::vector<double>& support,
               bool parallel);
  const std::vector<double>& forces() const { return force_; }

  /// sum_a (K/2) (V_a - V0_a)^2 / V0_a, plus the support's -sum_i F_i . x_i (G M^2/R), in index order.
  double energy(const double* position, const std::vector<double>& rest_volume,
                const std::vector<double>& support) const;

  /// P_a = -K (V_a - V0_a) / V0_a (e_g) of every pressure node, 0 for the others.
  std::vector<double> pressure(const double* position, const std::vector<double>& rest_volume) const;

 private:
  /// V_t of every tetrahedron into tet_volume_ (parallel over tetrahedra).
  void tetrahedron_volumes(const double* position, bool parallel) const;
  double volume_of(std::size_t a) const;  ///< V_a from tet_volume_

  const Body& body_;
  std::vector<std::int32_t> node_;         ///< pressure nodes (corners of a tetrahedron), increasing
  // For each particle p, entries [offset[p], offset[p+1]) of `corner_`: 4t + v for corner v of
  // tetrahedron t, in increasing order.
  std::vector<std::int32_t> offset_, corner_;
  mutable std::vector<double> tet_volume_; ///< [Nt]
  std::vector<double> pressure_;           ///< [N] P_a of the last compute()
  std::vector<double> corner_force_;       ///< [Nt*4*3]
  std::vector<double> force_;              ///< [N*3]
};

}  // namespace tidalcrust
