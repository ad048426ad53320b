#include "analysis/tidal_response.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "analysis/elastic_validation.hpp"
#include "base/errors.hpp"
#include "forces/force_field.hpp"
#include "integrate/leapfrog.hpp"
#include "io/progress.hpp"
#include "io/stop_signal.hpp"
#include "model/center_of_mass.hpp"

namespace tidalcrust {

namespace {

constexpr double pi = std::numbers::pi;
constexpr double degree = pi / 180;

bool is_shell(const Body& body, std::size_t i) { return body.species[i] == static_cast<std::uint8_t>(Species::shell); }

/// Displacement of particle i: (plus - minus)/2, or plus - rest, each about its centre of mass.
struct Displacements {
  const State& rest;
  const State& plus;
  const State* minus;
  Vec3 c_rest, c_plus, c_minus;
  Displacements(const Body& body, const State& r, const State& p, const State* m)
      : rest(r), plus(p), minus(m), c_rest(body_center_of_mass(body, r)), c_plus(body_center_of_mass(body, p)),
        c_minus(m ? body_center_of_mass(body, *m) : Vec3::Zero()) {}
  Vec3 at_rest(std::size_t i) const { return vec3_at(rest.position, i) - c_rest; }
  Vec3 of(std::size_t i) const {
    const Vec3 p = vec3_at(plus.position, i) - c_plus;
    if (minus) return 0.5 * (p - (vec3_at(minus->position, i) - c_minus));
    return p - at_rest(i);
  }
};

/// The continuum surface displacement (h W/g r_hat + l grad W/g, g = 1/r^2) per unit eps at x.
Vec3 continuum_displacement(const Vec3& x, double h2, double l2) {
  const double r = x.norm();
  const Vec3 rhat = x / r;
  const double c = rhat.z();
  // theta_hat = (cos theta cos phi, cos theta sin phi, -sin theta) = (c rhat - z_hat)/sin theta;
  // dP2/dtheta theta_hat = -3 c sin theta theta_hat = -3 c (c rhat - z_hat).
  const Vec3 tangential = -3 * c * (c * rhat - Vec3(0, 0, 1));
  return h2 * r * r * r * r * 0.5 * (3 * c * c - 1) * rhat + l2 * r * r * r * tangential;
}

/// Angle from the nearer end of the z axis, and the squared cosine of the angle between the unit
/// vector e and the meridian there.
struct SpringPlace {
  double gamma = 0;
  double meridional_weight = 0;  ///< (e . psi_hat)^2
  double azimuthal_weight = 0;   ///< (e . lambda_hat)^2
};
SpringPlace place_of(const Vec3& midpoint, const Vec3& e) {
  const Vec3 rhat = midpoint.normalized();
  SpringPlace p;
  p.gamma = std::acos(std::min(1.0, std::abs(rhat.z())));
  const Vec3 azimuth = Vec3(0, 0, 1).cross(rhat);
  if (azimuth.norm() < 1e-12) return p;  // on the axis: no meridian
  const Vec3 lambda_hat = azimuth.normalized();
  const Vec3 psi_hat = lambda_hat.cross(rhat);
  p.meridional_weight = std::pow(e.dot(psi_hat), 2);
  p.azimuthal_weight = std::pow(e.dot(lambda_hat), 2);
  return p;
}

/// Least squares of strain = A m + B a over the given samples (m, a the weights).
std::array<double, 2> fit_strain_tensor(const std::vector<std::array<double, 3>>& samples) {
  Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();
  Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
  for (const auto& [m, a, strain] : samples) {
    const Eigen::Vector2d basis(m, a);
    normal += basis * basis.transpose();
    rhs += basis * strain;
  }
  if (std::abs(normal.determinant()) < 1e-12 * std::max(1.0, normal.squaredNorm())) return {0, 0};
  const Eigen::Vector2d x = normal.ldlt().solve(rhs);
  return {x[0], x[1]};
}

double p2_signal(const Body& body, const State& rest, const State& plus, const State& minus) {
  return fit_degree_two_displacement(body, rest, plus, &minus, 1.0).h2;
}

}  // namespace

DegreeTwoFit fit_degree_two_displacement(const Body& body, const State& rest, const State& plus, const State* minus,
                                         double eps) {
  const Displacements d(body, rest, plus, minus);
  Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();
  Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
  double tangential_num = 0, tangential_den = 0, azimuthal = 0, radius = 0;
  std::int64_t count = 0;
  for (std::size_t i = 0; i < body.particle_count(); ++i) {
    if (!is_shell(body, i)) continue;
    const Vec3 x = d.at_rest(i);
    const double r = x.norm();
    const Vec3 rhat = x / r;
    const double c = rhat.z();
    const Vec3 u = d.of(i);
    const Eigen::Vector2d basis(1.0, eps * r * r * r * r * 0.5 * (3 * c * c - 1));
    normal += basis * basis.transpose();
    rhs += basis * u.dot(rhat);
    // u_theta basis eps r^3 dP2/dtheta theta_hat, written without theta_hat (continuum_displacement).
    const Vec3 b = eps * r * r * r * (-3 * c) * (c * rhat - Vec3(0, 0, 1));
    tangential_num += u.dot(b);
    tangential_den += b.squaredNorm();
    const Vec3 azimuth = Vec3(0, 0, 1).cross(rhat);
    if (azimuth.norm() > 1e-12) azimuthal += std::pow(u.dot(azimuth.normalized()) / eps, 2);
    radius += r;
    ++count;
  }
  if (count == 0) throw InputError("the Love-number fit needs a shell");
  const Eigen::Vector2d x = normal.ldlt().solve(rhs);
  DegreeTwoFit fit;
  fit.uniform = x[0];
  fit.h2 = x[1];
  fit.l2 = tangential_num / tangential_den;
  fit.mean_radius = radius / static_cast<double>(count);
  fit.rms_azimuthal = std::sqrt(azimuthal / static_cast<double>(count));
  return fit;
}

SurfaceStrain continuum_surface_strain(double h2, double l2, double gamma) {
  const double c = std::cos(gamma);
  const double p2 = 0.5 * (3 * c * c - 1);
  return {h2 * p2 - 3 * l2 * std::cos(2 * gamma), h2 * p2 - 3 * l2 * c * c};
}

TideResult measure_tide(const Checkpoint& relaxed, const Config& config, const BodyMaterial& material,
                        const LoveNumbers& theory, double surface_displacement, double drag, double duration,
                        bool progress) {
  const Body& body = relaxed.body;
  if (body.count_species(Species::shell) == 0) throw InputError("--measure tide needs a body with a crust");
  TideResult r;
  r.theory = theory;
  r.tidal_strength = surface_displacement / theory.h;
  const double omega_lamb = 2 * pi / lamb_breathing_period(material.youngs_modulus, material.poisson_ratio,
                                                           material.density, material.radius);
  r.drag = drag > 0 ? drag : omega_lamb;
  r.duration = duration > 0 ? duration : std::max(3.0, 30 / omega_lamb);
  State rest = relaxed.state;
  std::fill(rest.velocity.begin(), rest.velocity.end(), 0.0);
  const Vec3 center = body_center_of_mass(body, rest);
  const double dt = relaxed.stage.clock.dt;
  const std::int64_t steps = step_count(r.duration, dt);
  const std::int64_t early = 2 * steps / 3;
  ForceField forces(body, force_options(config, 0.0));
  r.plus = rest;
  r.minus = rest;
  const double eps = r.tidal_strength;
  const StepClock clock{rest.time, rest.step, dt};
  // Progress over the four runs (+eps and -eps, to 2/3 and on to the end): 2 * steps in all.
  std::optional<ProgressReporter> line;
  if (progress) line.emplace("validate: tide", 0, 0, 2 * steps, std::nullopt);
  std::int64_t before = 0;
  const auto run = [&](State& state, double strength, std::int64_t count) {
    relax_in_tidal_field(forces, state, center, strength, r.drag, clock, count,
                         [&](std::int64_t done) { if (line) line->update(before + done); });
    before += count;
  };
  run(r.plus, eps, early);
  run(r.minus, -eps, early);
  r.early_fit = fit_degree_two_displacement(body, rest, r.plus, &r.minus, eps);
  run(r.plus, eps, steps - early);
  run(r.minus, -eps, steps - early);
  if (line) line->finish(before);
  r.fit = fit_degree_two_displacement(body, rest, r.plus, &r.minus, eps);

  // Every intact crust spring: measured and continuum strain per unit eps.
  const Displacements d(body, rest, r.plus, &r.minus);
  const int bands = 15;
  std::vector<std::vector<std::array<double, 3>>> measured_in(bands), theory_in(bands);
  std::vector<std::array<double, 3>> peak_measured, peak_theory;
  double sub_measured = 0, sub_theory = 0;
  std::int64_t sub_count = 0;
  std::vector<double> own;
  for (std::size_t s = 0; s < body.spring_count(); ++s) {
    if (body.spring_kind[s] != static_cast<std::uint8_t>(SpringKind::shell) || relaxed.state.springs.failed[s]) continue;
    const auto a = static_cast<std::size_t>(body.springs[s][0]), b = static_cast<std::size_t>(body.springs[s][1]);
    const Vec3 xa = d.at_rest(a), xb = d.at_rest(b);
    const Vec3 chord = xb - xa;
    const double length = chord.norm();
    const double plus_length = (vec3_at(r.plus.position, b) - vec3_at(r.plus.position, a)).norm();
    const double minus_length = (vec3_at(r.minus.position, b) - vec3_at(r.minus.position, a)).norm();
    const double strain = (plus_length - minus_length) / (2 * length * eps);
    const auto chord_strain = [&](double h, double l) {
      return (continuum_displacement(xb, h, l) - continuum_displacement(xa, h, l)).dot(chord) / (length * length);
    };
    const double expected = chord_strain(theory.h, theory.l);
    const SpringPlace place = place_of(0.5 * (xa + xb), chord / length);
    r.spring_gamma.push_back(place.gamma / degree);
    r.spring_strain.push_back(strain);
    r.spring_theory.push_back(expected);
    own.push_back(chord_strain(r.fit.h2, r.fit.l2));
    const int band = std::min(bands - 1, static_cast<int>(place.gamma / (90 * degree) * bands));
    measured_in[band].push_back({place.meridional_weight, place.azimuthal_weight, strain});
    theory_in[band].push_back({place.meridional_weight, place.azimuthal_weight, expected});
    if (place.gamma >= 75 * degree) {
      peak_measured.push_back({place.meridional_weight, place.azimuthal_weight, strain});
      peak_theory.push_back({place.meridional_weight, place.azimuthal_weight, expected});
    }
    if (place.gamma < 15 * degree) sub_measured += strain, sub_theory += expected, ++sub_count;
  }
  r.springs = static_cast<std::int64_t>(r.spring_strain.size());
  if (r.springs < 2) throw InputError("--measure tide: the crust has fewer than two intact springs");
  const auto compare = [&](const std::vector<double>& m, const std::vector<double>& t, double& correlation,
                           double& slope, double* rms) {
    const auto n = static_cast<double>(m.size());
    double mm = 0, mt = 0, tt = 0, sm = 0, st = 0, residual = 0;
    for (std::size_t i = 0; i < m.size(); ++i) {
      mm += m[i] * m[i], mt += m[i] * t[i], tt += t[i] * t[i], sm += m[i], st += t[i];
      residual += (m[i] - t[i]) * (m[i] - t[i]);
    }
    correlation = (mt - sm * st / n) / std::sqrt((mm - sm * sm / n) * (tt - st * st / n));
    slope = mt / tt;
    if (rms) *rms = std::sqrt(residual / tt);
  };
  compare(r.spring_strain, r.spring_theory, r.correlation, r.slope, &r.rms_residual);
  compare(r.spring_strain, own, r.own_correlation, r.own_slope, nullptr);
  r.ratio = strain_ratio_spread(r.spring_strain, r.spring_theory);
  for (int band = 0; band < bands; ++band) {
    TidalStrainBin bin;
    bin.gamma_low = 90.0 * band / bands;
    bin.gamma_high = 90.0 * (band + 1) / bands;
    bin.springs = static_cast<std::int64_t>(measured_in[band].size());
    const auto m = fit_strain_tensor(measured_in[band]), t = fit_strain_tensor(theory_in[band]);
    bin.measured_meridional = m[0], bin.measured_azimuthal = m[1];
    bin.theory_meridional = t[0], bin.theory_azimuthal = t[1];
    r.bins.push_back(bin);
  }
  r.peak_tension = fit_strain_tensor(peak_measured)[0];
  r.theory_peak_tension = fit_strain_tensor(peak_theory)[0];
  if (sub_count > 0) {
    r.subsatellite_strain = sub_measured / static_cast<double>(sub_count);
    r.theory_subsatellite_strain = sub_theory / static_cast<double>(sub_count);
  }
  return r;
}

StrainRatioSpread strain_ratio_spread(const std::vector<double>& measured, const std::vector<double>& theory,
                                      double floor) {
  if (measured.size() != theory.size())
    throw InputError("strain_ratio_spread: measured and continuum strains differ in length");
  double tt = 0;
  for (double t : theory) tt += t * t;
  const double cut = floor * std::sqrt(tt / static_cast<double>(std::max<std::size_t>(theory.size(), 1)));
  std::vector<double> ratios;
  for (std::size_t i = 0; i < theory.size(); ++i)
    if (std::abs(theory[i]) >= cut && theory[i] != 0) ratios.push_back(measured[i] / theory[i]);
  if (ratios.empty()) throw InputError("strain_ratio_spread: no spring with a continuum strain to compare");
  std::sort(ratios.begin(), ratios.end());
  const auto percentile = [&](double p) {
    const double at = p * static_cast<double>(ratios.size() - 1);
    const auto below = static_cast<std::size_t>(std::floor(at));
    const std::size_t above = std::min(below + 1, ratios.size() - 1);
    return ratios[below] + (at - static_cast<double>(below)) * (ratios[above] - ratios[below]);
  };
  return {percentile(0.5), 0.5 * (percentile(0.84) - percentile(0.16)), static_cast<std::int64_t>(ratios.size())};
}

RingdownResult measure_ringdown(const Checkpoint& relaxed, const Config& config, const TideResult& tide,
                                double expected_omega, double duration, bool progress) {
  const Body& body = relaxed.body;
  RingdownResult r;
  State plus = tide.plus, minus = tide.minus;
  ForceField plus_forces(body, force_options(config, 0.0)), minus_forces(body, force_options(config, 0.0));
  const StepClock clock{plus.time, plus.step, relaxed.stage.clock.dt};
  Leapfrog plus_step(plus_forces, clock), minus_step(minus_forces, clock);
  const std::int64_t steps = step_count(duration, clock.dt);
  std::optional<ProgressReporter> line;
  if (progress) line.emplace("validate: ring-down", 0, 0, steps, std::nullopt);
  for (std::int64_t s = 0; s <= steps; ++s) {
    throw_if_stopped("the ring-down measurement");
    if (s > 0) plus_step.step(plus), minus_step.step(minus);
    if (line) line->update(s);
    r.time.push_back(static_cast<double>(s) * clock.dt);
    r.signal.push_back(p2_signal(body, relaxed.state, plus, minus));
  }
  if (line) line->finish(steps);
  r.initial = r.signal.front();
  const double omega = dominant_frequency(r.time, r.signal, 0.5 * expected_omega, 2 * expected_omega);
  r.period = 2 * pi / omega;
  r.amplitude = sinusoid_amplitude(r.time, r.signal, omega);
  return r;
}

}  // namespace tidalcrust
