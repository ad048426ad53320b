#include "physics/two_body_orbit.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "base/errors.hpp"
#include "base/invariant.hpp"
#include "base/portable_math.hpp"

namespace tidalcrust {
namespace {

constexpr double pi = std::numbers::pi;

/// x - sin x (sign = -1) or sinh x - x (sign = +1) without cancellation for small x: the
/// Taylor series x^3/3! + sign x^5/5! + x^7/7! + sign x^9/9! ... for |x| < 0.5 (to x^17: the
/// first omitted term is below 1e-18 of the sum).
double odd_remainder(double x, double sign, bool portable) {
  if (std::abs(x) >= 0.5)
    return sign < 0 ? x - portable_math::sin(x, portable) : portable_math::sinh(x, portable) - x;
  const double x2 = x * x;
  double term = x * x2 / 6.0;  // x^3/3!
  double sum = term;
  for (int k = 2; k <= 8; ++k) {
    term *= sign * x2 / ((2.0 * k) * (2.0 * k + 1.0));
    sum += term;
  }
  return sum;
}

/// Kepler's equation in a form without cancellation near e = 1:
/// elliptic  M = (1-e) E + e (E - sin E),   hyperbolic  M = (e-1) H + e (sinh H - H).
double kepler_mean_anomaly(double x, double e, OrbitType type, bool portable) {
  if (type == OrbitType::elliptic) return (1.0 - e) * x + e * odd_remainder(x, -1.0, portable);
  return (e - 1.0) * x + e * odd_remainder(x, +1.0, portable);
}

/// d M / d x: (1-e) + e (1 - cos E) = (1-e) + 2 e sin^2(E/2), or (e-1) + 2 e sinh^2(H/2).
double kepler_derivative(double x, double e, OrbitType type, bool portable) {
  if (type == OrbitType::elliptic) {
    const double s = portable_math::sin(0.5 * x, portable);
    return (1.0 - e) + 2.0 * e * s * s;
  }
  const double s = portable_math::sinh(0.5 * x, portable);
  return (e - 1.0) + 2.0 * e * s * s;
}

/// Solves kepler_mean_anomaly(x) = M >= 0 for x in [lo, hi] (the function is increasing):
/// Newton's method, falling back to bisection whenever a step leaves the bracket.
double solve_kepler(double M, double e, OrbitType type, double lo, double hi, bool portable) {
  if (M == 0) return 0;
  double x = 0.5 * (lo + hi);
  for (int iter = 0; iter < 200; ++iter) {
    const double residual = kepler_mean_anomaly(x, e, type, portable) - M;
    if (residual == 0) return x;
    if (residual > 0) hi = x;
    else lo = x;
    double next = x - residual / kepler_derivative(x, e, type, portable);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - x) <= 4.0 * std::numeric_limits<double>::epsilon() * std::abs(next)) return next;
    x = next;
  }
  return x;
}

}  // namespace

const char* orbit_type_name(OrbitType type) {
  switch (type) {
    case OrbitType::elliptic: return "elliptic";
    case OrbitType::parabolic: return "parabolic";
    case OrbitType::hyperbolic: return "hyperbolic";
  }
  return "unknown";
}

TwoBodyOrbit::TwoBodyOrbit(double mu, double pericenter, double pericenter_speed, double parabolic_tolerance,
                           bool portable)
    : mu_(mu), q_(pericenter), vq_(pericenter_speed), portable_(portable) {
  if (!std::isfinite(mu) || mu <= 0)
    throw InputError(fmt::format("two-body orbit: mu = G (M + M2) must be a finite number > 0, got {}", mu));
  if (!std::isfinite(pericenter) || pericenter <= 0)
    throw InputError(fmt::format("two-body orbit: pericenter q must be a finite number > 0, got {}", pericenter));
  if (!std::isfinite(pericenter_speed) || pericenter_speed <= 0)
    throw InputError(fmt::format("two-body orbit: pericenter speed V_q must be a finite number > 0, got {}",
                                 pericenter_speed));
  e_ = q_ * vq_ * vq_ / mu_ - 1.0;
  if (std::abs(e_ - 1.0) <= parabolic_tolerance) type_ = OrbitType::parabolic;
  else type_ = e_ < 1.0 ? OrbitType::elliptic : OrbitType::hyperbolic;
}

double TwoBodyOrbit::apocenter() const {
  if (type_ != OrbitType::elliptic) return std::numeric_limits<double>::infinity();
  return q_ * (1.0 + e_) / (1.0 - e_);
}

double TwoBodyOrbit::period() const {
  if (type_ != OrbitType::elliptic) return std::numeric_limits<double>::infinity();
  const double a = q_ / (1.0 - e_);
  return 2.0 * pi * std::sqrt(a * a * a / mu_);
}

double TwoBodyOrbit::true_anomaly_at_distance(double r, OrbitBranch branch) const {
  if (!std::isfinite(r) || r < q_)
    throw InputError(fmt::format("two-body orbit: distance r = {} is inside the pericenter q = {}", r, q_));
  if (r > apocenter())
    throw InputError(fmt::format(
        "two-body orbit: distance r = {} is beyond the apocenter {} of this elliptic orbit (e = {})", r,
        apocenter(), e_));
  double f = 0;
  if (r > q_) {
    // tan^2(f/2) = (1+e)(r-q) / ((1+e) q - (1-e) r): no cancellation near pericenter or e = 1.
    const double numerator = (1.0 + e_) * (r - q_);
    const double denominator = std::max(0.0, (1.0 + e_) * q_ - (1.0 - e_) * r);
    f = denominator > 0 ? 2.0 * portable_math::atan(std::sqrt(numerator / denominator), portable_) : pi;
  }
  return branch == OrbitBranch::incoming ? -f : f;
}

