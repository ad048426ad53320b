#include "model/derived_quantities.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include "base/vec3.hpp"
#include "model/center_of_mass.hpp"

namespace tidalcrust {
namespace {

/// Sums of one spring kind, in spring index order (fixed summation order).
struct KindSums {
  std::size_t count = 0;
  double rest_length = 0;        ///< sum L0, R
  double stiffness = 0;          ///< sum k, G M^2/R^3
  double stiffness_length2 = 0;  ///< sum k L0^2 (eq. 15), G M^2/R
  double mean_length() const { return count ? rest_length / static_cast<double>(count) : 0.0; }
  double mean_stiffness() const { return count ? stiffness / static_cast<double>(count) : 0.0; }
};

/// Poisson ratio of the random isotropic spring network (Kot 2015).
constexpr double interior_poisson_ratio = 0.25;
/// Mean density of the body in units M/R^3.
constexpr double mean_density = 3.0 / (4.0 * std::numbers::pi);

/// Stability bound of eq. 13: min over springs sqrt(mu_ij / (k_ij b)), with b the larger
/// spring count of the two endpoints. Springs with zero stiffness impose no bound.
/// Returns 0 when no spring bounds the step (no springs), so JSON output stays finite.
double stability_bound(const Body& body, const State& state) {
  std::vector<std::int32_t> springs_on(body.particle_count(), 0);
  for (const auto& s : body.springs) {
    ++springs_on[static_cast<std::size_t>(s[0])];
    ++springs_on[static_cast<std::size_t>(s[1])];
  }
  double bound = std::numeric_limits<double>::infinity();
  for (std::size_t n = 0; n < body.spring_count(); ++n) {
    const auto i = static_cast<std::size_t>(body.springs[n][0]);
    const auto j = static_cast<std::size_t>(body.springs[n][1]);
    const double k = state.springs.stiffness[n];
    if (!(k > 0)) continue;
    const double mu = body.mass[i] * body.mass[j] / (body.mass[i] + body.mass[j]);
    const double b = static_cast<double>(std::max(springs_on[i], springs_on[j]));
    bound = std::min(bound, std::sqrt(mu / (k * b)));
  }
  return std::isfinite(bound) ? bound : 0.0;
}

}  // namespace

double p_wave_speed(double youngs_modulus) {
  const double nu = interior_poisson_ratio;
  return std::sqrt(youngs_modulus / mean_density) * std::sqrt((1 - nu) / ((1 + nu) * (1 - 2 * nu)));
}

DerivedQuantities derive_quantities(const Body& body, const State& state, double interior_radius) {
  KindSums sums[3];
  for (std::size_t n = 0; n < body.spring_count(); ++n) {
    const auto kind = body.spring_kind[n];
    if (kind > 2) continue;
    KindSums& s = sums[kind];
    const double length = state.springs.rest_length[n];
    const double k = state.springs.stiffness[n];
    ++s.count;
    s.rest_length += length;
    s.stiffness += k;
    s.stiffness_length2 += k * length * length;
  }
  const KindSums& interior = sums[static_cast<int>(SpringKind::interior)];
  const KindSums& shell = sums[static_cast<int>(SpringKind::shell)];
  const KindSums& cross = sums[static_cast<int>(SpringKind::cross)];

  DerivedQuantities q;
  const double volume = 4.0 / 3.0 * std::numbers::pi * interior_radius * interior_radius * interior_radius;
  q.E_I = volume > 0 ? network_youngs_modulus(interior.stiffness_length2, volume) : 0.0;
  q.L_I = interior.mean_length();
  q.k_I = interior.mean_stiffness();
  q.L_S = shell.mean_length();
  q.k_S = shell.mean_stiffness();
  q.L_C = cross.mean_length();
  q.k_C = cross.mean_stiffness();
  for (std::size_t i = 0; i < body.particle_count(); ++i)
    if (body.species[i] == static_cast<std::uint8_t>(Species::shell)) q.M_S += body.mass[i];

  q.V_IP = p_wave_speed(q.E_I);
  if (q.M_S > 0) {
    q.V_SP = std::sqrt(q.k_S * 4.0 * std::numbers::pi / q.M_S);  // R = 1
    q.V_Co = std::sqrt(q.k_C * static_cast<double>(cross.count) / q.M_S) * q.L_C;
  }
  // E_2D = (2/sqrt 3) k_S = E_S h_S with the shell modulus taken equal to the interior's.
  if (q.E_I > 0 && shell.count > 0) q.h_S = 2.0 / std::sqrt(3.0) * q.k_S / q.E_I;
  q.E_2D = 2.0 / std::sqrt(3.0) * q.k_S;
  if (body.hinge_count() > 0) {
    double sum = 0;
    for (double k : body.hinge_stiffness) sum += k;
    const double mean_hinge = sum / static_cast<double>(body.hinge_count());
    q.D_F = hinge_lattice_flexural_rigidity(mean_hinge);
    q.D_F_eq23 = mean_hinge * q.L_S / 2.0;
  }
  q.dt_max = stability_bound(body, state);
  return q;
}

double inner_network_youngs_modulus(const Body& body, const State& state, double radius) {
  return interior_modulus_profile(body, state, {radius})[0];
}

std::vector<double> interior_modulus_profile(const Body& body, const State& state,
                                             const std::vector<double>& outer_radii) {
  const Vec3 center = body_center_of_mass(body, state);
  std::vector<double> sum(outer_radii.size(), 0.0);
  for (std::size_t n = 0; n < body.spring_count(); ++n) {
    if (body.spring_kind[n] != static_cast<std::uint8_t>(SpringKind::interior)) continue;
    const auto [i, j] = body.springs[n];
    const Vec3 mid = 0.5 * (vec3_at(state.position, static_cast<std::size_t>(i)) +
                            vec3_at(state.position, static_cast<std::size_t>(j)));
    const double r = (mid - center).norm();
    const auto b = static_cast<std::size_t>(std::upper_bound(outer_radii.begin(), outer_radii.end(), r) - outer_radii.begin());
    if (b == outer_radii.size()) continue;
    const double length = state.springs.rest_length[n];
    sum[b] += state.springs.stiffness[n] * length * length;
  }
  std::vector<double> modulus(outer_radii.size());
  double inner = 0;
  for (std::size_t b = 0; b < outer_radii.size(); ++b) {
    const double outer = outer_radii[b];
    // Written as the difference of two balls so that one bin from 0 rounds as 4/3 pi r r r did.
    const double volume = 4.0 / 3.0 * std::numbers::pi * outer * outer * outer -
                          4.0 / 3.0 * std::numbers::pi * inner * inner * inner;
    modulus[b] = network_youngs_modulus(sum[b], volume);
    inner = outer;
  }
  return modulus;
}

}  // namespace tidalcrust
