#include "physics/hydrostatic_stretch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <utility>
#include <vector>

#include "base/errors.hpp"
#include "base/vec3.hpp"
#include "forces/force_field.hpp"
#include "model/center_of_mass.hpp"
#include "model/derived_quantities.hpp"
#include "physics/hydrostatic_pressure.hpp"

namespace tidalcrust {
namespace {


/// Rest lengths may at most double: a body that needs more is not held by its springs.
constexpr double largest_stretch_factor = 2.0;
/// Strengthening no more than this: a stiffer core would need a much smaller time step.
constexpr double largest_strengthening = 100.0;

/// The surface whose mean radial acceleration the stretch zeroes: the shell nodes, or for a
/// body without shell the interior nodes within d_I/2 of the outermost one (those that lack
/// outward neighbours, like a surface).
std::vector<std::size_t> surface_nodes(const Body& body, const State& state, const Vec3& centre,
                                       double spring_distance) {
  std::vector<std::size_t> nodes;
  for (std::size_t i = 0; i < body.particle_count(); ++i)
    if (body.species[i] == static_cast<std::uint8_t>(Species::shell)) nodes.push_back(i);
  if (!nodes.empty()) return nodes;
  double r_max = 0;
  for (std::size_t i = 0; i < body.particle_count(); ++i)
    r_max = std::max(r_max, (vec3_at(state.position, i) - centre).norm());
  for (std::size_t i = 0; i < body.particle_count(); ++i)
    if ((vec3_at(state.position, i) - centre).norm() > r_max - 0.5 * spring_distance) nodes.push_back(i);
  return nodes;
}

/// The balance of the body at rest at its built positions with trial springs.
struct Balance {
  double surface = 0;  ///< mean a . r_hat over the surface nodes, G M/R^2
  /// sum m (x - c) . a / sum m |x - c|, G M/R^2: half the initial second derivative of the
  /// moment of inertia about the centre c, per unit sum m r. Zero: no breathing drive.
  double virial = 0;
};

/// The body at rest at its built positions with trial rest lengths and stiffnesses.
class StretchTrial {
 public:
  StretchTrial(const Body& body, const State& built, const Config& config)
      : body_(body),
        base_(built.springs),
        cross_compression_(config.stretch.cross_compression),
        forces_(body, force_options(config, 0.0)),  // the body is at rest: no damping
        state_(built),
        centre_(body_center_of_mass(body, built)),
        surface_(surface_nodes(body, built, centre_, config.interior.spring_distance)) {
    std::fill(state_.velocity.begin(), state_.velocity.end(), 0.0);
    state_.perturber = Perturber{};
    if (surface_.empty()) throw InputError("stretch: the body has no particles");
  }

  /// Rest lengths f L_built (cross springs (1 + cross_compression) times longer: slightly
  /// compressed; interior springs their own factor instead of f once hold_interior() was called)
  /// and stiffnesses k_built times `multiplier`.
  void apply(double factor, const std::vector<double>& multiplier, SpringState& springs) const {
    for (std::size_t n = 0; n < body_.spring_count(); ++n) {
      const auto kind = static_cast<SpringKind>(body_.spring_kind[n]);
      const double f = kind == SpringKind::interior && !interior_factor_.empty() ? interior_factor_[n] : factor;
      springs.rest_length[n] = f * base_.rest_length[n] * (kind == SpringKind::cross ? 1.0 + cross_compression_ : 1.0);
      springs.stiffness[n] = base_.stiffness[n] * multiplier[n];
    }
  }

  /// From now on interior spring n gets rest length factor[n] L_built whatever f is [Ns].
  void hold_interior(std::vector<double> factor) { interior_factor_ = std::move(factor); }

