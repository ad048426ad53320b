#pragma once
// Spring force law as an evaluator that returns force AND energy (the pattern of HOOMD-blue's
// EvaluatorBondHarmonic.h: a small object built from one bond's parameters, evaluated by the
// one loop over the bonds): linear elastic + Kelvin-Voigt damping (paper eqs. 12-14), with the
// optional strain-dependent softening of cross springs (eq. 26).
// Units: G = M = R = 1. Lengths R, velocities sqrt(GM/R), masses M, k in G M^2/R^3, gamma in
// 1/t_grav, forces G M^2/R^2, energies G M^2/R, power G M^2/R per t_grav.
#include <algorithm>
#include <cmath>

#include "base/vec3.hpp"

namespace tidalcrust {

/// Parameters of eq. 26 (Clavet et al. 2005), shared by every softened cross spring.
struct CrossSoftening {
  double strain_scale = 0.03;     ///< eps_C
  double min_force_factor = 0.1;  ///< F_Ck, the floor of the factor
};

/// Eq. 26: f(eps) = 1 for eps <= 0 (compression), max(1 - eps/eps_C, F_Ck) in tension.
/// eps = (L - L0)/L0 is the spring strain; eps_C the strain scale; F_Ck the floor.
inline double cross_spring_factor(double strain, double strain_scale, double min_factor) {
  return strain <= 0 ? 1.0 : std::max(1.0 - strain / strain_scale, min_factor);
}

/// Elastic energy of a spring softened by eq. 26: the integral of the force magnitude
/// k u f(u/L0) over the stretch u from 0 to u = L - L0 (G M^2/R). With a = L0 eps_C and
/// u_c = a max(0, 1 - F_Ck), the stretch where the floor F_Ck is reached:
///   u <= 0:          k u^2/2                                     (linear in compression)
///   0 < u <= u_c:    k (u^2/2 - u^3/(3a))                        (f = 1 - u/a)
///   u > u_c:         k (u_c^2/2 - u_c^3/(3a)) + k F_Ck (u^2 - u_c^2)/2   (f = F_Ck)
/// Continuous with a continuous derivative (the force) at 0 and at u_c.
inline double cross_spring_energy(double stretch, double rest_length, double stiffness, const CrossSoftening& c) {
  if (stretch <= 0) return 0.5 * stiffness * stretch * stretch;
  const double a = rest_length * c.strain_scale;
  const double kink = a * std::max(0.0, 1.0 - c.min_force_factor);
  const double u = std::min(stretch, kink);
  const double softened = stiffness * u * u * (0.5 - u / (3 * a));
  return stretch <= kink ? softened
                         : softened + 0.5 * stiffness * c.min_force_factor * (stretch - kink) * (stretch + kink);
}

/// What SpringEvaluator::force_and_energy returns for one spring (i, j).
struct SpringForceEnergy {
  /// c in G M^2/R^3: the force on particle i is -c (x_i - x_j), particle j feels the opposite.
  double coefficient = 0;
  /// The damping part of `coefficient`, gamma mu (d.dv)/L^2 (1/t_grav times M): the damping force on
  /// i is -damping_coefficient (x_i - x_j). The same bits as the term inside `coefficient`.
  double damping_coefficient = 0;
  /// Elastic energy, G M^2/R: k (L - L0)^2 / 2, or cross_spring_energy() when eq. 26 applies.
  double energy = 0;
  /// Power the damping force removes from the motion, gamma mu (d.dv)^2 / L^2 >= 0 (G M^2/R per
  /// t_grav). Damping has no potential; this is its share of an energy budget.
  double dissipated_power = 0;
};

/// One spring (i, j): elastic (eq. 12) -k (L - L0) n, n = (x_i - x_j)/L, times f(eps) of eq. 26
/// for a softened cross spring (the elastic part only), plus damping (eq. 14)
/// -gamma mu L0 eps_dot n with eps_dot = d.dv / (L L0), i.e. -gamma mu (d.dv/L^2) d.
/// A failed spring needs no special case: its stiffness already is F_Sk k.
class SpringEvaluator {
 public:
  /// rest_length L0 (R, > 0); stiffness k (G M^2/R^3); gamma_mu = gamma * mu, the damping rate
  /// times the reduced mass m_i m_j/(m_i+m_j) (M/t_grav); softening: eq. 26 parameters, or
  /// nullptr for a linear spring (must outlive the evaluator).
  SpringEvaluator(double rest_length, double stiffness, double gamma_mu, const CrossSoftening* softening = nullptr)
      : rest_length_(rest_length), stiffness_(stiffness), gamma_mu_(gamma_mu), softening_(softening) {}

  /// length = L = |x_i - x_j| (R, > 0); d_dot_dv = (x_i - x_j).(v_i - v_j) (R^2/t_grav).
  SpringForceEnergy force_and_energy(double length, double d_dot_dv) const {
    const double factor =
        softening_ ? cross_spring_factor((length - rest_length_) / rest_length_, softening_->strain_scale,
                                         softening_->min_force_factor)
                   : 1.0;
    const double inv_length = 1.0 / length;
    SpringForceEnergy r;
    r.damping_coefficient = gamma_mu_ * d_dot_dv * (inv_length * inv_length);
    r.coefficient = factor * stiffness_ * (length - rest_length_) * inv_length + r.damping_coefficient;
    const double stretch = length - rest_length_;
    r.energy = softening_ ? cross_spring_energy(stretch, rest_length_, stiffness_, *softening_)
                          : 0.5 * stiffness_ * stretch * stretch;
    const double stretch_rate = d_dot_dv * inv_length;  // dL/dt
    r.dissipated_power = gamma_mu_ * stretch_rate * stretch_rate;
    return r;
  }

  /// Force on particle i (G M^2/R^2) for d = x_i - x_j, dv = v_i - v_j; j feels the opposite.
  Vec3 force(const Vec3& d, const Vec3& dv) const { return -force_and_energy(d.norm(), d.dot(dv)).coefficient * d; }

 private:
  double rest_length_;
  double stiffness_;
  double gamma_mu_;
  const CrossSoftening* softening_;
};

/// Reduced mass m_i m_j / (m_i + m_j) in M.
inline double reduced_mass(double mass_i, double mass_j) { return mass_i * mass_j / (mass_i + mass_j); }

}  // namespace tidalcrust
