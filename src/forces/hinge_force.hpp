#pragma once
// Hinge (bending) force law of Bridson, Marino & Fedkiw 2003, section 4 (paper eq. 22), as an
// evaluator of force and energy. Units: G = M = R = 1; positions R, k_e in G M^2/R^2 as in the
// paper (Bridson's k_e is a force times a length; with R = 1 the numbers agree), forces
// G M^2/R^2, energies G M^2/R.
#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Geometry>  // cross()

#include "base/portable_math.hpp"
#include "base/vec3.hpp"

namespace tidalcrust {

/// Forces on the four vertices of a hinge, in Body::hinges order {wing_1, wing_2, edge_a, edge_b}.
struct HingeForces {
  std::array<Vec3, 4> on;
  bool collapsed = false;  ///< a face is (nearly) degenerate: see collapsed_face_fraction
  double energy = 0;       ///< bending energy E_h, G M^2/R (HingeEvaluator; docs/energy-budget.md)
  /// E_h / C = 2 k_e (1 - cos((theta - theta_rest)/2)), G M^2/R^2: the rate dW/dC at which the
  /// hinge force does work that E_h does not account for (docs/energy-budget.md).
  double energy_per_prefactor = 0;
};

/// Bridson's geometric prefactor C = L^2/(|N1| + |N2|) (R) of the hinge {x1, x2, x3, x4} =
/// {wing_1, wing_2, edge_a, edge_b}: the edge length squared over twice the summed face areas.
inline double hinge_prefactor(const Vec3& x1, const Vec3& x2, const Vec3& x3, const Vec3& x4) {
  return (x4 - x3).squaredNorm() / ((x1 - x3).cross(x1 - x4).norm() + (x2 - x4).cross(x2 - x3).norm());
}

/// A face counts as collapsed (hinge forces ~ 1/|N|^2 blow up) when twice its area |N| falls
/// below this fraction of L^2, L the hinge edge: a wing vertex within ~1e-3 L of the edge line
/// (an equilateral face has |N| = 0.87 L^2).
inline constexpr double collapsed_face_fraction = 1e-3;

/// sin and cos of half the rest angle: the only trigonometry the force needs, computed once
/// per rest angle rather than every step; `portable` (the portable mode): from portable_math,
/// the same bits on every CPU.
struct HalfRestAngle {
  double sin = 0;
  double cos = 1;
  static HalfRestAngle of(double rest_angle, bool portable = false) {
    return {portable_math::sin(0.5 * rest_angle, portable), portable_math::cos(0.5 * rest_angle, portable)};
  }
};

/// One hinge as an evaluator of force AND energy (as HOOMD-blue's bond evaluators), built from
/// its rest angle and stiffness k_e.
///
/// Force: Bridson's F_i = |F| u_i with |F| = k_e C sin((theta - theta_rest)/2), C = L^2/(|N1| + |N2|)
/// (eq. 22), where x1, x2 are the wings, x3-x4 the shared edge, E = x4 - x3, L = |E|,
/// N1 = (x1-x3) x (x1-x4), N2 = (x2-x4) x (x2-x3) (|N| is twice the face area), and
///   u1 = L N1/|N1|^2,  u2 = L N2/|N2|^2,
///   u3 = (x1-x4).E/L N1/|N1|^2 + (x2-x4).E/L N2/|N2|^2,
///   u4 = -(x1-x3).E/L N1/|N1|^2 - (x2-x3).E/L N2/|N2|^2.
/// theta follows hinge_angle() (hinge_geometry.hpp); u_i = -d theta/d x_i, so the force drives
/// theta back to theta_rest. The u_i sum to zero and exert no net torque (momentum and angular
/// momentum conserved). sin and cos of theta/2 come from half-angle formulas, no atan2.
///
/// Energy: this force has no potential at all (docs/energy-budget.md gives the proof): its work
/// form -k_e C sin((theta - theta_rest)/2) d theta has the exterior derivative
/// -k_e sin((theta - theta_rest)/2) dC ^ d theta, not zero because C and theta are independent
/// functions of the positions (moving a wing within its face plane changes C, not theta): the
/// work around a loop that bends the hinge at one C and back at another is not zero. The energy
/// returned is the one whose gradient is -F when C is held fixed:
///   E_h = 2 k_e C (1 - cos((theta - theta_rest)/2)) = 4 k_e C sin^2((theta - theta_rest)/4),
/// (zero at rest, k_e C (theta - theta_rest)^2/4 near it). Exactly
///   F . dx = -dE_h + (E_h/C) dC,
/// so the hinge force does the work W_h = integral of (E_h/C) dC beyond -Delta E_h; the energy
/// budget accumulates it every step (energy_per_prefactor, Leapfrog::last_work). The mismatch
/// of the gradient is second order in theta - theta_rest while the force is first order:
/// tests/forces/test_energies.cpp checks it term by term. 1 - cos is evaluated as
/// sin^2/(1 + cos) where cos >= 0, free of cancellation for small angles. Theta jumps at a
/// fully folded hinge (theta = pi); the energy jumps there too, as the force flips.
class HingeEvaluator {
 public:
  /// rest: sin and cos of theta_rest/2; stiffness k_e (G M^2/R^2).
  HingeEvaluator(HalfRestAngle rest, double stiffness) : rest_(rest), stiffness_(stiffness) {}
  /// rest_angle theta_rest in radians.
  HingeEvaluator(double rest_angle, double stiffness) : HingeEvaluator(HalfRestAngle::of(rest_angle), stiffness) {}