  /// Accelerations at rest (gravity + springs + hinges) for stretch factor f and stiffness
  /// multipliers, reduced to the two balances the stage zeroes.
  Balance balance(double factor, const std::vector<double>& multiplier) {
    apply(factor, multiplier, state_.springs);
    forces_.compute(state_, acc_);
    Balance b;
    for (std::size_t i : surface_) {
      const Vec3 r_hat = (vec3_at(state_.position, i) - centre_).normalized();
      b.surface += vec3_at(acc_.body, i).dot(r_hat);
    }
    b.surface /= static_cast<double>(surface_.size());
    double moment = 0;
    for (std::size_t i = 0; i < body_.particle_count(); ++i) {
      const Vec3 r = vec3_at(state_.position, i) - centre_;
      b.virial += body_.mass[i] * r.dot(vec3_at(acc_.body, i));
      moment += body_.mass[i] * r.norm();
    }
    b.virial /= moment;
    return b;
  }

  const Vec3& centre() const { return centre_; }

 private:
  const Body& body_;
  const SpringState& base_;
  double cross_compression_;
  ForceField forces_;
  State state_;
  Accelerations acc_;
  Vec3 centre_;
  std::vector<std::size_t> surface_;
  std::vector<double> interior_factor_;  ///< [Ns] or empty: interior springs follow f
};

/// Counts force evaluations against stretch.max_iterations.
class EvaluationBudget {
 public:
  EvaluationBudget(std::int64_t limit, double tolerance) : limit_(limit), tolerance_(tolerance) {}
  void spend(const char* what, double x, double residual) {
    if (used_ >= limit_)
      throw SimulationError(fmt::format(
          "stretch: {} not found to |residual| < {} G M/R^2 (stretch.tolerance) within stretch.max_iterations = {} "
          "force evaluations; last residual {:.3g} at {:.9g}",
          what, tolerance_, limit_, residual, x));
    ++used_;
  }
  std::int64_t used() const { return used_; }
  double tolerance() const { return tolerance_; }