RelativeState TwoBodyOrbit::state_at_true_anomaly(double f) const {
  const double c = portable_math::cos(f, portable_), s = portable_math::sin(f, portable_);
  const double r = q_ * (1.0 + e_) / (1.0 + e_ * c);
  const double v_scale = mu_ / specific_angular_momentum();
  // Pericenter direction P = +y, direction of motion at pericenter Q = -x.
  return {Vec3(-r * s, r * c, 0.0), Vec3(-v_scale * (e_ + c), -v_scale * s, 0.0)};
}

RelativeState TwoBodyOrbit::state_at_distance(double r, OrbitBranch branch) const {
  return state_at_true_anomaly(true_anomaly_at_distance(r, branch));
}

double TwoBodyOrbit::time_from_half_tangent(double D) const {
  if (type_ == OrbitType::parabolic) {
    // Barker's equation: t = sqrt(2 q^3 / mu) (D + D^3/3).
    return std::sqrt(2.0 * q_ * q_ * q_ / mu_) * (D + D * D * D / 3.0);
  }
  const double a = q_ / std::abs(1.0 - e_);  // |semi-major axis|
  const double time_unit = std::sqrt(a * a * a / mu_);
  if (type_ == OrbitType::elliptic) {
    const double E = 2.0 * portable_math::atan(std::sqrt((1.0 - e_) / (1.0 + e_)) * D, portable_);
    return kepler_mean_anomaly(E, e_, type_, portable_) * time_unit;
  }
  const double tanh_half = std::sqrt((e_ - 1.0) / (e_ + 1.0)) * D;
  TIDALCRUST_ASSERT(std::abs(tanh_half) < 1.0, "two-body orbit: true anomaly beyond the hyperbolic asymptote");
  const double H = 2.0 * std::atanh(tanh_half);
  return kepler_mean_anomaly(H, e_, type_, portable_) * time_unit;
}

double TwoBodyOrbit::time_from_pericenter(double f) const {
  TIDALCRUST_ASSERT(std::abs(f) <= pi, "two-body orbit: |true anomaly| must be <= pi");
  return time_from_half_tangent(portable_math::tan(0.5 * f, portable_));
}

double TwoBodyOrbit::time_to_pericenter(double r) const {
  return -time_from_pericenter(true_anomaly_at_distance(r, OrbitBranch::incoming));
}

double TwoBodyOrbit::half_tangent_at_time(double t) const {
  const double sign = t < 0 ? -1.0 : 1.0;
  if (type_ == OrbitType::parabolic) {
    // D^3 + 3 D = 3 A has the one real root D = Y - 1/Y = 3 A / (Y^2 + 1 + Y^-2),
    // Y^3 = 3A/2 + sqrt(9A^2/4 + 1); the second form has no cancellation for small A.
    const double A = std::abs(t) / std::sqrt(2.0 * q_ * q_ * q_ / mu_);
    const double Y = portable_math::cbrt(1.5 * A + std::sqrt(2.25 * A * A + 1.0), portable_);
    return sign * 3.0 * A / (Y * Y + 1.0 + 1.0 / (Y * Y));
  }
  const double a = q_ / std::abs(1.0 - e_);
  const double mean_motion = std::sqrt(mu_ / (a * a * a));
  if (type_ == OrbitType::elliptic) {
    // The state repeats every period: reduce the mean anomaly to [-pi, pi].
    double M = mean_motion * t;
    M -= 2.0 * pi * std::nearbyint(M / (2.0 * pi));
    const double E = solve_kepler(std::abs(M), e_, type_, 0.0, pi, portable_);
    return (M < 0 ? -1.0 : 1.0) * std::sqrt((1.0 + e_) / (1.0 - e_)) * portable_math::tan(0.5 * E, portable_);
  }
  const double M = mean_motion * std::abs(t);
  double hi = 1.0;
  while (kepler_mean_anomaly(hi, e_, type_, portable_) < M) hi *= 2.0;
  const double H = solve_kepler(M, e_, type_, 0.0, hi, portable_);
  return sign * std::sqrt((e_ + 1.0) / (e_ - 1.0)) * std::tanh(0.5 * H);
}

RelativeState TwoBodyOrbit::state_at_time(double t) const {
  TIDALCRUST_ASSERT(std::isfinite(t), "two-body orbit: time must be finite");
  return state_at_true_anomaly(2.0 * portable_math::atan(half_tangent_at_time(t), portable_));
}

TwoBodyOrbit perturber_orbit(double perturber_mass, double pericenter, double pericenter_speed, bool portable) {
  if (!std::isfinite(perturber_mass) || perturber_mass < 0)
    throw InputError(fmt::format("two-body orbit: perturber mass M2 must be a finite number >= 0, got {}",
                                 perturber_mass));
  return TwoBodyOrbit(1.0 + perturber_mass, pericenter, pericenter_speed, TwoBodyOrbit::default_parabolic_tolerance,
                      portable);
}

EncounterStart encounter_start(const TwoBodyOrbit& orbit, double r_start) {
  EncounterStart start;
  start.relative = orbit.state_at_distance(r_start, OrbitBranch::incoming);
  start.time_to_pericenter = orbit.time_to_pericenter(r_start);
  return start;
}

}  // namespace tidalcrust
