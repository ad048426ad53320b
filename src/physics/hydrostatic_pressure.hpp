#pragma once
// Pressure of a self-gravitating sphere in hydrostatic equilibrium (paper section 2.3,
// Dobrovolskis 1990 eq. 2), uniform or with a denser core (issue 12), in the units G = M = R = 1.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <numeric>
#include <vector>

namespace tidalcrust {

/// Mean density of the body, 3/(4 pi) M/R^3.
inline constexpr double mean_body_density = 3.0 / (4.0 * std::numbers::pi);

/// P(r) = (2/3) pi G rho^2 (R^2 - r^2) with rho = 3/(4 pi), R = 1: 3/(8 pi) (1 - r^2) in
/// e_g = G M^2/R^4 for r in R. Negative outside the body (callers clamp where it matters).
inline double hydrostatic_pressure(double r) {
  return 2.0 / 3.0 * std::numbers::pi * mean_body_density * mean_body_density * (1.0 - r * r);
}

/// A two-layer sphere of mass M = 1 and radius R = 1: a core of radius r_c with density
/// density_ratio times the mantle's (mantle density 3/(4 pi) / (1 + (q - 1) r_c^3)).
struct LayeredSphere {
  double core_radius = 0;    ///< r_c, R
  double density_ratio = 1;  ///< q = rho_c / rho_m

  double mantle_density() const {
    return mean_body_density / (1.0 + (density_ratio - 1.0) * core_radius * core_radius * core_radius);
  }
  double core_density() const { return density_ratio * mantle_density(); }

  /// P(r) (e_g): the hydrostatic equation dP/dr = -rho(r) G m(r)/r^2 with P(R) = 0, integrated
  /// in closed form for the two layers (derivation in docs/material.md):
  ///   mantle r >= r_c: P = rho_m [A (1/r - 1) + (2/3) pi rho_m (1 - r^2)],
  ///                    A = (4/3) pi r_c^3 (rho_c - rho_m) (the core's excess mass);
  ///   core   r <  r_c: P = P(r_c) + (2/3) pi rho_c^2 (r_c^2 - r^2).
  /// With density_ratio = 1 or r_c = 0 this is hydrostatic_pressure(r).
  double pressure(double r) const {
    const double pi = std::numbers::pi;
    const double rho_m = mantle_density(), rho_c = core_density(), rc = core_radius;
    const double excess = 4.0 / 3.0 * pi * rc * rc * rc * (rho_c - rho_m);
    auto mantle = [&](double x) {  // the excess term vanishes without a core (also at x = 0)
      const double core_pull = excess != 0 ? excess * (1.0 / x - 1.0) : 0.0;
      return rho_m * (core_pull + 2.0 / 3.0 * pi * rho_m * (1.0 - x * x));
    };
    if (r >= rc) return mantle(r);
    return mantle(rc) + 2.0 / 3.0 * pi * rho_c * rho_c * (rc * rc - r * r);
  }
};

/// Hydrostatic pressure of a body of point masses, spherically averaged: each particle's weight
/// spread over the sphere through it, P(r) = sum over r_j > r of m_j G m(< r_j) / (4 pi r_j^4)
/// (dP/dr = -rho g for the averaged density; m(< r_j) the mass strictly closer to the centre).
/// Unlike hydrostatic_pressure() it follows the mass as the body was built: an interior that ends
/// at r_I < R under a crust at R carries only the crust's weight at r_I, a heavy core its own.
/// Units G = 1: e_g with masses in M and radii in R. Deterministic (ties in radius by index).
class ParticleHydrostaticPressure {
 public:
  /// radii[i] (R, distance from the centre of mass) and mass[i] (M) of every particle.
  ParticleHydrostaticPressure(const std::vector<double>& radii, const std::vector<double>& mass) {
    std::vector<std::size_t> order(radii.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return radii[a] < radii[b] || (radii[a] == radii[b] && a < b);
    });
    radius_.resize(order.size());
    pressure_.assign(order.size() + 1, 0.0);
    std::vector<double> weight(order.size());
    double inside = 0;
    for (std::size_t k = 0; k < order.size(); ++k) {
      const double r = radii[order[k]];
      radius_[k] = r;
      weight[k] = r > 0 ? mass[order[k]] * inside / (4 * std::numbers::pi * r * r * r * r) : 0.0;
      inside += mass[order[k]];
    }
    for (std::size_t k = order.size(); k-- > 0;) pressure_[k] = pressure_[k + 1] + weight[k];
  }

  /// P(r), e_g: the weight of every particle farther out than r; 0 beyond the outermost.
  double operator()(double r) const {
    const auto k = static_cast<std::size_t>(std::upper_bound(radius_.begin(), radius_.end(), r) - radius_.begin());
    return pressure_[k];
  }

 private:
  std::vector<double> radius_;    ///< [N] sorted radii
  std::vector<double> pressure_;  ///< [N+1] pressure_[k] = weight of particles k.. (sorted order)
};

}  // namespace tidalcrust