 private:
  std::int64_t limit_;
  double tolerance_;
  std::int64_t used_ = 0;
};

struct Root {
  double x = 0;
  double residual = 0;
};

/// Root of an increasing-or-decreasing g inside the bracket [a, b] (g(a), g(b) of opposite
/// signs): Illinois regula falsi, a secant step kept inside the bracket. For linear springs at
/// rest g is linear (or piecewise linear) in the unknown, so it converges in a step or two.
Root illinois(const std::function<double(double)>& g, double a, double ga, double b, double gb,
              EvaluationBudget& budget, const char* what) {
  Root last{b, gb};
  while (std::abs(last.residual) >= budget.tolerance()) {
    budget.spend(what, last.x, last.residual);
    const double c = (a * gb - b * ga) / (gb - ga);
    const double gc = g(c);
    if ((gc < 0) != (gb < 0)) {
      a = b;
      ga = gb;
    } else {
      ga *= 0.5;  // Illinois: keeps the stale end from stalling the secant
    }
    b = c;
    gb = gc;
    last = {c, gc};
  }
  return last;
}

/// The common factor f of all rest lengths that zeroes the mean radial surface acceleration:
/// from f = 1 (built lengths; gravity pulls the surface in, g < 0) the bracket grows by
/// doubling steps, then Illinois.
Root solve_stretch_factor(const std::function<double(double)>& g, EvaluationBudget& budget) {
  const char* what = "stretch factor";
  budget.spend(what, 1, 0);
  double a = 1, ga = g(a);
  if (std::abs(ga) < budget.tolerance()) return {a, ga};
  // An inward pull (ga < 0) needs longer rest lengths: compressed springs push outward.
  const double direction = ga < 0 ? 1.0 : -1.0;
  double step = 0.01, b = 1 + direction * step;
  budget.spend(what, b, ga);
  double gb = g(b);
  while ((gb < 0) == (ga < 0)) {
    if (std::abs(gb) < budget.tolerance()) return {b, gb};
    a = b;
    ga = gb;
    step *= 2;
    b = 1 + direction * step;
    if (b > largest_stretch_factor || b < 1 / largest_stretch_factor)
      throw InputError(fmt::format(
          "stretch: the springs cannot hold the body against self-gravity (the surface still accelerates by "
          "{:.3g} G M/R^2 with rest lengths scaled by {:.3g}); stiffen interior.spring_constant, "
          "shell.spring_constant or cross.spring_constant",
          gb, a));
    budget.spend(what, b, gb);
    gb = g(b);
  }
  return illinois(g, a, ga, b, gb, budget, what);
}

/// Stiffness multipliers of the hydrostatic strengthening: interior spring n gets
/// max(1, P(r_mid)/P_uniform), P the paper's hydrostatic pressure at its midpoint radius and
/// P_uniform the pressure of the uniformly compressed network; shell and cross springs keep 1.
/// `inverse_uniform_pressure` = 1/P_uniform (0: no strengthening).
struct Strengthening {
  std::vector<double> multiplier;  ///< [Ns]
  double largest = 1;
  double inverse_uniform_pressure = 0;
};

Strengthening strengthen(const Body& body, const std::vector<double>& midpoint_pressure,
                         double inverse_uniform_pressure) {
  Strengthening s;
  s.inverse_uniform_pressure = inverse_uniform_pressure;
  s.multiplier.assign(body.spring_count(), 1.0);
  for (std::size_t n = 0; n < body.spring_count(); ++n) {
    if (body.spring_kind[n] != static_cast<std::uint8_t>(SpringKind::interior)) continue;
    s.multiplier[n] = std::max(1.0, midpoint_pressure[n] * inverse_uniform_pressure);
    s.largest = std::max(s.largest, s.multiplier[n]);
  }
  return s;
}

/// P(r) of section 2.3 at every spring's midpoint radius (e_g). With a core (issue 12) the
/// layered body's P(r), and a core spring's value divided by core.modulus_ratio: the even
/// compression presses the stiffer core modulus_ratio times harder, so its springs need that
/// much less strengthening.
std::vector<double> midpoint_pressures(const Body& body, const State& state, const Vec3& centre,
                                       const Config& config) {
  std::vector<double> p(body.spring_count());
  const LayeredSphere layered{config.core.radius.value_or(0.0), config.core.density_ratio.value_or(1.0)};
  for (std::size_t n = 0; n < body.spring_count(); ++n) {
    const Vec3 mid = 0.5 * (vec3_at(state.position, static_cast<std::size_t>(body.springs[n][0])) +
                            vec3_at(state.position, static_cast<std::size_t>(body.springs[n][1])));
    const double r = (mid - centre).norm();
    if (!config.core.present()) {
      p[n] = std::max(0.0, hydrostatic_pressure(r));
      continue;
    }
    p[n] = std::max(0.0, layered.pressure(r));
    if (r < layered.core_radius && body.spring_kind[n] == static_cast<std::uint8_t>(SpringKind::interior))
      p[n] /= config.core.modulus_ratio.value_or(1.0);
  }
  return p;
}

/// Rest-length factors that let every interior spring carry the hydrostatic pressure of the body
/// as built at its own stiffness ("compress"): 1 + P(r_mid) / (2 E) [Ns], P the particle
/// pressure profile (ParticleHydrostaticPressure) at the spring's midpoint radius and E the
/// layer's modulus (the mantle's, core.modulus_ratio times it inside the core), by the virial
/// pressure of an evenly compressed network, 2 E (f - 1) (uniform_network_pressure). Other
/// springs get 1. Unlike strengthening, this leaves every stiffness as built, so the interior's
/// moduli are the material's at any resolution (issue 13: strengthening stiffened the centre
/// 1.6x at level 3 and 3.5x at level 6).
std::vector<double> interior_compression_factors(const Body& body, const State& state, const Vec3& centre,
                                                 const Config& config, double mantle_modulus) {
  std::vector<double> radius(body.particle_count());
  for (std::size_t i = 0; i < body.particle_count(); ++i) radius[i] = (vec3_at(state.position, i) - centre).norm();
  const ParticleHydrostaticPressure pressure(radius, body.mass);
  const double core_radius = config.core.radius.value_or(0.0);
  const double core_modulus = mantle_modulus * config.core.modulus_ratio.value_or(1.0);
  std::vector<double> factor(body.spring_count(), 1.0);
  for (std::size_t n = 0; n < body.spring_count(); ++n) {
    if (body.spring_kind[n] != static_cast<std::uint8_t>(SpringKind::interior)) continue;
    const Vec3 mid = 0.5 * (vec3_at(state.position, static_cast<std::size_t>(body.springs[n][0])) +
                            vec3_at(state.position, static_cast<std::size_t>(body.springs[n][1])));
    const double r = (mid - centre).norm();
    factor[n] = 1 + pressure(r) / (2 * (r < core_radius ? core_modulus : mantle_modulus));
  }
  return factor;
}

/// Young's modulus of eq. 15 over the mantle (interior springs with midpoints outside the core,
/// the volume between core and interior radius); the whole interior without a core.
double mantle_youngs_modulus(const Body& body, const State& state, const Config& config) {
  if (!config.core.present()) return derive_quantities(body, state, config.interior.radius).E_I;
  const double rc = *config.core.radius, ri = config.interior.radius;
  double sum = 0;
  for (std::size_t n = 0; n < body.spring_count(); ++n) {
    if (body.spring_kind[n] != static_cast<std::uint8_t>(SpringKind::interior)) continue;
    const Vec3 mid = 0.5 * (vec3_at(state.position, static_cast<std::size_t>(body.springs[n][0])) +
                            vec3_at(state.position, static_cast<std::size_t>(body.springs[n][1])));
    if (mid.norm() < rc) continue;
    const double length = state.springs.rest_length[n];
    sum += state.springs.stiffness[n] * length * length;
  }
  // network_youngs_modulus (eq. 15) with 6 V rounded as 8 pi (r_I^3 - r_c^3), not 6 (4 pi/3 (...)):
  // the two differ in the last bit for core-T's r_I = 0.897, and its stretch keeps the bits it had.
  return sum / (6.0 * 4.0 / 3.0 * std::numbers::pi * (ri * ri * ri - rc * rc * rc));
}

/// Pressure of the interior network when every spring is compressed by the common factor f
/// (e_g). Each spring then pushes with k L (f - 1), and the virial stress of an isotropic
/// network, P = (1/3V) sum F L = (1/3V) sum k L^2 (f - 1), is 2 E_I (f - 1) with E_I of eq. 15
/// (the bulk modulus of the Poisson-1/4 network is 2 E_I/3 and the volumetric strain
/// 3 (f - 1)). The paper's "P ~ E_I eps" fixes only the order of magnitude; with E_I eps the
/// core would be strengthened twice too much and push the body outward (tests: the stretched
/// body then rings almost as much as the unstretched one).
double uniform_network_pressure(double young_modulus, double factor) { return 2 * young_modulus * (factor - 1); }

}  // namespace

StretchRecord stretch_springs(const Body& body, const State& built, const Config& config, SpringState& stretched) {
  StretchTrial trial(body, built, config);
  const double young_modulus = mantle_youngs_modulus(body, built, config);
  const std::vector<double> pressure = midpoint_pressures(body, built, trial.centre(), config);
  EvaluationBudget budget(config.stretch.max_iterations, config.stretch.tolerance);

  // (a) The common factor with the built stiffnesses.
  Strengthening strengthening = strengthen(body, pressure, 0);
  auto solve_factor = [&] {
    return solve_stretch_factor([&](double f) { return trial.balance(f, strengthening.multiplier).surface; },
                                budget);
  };
  const bool compress = config.stretch.hydrostatic_support == HydrostaticSupport::compress;
  if (compress)  // each interior spring carries its own pressure; f sets only the crust's and cross springs'
    trial.hold_interior(interior_compression_factors(body, built, trial.centre(), config, young_modulus));
  const bool f_moves_forces = !compress || std::any_of(body.spring_kind.begin(), body.spring_kind.end(), [](auto k) {
    return k != static_cast<std::uint8_t>(SpringKind::interior);
  });
  const Root unstrengthened = f_moves_forces ? solve_factor() : Root{1.0, 0.0};
  // (b) Strengthening for the pressure of that compression, then the factor again with the
  // strengthened springs. With a shell the surface nodes carry no interior springs and the
  // factor does not change. Without a shell it drops a little (the stiffer outer interior
  // pushes the surface out); strengthening is not iterated to a fixed point, which for such a
  // body drifts toward f = 1 with ever stiffer springs (the force of a strengthened spring,
  // k P(r)/P_uniform (f - 1) L, no longer depends on f).
  Root factor = unstrengthened;
  if (!compress) {
    const double uniform_pressure = uniform_network_pressure(young_modulus, unstrengthened.x);
    strengthening = strengthen(body, pressure, uniform_pressure > 0 ? 1 / uniform_pressure : 0.0);
    if (strengthening.largest > largest_strengthening)
      throw InputError(fmt::format(
          "stretch: the common compression (stretch factor {:.6g}) is too small for the interior to carry the "
          "hydrostatic pressure: its central springs would have to be {:.3g}x stiffer (limit {}); soften "
          "interior.spring_constant relative to shell.spring_constant and cross.spring_constant",
          unstrengthened.x, strengthening.largest, largest_strengthening));
    factor = solve_factor();
  }
  trial.apply(factor.x, strengthening.multiplier, stretched);
  const Balance final_balance = trial.balance(factor.x, strengthening.multiplier);

  StretchRecord record;
  const double beta = strengthening.inverse_uniform_pressure;
  record.stretch_factor = factor.x;
  record.residual_surface_acceleration = final_balance.surface;
  record.residual_virial_acceleration = final_balance.virial;
  record.iterations = budget.used();
  record.stretch_factor_unstrengthened = unstrengthened.x;
  record.strengthening_max = strengthening.largest;
  record.uniform_pressure = beta > 0 ? 1 / beta : 0.0;
  // P(r) = P_uniform at r^2 = 1 - P_uniform/P(0): springs inside were strengthened.
  record.strengthening_radius = beta > 0 ? std::sqrt(std::max(0.0, 1 - 1 / (beta * hydrostatic_pressure(0)))) : 0.0;
  return record;
}

void set_hydrostatic_liquid_rest_volumes(const Body& body, State& state) {
  const std::size_t n = body.particle_count();
  const auto shell = static_cast<std::uint8_t>(Species::shell);
  const auto liquid = static_cast<std::uint8_t>(Species::liquid);
  const Vec3 centre = body_center_of_mass(body, state);
  std::vector<double> radius(n);
  for (std::size_t i = 0; i < n; ++i) radius[i] = (vec3_at(state.position, i) - centre).norm();
  LiquidPressure layer(body);
  const std::vector<double> volume = layer.volumes(state.position.data());

  // The liquid's density (its particles carry only liquid, V_a of it each), the crust's radius
  // (mean over its nodes) and mass.
  double liquid_mass = 0, liquid_volume = 0, crust_mass = 0, crust_radius = 0;
  std::size_t crust_nodes = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (body.species[i] == liquid) {
      liquid_mass += body.mass[i];
      liquid_volume += volume[i];
    } else if (body.species[i] == shell) {
      crust_mass += body.mass[i];
      crust_radius += radius[i];
      ++crust_nodes;
    }
  }
  const double density = liquid_mass / liquid_volume;
  crust_radius /= static_cast<double>(crust_nodes);