  /// Forces on {x1, x2, x3, x4} = {wing_1, wing_2, edge_a, edge_b} (R), the energy, and whether
  /// a face collapsed.
  HingeForces force_and_energy(const Vec3& x1, const Vec3& x2, const Vec3& x3, const Vec3& x4) const {
    const Vec3 e = x4 - x3;
    const Vec3 n1 = (x1 - x3).cross(x1 - x4);
    const Vec3 n2 = (x2 - x4).cross(x2 - x3);
    const double n1_sq = n1.squaredNorm();
    const double n2_sq = n2.squaredNorm();
    const double n1_norm = std::sqrt(n1_sq);
    const double n2_norm = std::sqrt(n2_sq);
    const double length = e.norm();
    const double inv_length = 1 / length;
    const double inv_normal_product = 1 / (n1_norm * n2_norm);
    // Both normals are perpendicular to the edge, so n1 x n2 is parallel to it.
    const double cos_theta = n1.dot(n2) * inv_normal_product;
    const double sin_theta = n1.cross(n2).dot(e) * (inv_normal_product * inv_length);
    // Half angles, each from the formula without cancellation on its side of pi/2.
    double sin_half, cos_half;
    if (cos_theta >= 0) {
      cos_half = std::sqrt(0.5 * (1 + cos_theta));
      sin_half = sin_theta / (2 * cos_half);
    } else {
      sin_half = std::copysign(std::sqrt(0.5 * (1 - cos_theta)), sin_theta);
      cos_half = sin_theta / (2 * sin_half);
    }
    const double sin_half_difference = sin_half * rest_.cos - cos_half * rest_.sin;
    const double scale = stiffness_ * length * length / (n1_norm + n2_norm);  // k_e C
    const double magnitude = scale * sin_half_difference;

    const Vec3 w1 = n1 * (1 / n1_sq);  // N1/|N1|^2
    const Vec3 w2 = n2 * (1 / n2_sq);
    HingeForces f;
    f.collapsed = !(std::min(n1_norm, n2_norm) >= collapsed_face_fraction * length * length);
    f.on[0] = (magnitude * length) * w1;
    f.on[1] = (magnitude * length) * w2;
    f.on[2] = (magnitude * (x1 - x4).dot(e) * inv_length) * w1 + (magnitude * (x2 - x4).dot(e) * inv_length) * w2;
    f.on[3] = (-magnitude * (x1 - x3).dot(e) * inv_length) * w1 - (magnitude * (x2 - x3).dot(e) * inv_length) * w2;
    const double cos_half_difference = cos_half * rest_.cos + sin_half * rest_.sin;
    const double one_minus_cos = cos_half_difference >= 0 ? sin_half_difference * sin_half_difference /
                                                                (1 + cos_half_difference)
                                                          : 1 - cos_half_difference;
    f.energy = 2 * scale * one_minus_cos;
    f.energy_per_prefactor = 2 * stiffness_ * one_minus_cos;
    return f;
  }

 private:
  HalfRestAngle rest_;
  double stiffness_;
};

}  // namespace tidalcrust
