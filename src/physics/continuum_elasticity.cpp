#include "physics/continuum_elasticity.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "base/errors.hpp"

namespace tidalcrust {

namespace {

void check_poisson_ratio(double poisson_ratio, double lowest) {
  if (!(poisson_ratio > lowest && poisson_ratio < 0.5))
    throw InputError(fmt::format("Poisson ratio must lie in ({}, 1/2), got {}", lowest, poisson_ratio));
}

void check_positive(double value, const char* name) {
  if (!(value > 0 && std::isfinite(value))) throw InputError(fmt::format("{} must be > 0, got {}", name, value));
}

/// The Lame parameters (lambda, mu) of Young's modulus E and Poisson ratio nu.
std::array<double, 2> lame_parameters(double youngs_modulus, double poisson_ratio) {
  const double mu = youngs_modulus / (2 * (1 + poisson_ratio));
  const double lambda = youngs_modulus * poisson_ratio / ((1 + poisson_ratio) * (1 - 2 * poisson_ratio));
  return {lambda, mu};
}

using Y = std::array<double, 6>;  // y1..y6 of Takeuchi & Saito (1972)

/// Right-hand side of TS72 eq. 82 at radius r in a layer (lambda, mu, rho) with the gravity
/// g(r) = m(r)/r^2 of the mass inside r (G = 1); L = n(n+1). y5 is the potential perturbation in
/// the geodesy sign (force = +grad y5), y6 = y5' - 4 pi rho y1 + (n+1) y5 / r. `omega_squared`
/// adds the inertia -omega^2 rho u of a free oscillation to the two momentum equations (dy2/dr,
/// dy4/dr; TS72 eq. 82 as printed); `gravity` 0 drops self-gravity (g and the Poisson terms) but
/// keeps the body force rho grad y5 of an external potential.
Y spheroidal_rhs(double r, const Y& y, int n, double lambda, double mu, double rho, double g, double omega_squared,
                 double gravity) {
  const double four_pi_rho = gravity * 4 * std::numbers::pi * rho;
  const double rho_g = gravity * rho * g;
  const double L = n * (n + 1.0);
  const double beta = lambda + 2 * mu;
  const double inv_r = 1 / r;
  const double divergence_part = 2 * y[0] - L * y[2];  // r times the horizontal divergence part
  Y d;
  d[0] = (y[1] - lambda * divergence_part * inv_r) / beta;
  d[1] = inv_r * (-2 * rho_g * y[0] - 2 * y[1] + L * y[3] + rho * (n + 1) * y[4] - rho * r * y[5] +
                  2 * lambda * d[0] + divergence_part * (2 * (lambda + mu) * inv_r - rho_g)) -
         omega_squared * rho * y[0];
  d[2] = (y[2] - y[0]) * inv_r + y[3] / mu;
  d[3] = inv_r * ((rho_g + 2 * mu * inv_r) * y[0] - 2 * mu * inv_r * y[2] - 3 * y[3] - rho * y[4] -
                  lambda * d[0] - divergence_part * beta * inv_r) -
         omega_squared * rho * y[2];
  d[4] = four_pi_rho * y[0] - (n + 1) * inv_r * y[4] + y[5];
  d[5] = inv_r * (four_pi_rho * (n - 1) * y[0] + (n - 1) * y[5] + four_pi_rho * divergence_part);
  return d;
}

Y axpy(const Y& y, double h, const Y& k) {
  Y out;
  for (int i = 0; i < 6; ++i) out[i] = y[i] + h * k[i];
  return out;
}

}  // namespace

double p_wave_speed(double youngs_modulus, double poisson_ratio, double density) {
  check_poisson_ratio(poisson_ratio, -1);
  check_positive(youngs_modulus, "Young's modulus");
  check_positive(density, "density");
  const double nu = poisson_ratio;
  return std::sqrt(youngs_modulus / density) * std::sqrt((1 - nu) / ((1 + nu) * (1 - 2 * nu)));
}

double lamb_breathing_root(double poisson_ratio) {
  check_poisson_ratio(poisson_ratio, -1);
  const double c = (1 - poisson_ratio) / (2 * (1 - 2 * poisson_ratio));
  // Multiplied by cos x, the equation has no poles; near 0 it goes as x^3 (1/3 - c).
  const auto f = [c](double x) { return (1 - c * x * x) * std::sin(x) - x * std::cos(x); };
  const double step = 1e-3;
  double lo = step;
  const double sign_near_zero = f(lo);
  while (f(lo + step) * sign_near_zero > 0) {
    lo += step;
    if (lo > 10) throw InputError(fmt::format("no breathing root below 10 for Poisson ratio {}", poisson_ratio));
  }
  double hi = lo + step;
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) * sign_near_zero > 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double lamb_breathing_period(double youngs_modulus, double poisson_ratio, double density, double radius) {
  check_positive(radius, "radius");
  return 2 * std::numbers::pi * radius /
         (lamb_breathing_root(poisson_ratio) * p_wave_speed(youngs_modulus, poisson_ratio, density));
}

double self_gravitating_breathing_period(double youngs_modulus, double poisson_ratio, double density, double radius) {
  const double omega_lamb = 2 * std::numbers::pi / lamb_breathing_period(youngs_modulus, poisson_ratio, density, radius);
  const double omega_squared = omega_lamb * omega_lamb - 16 * std::numbers::pi / 3 * density;
  if (!(omega_squared > 0))
    throw InputError(fmt::format("a homogeneous sphere of E = {} and density {} collapses under its own gravity",
                                 youngs_modulus, density));
  return 2 * std::numbers::pi / std::sqrt(omega_squared);
}

LoveNumbers homogeneous_sphere_love_numbers(int degree, double youngs_modulus, double poisson_ratio, double density,
                                            double radius, int steps) {
  return layered_sphere_love_numbers(degree, {{radius, youngs_modulus, poisson_ratio, density}}, steps);
}

namespace {

void check_layers(int degree, const std::vector<ElasticLayer>& layers, int steps) {
  if (degree < 2) throw InputError(fmt::format("spheroidal solutions need degree >= 2, got {}", degree));
  if (steps < 100) throw InputError(fmt::format("the spheroidal integration needs >= 100 steps, got {}", steps));
  if (layers.empty()) throw InputError("a layered sphere needs at least one layer");
  double inner = 0;
  for (const auto& layer : layers) {
    check_poisson_ratio(layer.poisson_ratio, -1);
    check_positive(layer.youngs_modulus, "Young's modulus");
    check_positive(layer.density, "density");
    if (!(layer.outer_radius > inner))
      throw InputError(fmt::format("layer radii must increase, got {} after {}", layer.outer_radius, inner));
    inner = layer.outer_radius;
  }
  if (!(0.005 * layers.back().outer_radius < layers.front().outer_radius))
    throw InputError("the innermost layer is thinner than the start radius");
}

/// The three regular solutions of TS72's y1..y6 at the surface (the last layer's outer radius),
/// and the surface gravity m/a^2 of the layers' mass (G = 1).
struct SurfaceSolutions {
  std::array<Y, 3> y;
  double gravity = 0;
};

SurfaceSolutions regular_solutions_at_surface(int n, const std::vector<ElasticLayer>& layers, int steps,
                                              double omega_squared, double gravity) {
  const double radius = layers.back().outer_radius;
  const double L = n * (n + 1.0);

  // Regular solutions near the centre, exact without gravity and inertia (whose terms are
  // O(rho^2 r^2/mu) and O(omega^2 rho r^2/mu) smaller there): u = grad(r^n Y_n); the r^(n+1)
  // solution of the Navier equation, y1 = r^(n+1), y3 = b r^(n+1), y2 = c r^n, y4 = d r^n with
  // b, c, d from the equations; and the potential r^n alone. Any error excites the irregular
  // solutions, which decay outward as (r0/r)^(2n+1).
  const double r0 = 0.005 * radius;
  const auto [lambda0, mu0] = lame_parameters(layers.front().youngs_modulus, layers.front().poisson_ratio);
  const double beta0 = lambda0 + 2 * mu0;
  const double b = (2 * mu0 - lambda0 * (n + 1) - 2 * beta0 - (n + 3) * mu0) / ((n + 3) * n * mu0 + 2 * mu0 - L * beta0);
  const double c = beta0 * (n + 1) + lambda0 * (2 - L * b);
  const double d = mu0 * (n * b + 1);
  SurfaceSolutions out;
  auto& solutions = out.y;
  const double p_minus_2 = std::pow(r0, n - 2), p_minus_1 = p_minus_2 * r0, p = p_minus_1 * r0, p_plus_1 = p * r0;
  solutions[0] = {n * p_minus_1, 2 * mu0 * n * (n - 1) * p_minus_2, p_minus_1, 2 * mu0 * (n - 1) * p_minus_2, 0, 0};
  solutions[1] = {p_plus_1, c * p, b * p_plus_1, d * p, 0, 0};
  solutions[2] = {0, 0, 0, 0, p, (2 * n + 1) * p_minus_1};

  // Layer by layer (y1..y6 are continuous across the boundaries of welded solid layers), each with
  // its share of the steps; g(r) from the mass inside r.
  double start = r0, mass_below = 0, layer_inner = 0;
  for (const auto& layer : layers) {
    const auto [lambda, mu] = lame_parameters(layer.youngs_modulus, layer.poisson_ratio);
    const double rho = layer.density;
    const double four_pi_rho_3 = 4 * std::numbers::pi * rho / 3;
    const double below = mass_below - four_pi_rho_3 * layer_inner * layer_inner * layer_inner;
    const auto g_at = [&](double r) { return (below + four_pi_rho_3 * r * r * r) / (r * r); };
    const auto rhs = [&](double r, const Y& y) {
      return spheroidal_rhs(r, y, n, lambda, mu, rho, g_at(r), omega_squared, gravity);
    };
    const int layer_steps = std::max(100, static_cast<int>(std::ceil(steps * (layer.outer_radius - start) / radius)));
    const double h = (layer.outer_radius - start) / layer_steps;
    for (auto& y : solutions) {
      for (int s = 0; s < layer_steps; ++s) {
        const double r = start + s * h;
        const Y k1 = rhs(r, y);
        const Y k2 = rhs(r + h / 2, axpy(y, h / 2, k1));
        const Y k3 = rhs(r + h / 2, axpy(y, h / 2, k2));
        const Y k4 = rhs(r + h, axpy(y, h, k3));
        for (int i = 0; i < 6; ++i) y[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
      }
    }
    mass_below = below + four_pi_rho_3 * layer.outer_radius * layer.outer_radius * layer.outer_radius;
    layer_inner = start = layer.outer_radius;
  }
  out.gravity = mass_below / (radius * radius);
  return out;
}

/// The surface rows y2, y4, y6 of the three solutions (columns), each column scaled to unit
/// largest entry (the sign of the determinant is kept).
Eigen::Matrix3d boundary_matrix(const SurfaceSolutions& s, bool normalize) {
  Eigen::Matrix3d boundary;
  for (int j = 0; j < 3; ++j) {
    boundary(0, j) = s.y[j][1];
    boundary(1, j) = s.y[j][3];
    boundary(2, j) = s.y[j][5];
    if (normalize) boundary.col(j) /= boundary.col(j).cwiseAbs().maxCoeff();
  }
  return boundary;
}

}  // namespace

LoveNumbers layered_sphere_love_numbers(int degree, const std::vector<ElasticLayer>& layers, int steps,
                                        bool self_gravity) {
  check_layers(degree, layers, steps);
  const int n = degree;
  const double radius = layers.back().outer_radius;
  const SurfaceSolutions s = regular_solutions_at_surface(n, layers, steps, 0.0, self_gravity ? 1.0 : 0.0);
  // Surface: free of traction (y2 = y4 = 0) under a unit external potential (y6 = (2n+1)/a).
  const Eigen::Vector3d weights =
      boundary_matrix(s, false).fullPivLu().solve(Eigen::Vector3d(0, 0, (2 * n + 1) / radius));
  Y surface{};
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 6; ++i) surface[i] += weights[j] * s.y[j][i];
  const double g = s.gravity;
  return {g * surface[0], self_gravity ? surface[4] - 1 : 0.0, g * surface[2]};
}

double spheroidal_fundamental_frequency(int degree, const std::vector<ElasticLayer>& layers, bool self_gravity,
                                        int steps) {
  check_layers(degree, layers, steps);
  const double radius = layers.back().outer_radius;
  double shear_speed = 0;
  for (const auto& layer : layers)
    shear_speed = std::max(shear_speed, std::sqrt(lame_parameters(layer.youngs_modulus, layer.poisson_ratio)[1] /
                                                  layer.density));
  // Free surface, no external potential: y2 = y4 = y6 = 0, i.e. the boundary matrix is singular.
  const auto determinant = [&](double omega) {
    return boundary_matrix(regular_solutions_at_surface(degree, layers, steps, omega * omega, self_gravity ? 1.0 : 0.0),
                           true)
        .determinant();
  };
  const double scale = shear_speed / radius, step = 0.02 * scale;
  double lo = 0.05 * scale;
  const double first = determinant(lo);
  double hi = lo + step;
  while (determinant(hi) * first > 0) {
    lo = hi;
    hi += step;
    if (hi > 30 * scale) throw InputError("no spheroidal mode below 30 V_S / a");
  }
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (determinant(mid) * first > 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

LoveNumbers nongravitating_sphere_love_numbers(double youngs_modulus, double poisson_ratio, double density,
                                               double radius) {
  check_poisson_ratio(poisson_ratio, -1);
  check_positive(youngs_modulus, "Young's modulus");
  check_positive(density, "density");
  check_positive(radius, "radius");
  const auto [lambda, mu] = lame_parameters(youngs_modulus, poisson_ratio);
  const double g = 4 * std::numbers::pi / 3 * density * radius;
  const double stiffness = density * g * radius / mu;
  const double denominator = 19 * lambda + 14 * mu;
  return {stiffness * (5 * lambda + 4 * mu) / denominator, 0.0, stiffness * (3 * lambda + 2 * mu) / (2 * denominator)};
}

double incompressible_love_h2(double shear_modulus, double density, double radius) {
  check_positive(shear_modulus, "shear modulus");
  check_positive(density, "density");
  check_positive(radius, "radius");
  const double g = 4 * std::numbers::pi / 3 * density * radius;
  return 2.5 / (1 + 19 * shear_modulus / (2 * density * g * radius));
}

double incompressible_love_l2(double shear_modulus, double density, double radius) {
  return 0.3 * incompressible_love_h2(shear_modulus, density, radius);
}

double plate_sinusoidal_deflection(double load_amplitude, double wavenumber, double flexural_rigidity) {
  check_positive(wavenumber, "wavenumber");
  check_positive(flexural_rigidity, "flexural rigidity");
  return load_amplitude / (flexural_rigidity * std::pow(wavenumber, 4));
}

double layered_sphere_compression(const std::vector<ElasticLayer>& layers) {
  if (layers.empty()) throw InputError("layered sphere: no layer");
  // (A, B) of the current layer, up to a common factor: B = 0 at the centre.
  double a = 1, b = 0, inner = 0;
  double bulk = 0, shear = 0;
  for (std::size_t n = 0; n < layers.size(); ++n) {
    const ElasticLayer& layer = layers[n];
    if (!(layer.outer_radius > inner) || !(layer.youngs_modulus > 0) || !(layer.poisson_ratio > -1) ||
        !(layer.poisson_ratio < 0.5))
      throw InputError(fmt::format("layered sphere: layer {} has outer radius {}, E {}, nu {}", n, layer.outer_radius,
                                   layer.youngs_modulus, layer.poisson_ratio));
    const double next_bulk = layer.youngs_modulus / (3 * (1 - 2 * layer.poisson_ratio));
    const double next_shear = layer.youngs_modulus / (2 * (1 + layer.poisson_ratio));
    if (n > 0) {
      // At r = inner: u / r = A + B / r^3 and sigma_rr = 3 K A - 4 mu B / r^3 carry over.
      const double r3 = inner * inner * inner;
      const double strain = a + b / r3, stress = 3 * bulk * a - 4 * shear * b / r3;
      // Solve A' + B'/r3 = strain, 3 K' A' - 4 mu' B'/r3 = stress.
      const double b_over_r3 = (3 * next_bulk * strain - stress) / (3 * next_bulk + 4 * next_shear);
      a = strain - b_over_r3;
      b = b_over_r3 * r3;
    }
    bulk = next_bulk;
    shear = next_shear;
    inner = layer.outer_radius;
  }
  const double r3 = inner * inner * inner;
  const double strain = a + b / r3, stress = 3 * bulk * a - 4 * shear * b / r3;
  return strain / stress;  // u/a = -c p and sigma_rr = -p, both per the common factor
}

}  // namespace tidalcrust