  // g(r) = m(< r)/r^2 of the particles under the crust, piecewise constant m between their radii:
  // depth_pressure(r) = density * integral from r to the crust's radius of g, exactly.
  std::vector<std::pair<double, double>> below;  // (radius, mass), sorted
  for (std::size_t i = 0; i < n; ++i)
    if (body.species[i] != shell) below.emplace_back(radius[i], body.mass[i]);
  std::sort(below.begin(), below.end());
  std::vector<double> enclosed(below.size() + 1, 0.0);  // enclosed[k]: mass of below[0..k)
  for (std::size_t k = 0; k < below.size(); ++k) enclosed[k + 1] = enclosed[k] + below[k].second;
  auto enclosed_mass = [&](double r) {
    const auto k = std::lower_bound(below.begin(), below.end(), std::make_pair(r, 0.0)) - below.begin();
    return enclosed[static_cast<std::size_t>(k)];
  };
  // integral[k] = int from min(r_k, top) to top of g: accumulated from the top down.
  const double top = crust_radius;
  std::vector<double> integral(below.size() + 1, 0.0);
  for (std::size_t k = below.size(); k-- > 0;) {
    const double from = std::min(below[k].first, top);
    const double to = k + 1 < below.size() ? std::min(below[k + 1].first, top) : top;
    integral[k] = integral[k + 1] + enclosed[k + 1] * (1 / from - 1 / to);
  }
  auto depth_pressure = [&](double r) {
    if (r >= top) return 0.0;
    // below[k] is the first particle farther out than r: m(< s) = enclosed[k] on (r, r_k].
    const auto k = static_cast<std::size_t>(std::upper_bound(below.begin(), below.end(), std::make_pair(r, 1e300)) - below.begin());
    const double to = k < below.size() ? std::min(below[k].first, top) : top;
    return density * (enclosed[k] * (1 / r - 1 / to) + integral[k]);
  };

