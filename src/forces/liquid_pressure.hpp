#pragma once
// A liquid as particles with pressure-only interactions (docs/ocean.md). Each liquid particle's
// energy depends on its number density alone,
//   n_a = w_a W(0) + sum_b w_b W(|x_a - x_b|),
// a kernel sum over the liquid particles and the solid particles at the layer's boundary
// (Body::liquid's density_weight w), with the Wendland C2 kernel (Wendland 1995; stable against
// pairing, Dehnen & Aly 2012). The forces are minus the gradient of the total energy: central,
// equal and opposite, so momentum, angular momentum and (without damping) energy are conserved.
// N particles and N densities leave 2N directions free, so a shear that moves the particles to
// keep every density costs nothing: the layer has a bulk modulus and no static shear modulus.
// Units: G = M = R = 1. Lengths R, number densities 1/R^3, K and pressure e_g = G M^2/R^4,
// forces G M^2/R^2, energies G M^2/R, damping rate 1/t_grav.
//
// Determinism: the neighbours of every particle are found afresh from the positions in each pass
// (cells of size H sorted by cell and index); each particle sums over its own neighbours in that
// order and computes the pair terms itself (each pair twice, the two results exactly opposite), so
// the result depends on the positions only: bitwise the same for any thread count, across resume
// and whenever the pass is called.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <vector>

#include "model/body.hpp"

namespace tidalcrust {

/// The Wendland C2 kernel in three dimensions with support radius H (R):
///   W(r) = 21/(2 pi H^3) (1 - q)^4 (1 + 4 q) for q = r/H < 1, 0 beyond (1/R^3),
/// normalised to 1 over space; dW/dr = -(210/(2 pi H^4)) q (1 - q)^3 (1/R^4).
struct WendlandKernel {
  double support = 1;  ///< H, R (> 0)
  double value(double r) const {
    const double q = r / support;
    if (q >= 1) return 0;
    const double s = 1 - q;
    return norm() * (s * s) * (s * s) * (1 + 4 * q);
  }
  double derivative(double r) const {
    const double q = r / support;
    if (q >= 1) return 0;
    const double s = 1 - q;
    return -20 * norm() / support * q * (s * s * s);
  }
  double norm() const { return 21.0 / (2.0 * std::numbers::pi * support * support * support); }
};

/// The equation of state of one liquid particle of reference number density n0 (zero pressure,
/// 1/R^3) and bulk modulus K (e_g): pressure P(n) = K (n/n0 - 1) (e_g); energy, minus the work of
/// P on the particle's volume 1/n, e(n) = (K/n0) (ln(n/n0) + n0/n - 1) (G M^2/R, >= 0, 0 at n0);
/// de/dn = P/n^2 (G M^2/R * R^3).
struct LiquidEquationOfState {
  double reference_density;  ///< n0, 1/R^3 (> 0)
  double bulk_modulus;       ///< K, e_g
  double pressure(double n) const { return bulk_modulus * (n / reference_density - 1); }
  double energy(double n) const {
    return bulk_modulus / reference_density * (std::log(n / reference_density) + reference_density / n - 1);
  }
  double energy_slope(double n) const { return pressure(n) / (n * n); }
};

/// The contact between a liquid particle and a solid one at distance r (R), contact radius delta
/// (R) and stiffness k (G M^2/R^3): energy (k/2)(delta - r)^2 for r < delta, 0 beyond; the force on
/// the liquid particle is k (delta - r) along (x_liquid - x_solid)/r, the solid one feels the
/// opposite. Why contact and not the density sum: in equilibrium the contacts must carry the
/// liquid's pressure onto the walls exactly (momentum balance of the liquid), whereas a single
/// layer of crust nodes in the density sums carries a fraction of it; and the kernel smooths over
/// H, wider than the gaps between crust nodes, so liquid particles would pass through the crust
/// (measured: docs/ocean.md).
struct LiquidContact {
  double stiffness;  ///< k, G M^2/R^3
  double energy(double r, double radius) const { return r < radius ? 0.5 * stiffness * (radius - r) * (radius - r) : 0.0; }
  /// Force magnitude over r (G M^2/R^3): the force on the liquid particle is this times d.
  double coefficient(double r, double radius) const { return r < radius ? stiffness * (radius - r) / r : 0.0; }
};

/// The liquid layer's forces, energy and densities for a Body with Body::liquid present. Keeps a
/// reference to the body, which must outlive it.
class LiquidPressure {
 public:
  explicit LiquidPressure(const Body& body);

  /// Number density n [N] (1/R^3) of every liquid particle at positions [N*3] (R); 0 for the
  /// other particles.
  std::vector<double> densities(const double* position, bool parallel) const;

  /// Forces [N*3] (G M^2/R^2) on every particle at positions [N*3] (R) and velocities [N*3]
  /// (sqrt(GM/R)), with reference densities n0 [N] (State::liquid_reference_density): the pressure
  /// forces, plus a damping of each pair's approach speed at rate `damping` (1/t_grav) weighted by
  /// W(r)/W(0), -damping mu (W(r)/W(0)) (d.dv/r^2) d on a, as the springs' eq. 14 (mu the reduced
  /// mass). Written into forces() (0 for a particle the liquid does not reach).
  void compute(const double* position, const double* velocity, const std::vector<double>& reference_density,
               double damping, bool parallel);
  const std::vector<double>& forces() const { return force_; }

  /// Energy sum_a e_a(n_a) of the liquid particles plus their contact energy with solid particles
  /// (G M^2/R), summed in index order.
  double energy(const double* position, const std::vector<double>& reference_density) const;
  /// Power the pair damping removes at velocities [N*3], sum over pairs of damping mu (W/W(0))
  /// (d.dv)^2/r^2 (G M^2/R per t_grav), each pair once, in index order.
  double damping_power(const double* position, const double* velocity, double damping) const;
  /// Energy the pair damping of the last compute() took out of the motion from positions `start`
  /// to `end` [N*3]: minus the sum over particles of F_damping . (x_end - x_start), in index order
  /// (G M^2/R; >= 0 up to O(dt^2)). 0 before the first compute().
  double damping_work(const double* start, const double* end) const;

  const WendlandKernel& kernel() const { return kernel_; }
  const LiquidContact& contact() const { return contact_; }

 private:
  /// The particles within H of particle a (w > 0, b != a) at `position`, in a fixed order
  /// (cells in order, then index), into `out`.
  void neighbours(std::size_t a, const double* position, std::vector<std::int32_t>& out) const;
  /// Sorts the reachable particles into cells of size H at `position` (cell_key_, cell_order_).
  void build_cells(const double* position) const;
  std::int64_t cell_of(const double* x) const;

  const Body& body_;
  WendlandKernel kernel_;
  LiquidContact contact_;
  std::vector<std::int32_t> reachable_;  ///< particles with density weight > 0, in index order
  std::vector<double> force_;            ///< [N*3] all liquid forces of the last compute()
  std::vector<double> damping_force_;    ///< [N*3] their damping part
  std::vector<double> density_;          ///< [N] workspace of compute()
  // Cells of the last build_cells: reachable particles sorted by (cell key, index).
  mutable std::vector<std::int64_t> cell_key_;
  mutable std::vector<std::int32_t> cell_order_;
  mutable double origin_[3] = {0, 0, 0};
};

}  // namespace tidalcrust
