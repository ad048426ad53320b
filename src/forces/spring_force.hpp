#pragma once
// Spring force law: linear elastic + Kelvin-Voigt damping (paper eqs. 12-14), with the
// optional strain-dependent softening of cross springs (eq. 26).
// Units: lengths R, velocities sqrt(GM/R), masses M, k in G M^2/R^3, gamma in 1/t_grav,
// forces in G M^2/R^2.
#include <algorithm>
#include <cmath>

#include "base/vec3.hpp"

namespace tidalcrust {

/// The spring force on particle i is -c (x_i - x_j); this returns c (G M^2/R^3).
/// length = L = |x_i - x_j| (R); d_dot_dv = (x_i - x_j).(v_i - v_j) (R^2/t_grav);
/// rest_length L0 (R); stiffness k (G M^2/R^3); gamma_mu = gamma * mu, damping rate times
/// reduced mass m_i m_j/(m_i+m_j) (M/t_grav); elastic_factor multiplies the elastic part only
/// (1, or f(eps) of eq. 26).
/// Elastic (eq. 12): -k (L - L0) n, n = (x_i - x_j)/L.
/// Damping (eq. 14): -gamma mu L0 eps_dot n with eps_dot = d.dv / (L L0), i.e. -gamma mu (d.dv/L^2) d.
/// A failed spring needs no special case: its State stiffness already is F_Sk k.
inline double spring_force_coefficient(double length, double d_dot_dv, double rest_length,
                                       double stiffness, double gamma_mu, double elastic_factor = 1.0) {
  const double inv_length = 1.0 / length;
  return elastic_factor * stiffness * (length - rest_length) * inv_length +
         gamma_mu * d_dot_dv * (inv_length * inv_length);
}

/// Eq. 26 (Clavet 2005): f(eps) = 1 for eps <= 0 (compression), max(1 - eps/eps_C, F_Ck) in
/// tension. eps = (L - L0)/L0 is the spring strain; eps_C the strain scale; F_Ck the floor.
inline double cross_spring_factor(double strain, double strain_scale, double min_factor) {
  return strain <= 0 ? 1.0 : std::max(1.0 - strain / strain_scale, min_factor);
}

/// Force on particle i (G M^2/R^2) from the spring (i, j); particle j feels the opposite.
/// d = x_i - x_j, dv = v_i - v_j, reduced_mass mu = m_i m_j/(m_i + m_j), gamma a rate.
inline Vec3 spring_force(const Vec3& d, const Vec3& dv, double rest_length, double stiffness,
                         double gamma, double reduced_mass, double elastic_factor = 1.0) {
  return -spring_force_coefficient(d.norm(), d.dot(dv), rest_length, stiffness, gamma * reduced_mass,
                                   elastic_factor) *
         d;
}

/// Reduced mass m_i m_j / (m_i + m_j) in M.
inline double reduced_mass(double mass_i, double mass_j) { return mass_i * mass_j / (mass_i + mass_j); }

}  // namespace tidalcrust