  // Pressure at the top, P_top, so that the liquid carries the crust's weight: every node's
  // pressure P_top + depth_pressure(r) (crust nodes P_top), and the radial push of the layer on the
  // crust nodes, linear in P_top, equal to their weight, m_a g_a with g_a = (m(< r_a) + M_crust/2)
  // / r_a^2 (a node in a thin shell feels half the shell's mass; measured within 0.5% of the
  // direct sum on ocean-L3, docs/ocean.md).
  const double bulk = body.liquid.bulk_modulus;
  auto radial_push_on_crust = [&](const std::vector<double>& pressure) {
    std::vector<double> rest(n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
      if (volume[i] > 0) rest[i] = volume[i] / (1 - pressure[i] / bulk);
    layer.compute(state.position.data(), rest, {}, false);
    double push = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (body.species[i] == shell) {
        const Vec3 r = vec3_at(state.position, i) - centre;
        push += vec3_at(layer.forces(), i).dot(r) / r.norm();
      }
    return push;
  };
  constexpr double unit = 1e-6;  // a small probe pressure (e_g): V0 stays positive for any K
  std::vector<double> pressure(n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    if (volume[i] > 0) pressure[i] = unit;
  const double push_per_pressure = radial_push_on_crust(pressure) / unit;
  for (std::size_t i = 0; i < n; ++i)
    if (volume[i] > 0) pressure[i] = body.species[i] == shell ? 0.0 : depth_pressure(radius[i]);
  const double push_of_depth = radial_push_on_crust(pressure);
  double weight = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (body.species[i] == shell)
      weight += body.mass[i] * (enclosed_mass(radius[i]) + 0.5 * crust_mass) / (radius[i] * radius[i]);
  const double top_pressure = (weight - push_of_depth) / push_per_pressure;
  double deepest = top_pressure;
  for (std::size_t i = 0; i < n; ++i) deepest = std::max(deepest, top_pressure + pressure[i]);
  if (!(deepest < 0.5 * bulk))
    throw InputError(fmt::format("ocean.bulk_modulus = {:.4g} e_g is too small for the ocean's pressure (up to {:.4g} e_g): "
                                 "the liquid would be compressed by more than half",
                                 bulk, deepest));
  state.liquid_rest_volume.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    if (volume[i] > 0) state.liquid_rest_volume[i] = volume[i] / (1 - (top_pressure + pressure[i]) / bulk);
}

}  // namespace tidalcrust
