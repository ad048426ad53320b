#pragma once
// Pressure of a self-gravitating sphere of uniform density in hydrostatic equilibrium
// (paper section 2.3, Dobrovolskis 1990 eq. 2), in the units G = M = R = 1.
#include <numbers>

namespace tidalcrust {

/// Mean density of the body, 3/(4 pi) M/R^3.
inline constexpr double mean_body_density = 3.0 / (4.0 * std::numbers::pi);

/// P(r) = (2/3) pi G rho^2 (R^2 - r^2) with rho = 3/(4 pi), R = 1: 3/(8 pi) (1 - r^2) in
/// e_g = G M^2/R^4 for r in R. Negative outside the body (callers clamp where it matters).
inline double hydrostatic_pressure(double r) {
  return 2.0 / 3.0 * std::numbers::pi * mean_body_density * mean_body_density * (1.0 - r * r);
}

}  // namespace tidalcrust
