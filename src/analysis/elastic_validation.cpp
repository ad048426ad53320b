#include "analysis/elastic_validation.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "base/errors.hpp"
#include "forces/force_field.hpp"
#include "forces/hinge_force.hpp"
#include "model/derived_quantities.hpp"
#include "forces/hinge_geometry.hpp"
#include "forces/spring_force.hpp"
#include "integrate/leapfrog.hpp"
#include "io/stop_signal.hpp"
#include "model/center_of_mass.hpp"
#include "physics/continuum_elasticity.hpp"

namespace tidalcrust {

namespace {

constexpr double pi = std::numbers::pi;

Vec3 position_of(const State& state, std::size_t i) {
  return {state.position[3 * i], state.position[3 * i + 1], state.position[3 * i + 2]};
}

/// The relaxed state at rest: velocities zeroed, so that only what a measurement adds moves it.
State state_at_rest(const Checkpoint& relaxed) {
  State state = relaxed.state;
  std::fill(state.velocity.begin(), state.velocity.end(), 0.0);
  return state;
}

/// Mass-weighted mean distance of the particles from the centre of mass, R.
double mean_radius(const Body& body, const State& state) {
  const Vec3 center = body_center_of_mass(body, state);
  double sum = 0, mass = 0;
  for (std::size_t i = 0; i < body.particle_count(); ++i) {
    sum += body.mass[i] * (position_of(state, i) - center).norm();
    mass += body.mass[i];
  }
  return sum / mass;
}

}  // namespace

std::int64_t step_count(double duration, double dt) { return static_cast<std::int64_t>(std::ceil(duration / dt)); }

/// Least-squares fit of s(t) = a cos(w t) + b sin(w t) + c: its amplitude sqrt(a^2 + b^2).
double sinusoid_amplitude(const std::vector<double>& t, const std::vector<double>& s, double omega) {
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < t.size(); ++i) {
    const Eigen::Vector3d basis(std::cos(omega * t[i]), std::sin(omega * t[i]), 1.0);
    normal += basis * basis.transpose();
    rhs += basis * s[i];
  }
  const Eigen::Vector3d x = normal.ldlt().solve(rhs);
  return std::hypot(x[0], x[1]);
}

/// The angular frequency in [low, high] of the best least-squares sinusoid (a scan of 600
/// frequencies, then golden-section refinement around the best).
double dominant_frequency(const std::vector<double>& t, const std::vector<double>& s, double low, double high) {
  const int scan = 600;
  double best = low, best_amplitude = -1;
  for (int i = 0; i <= scan; ++i) {
    const double omega = low + (high - low) * i / scan;
    const double a = sinusoid_amplitude(t, s, omega);
    if (a > best_amplitude) best_amplitude = a, best = omega;
  }
  double lo = best - (high - low) / scan, hi = best + (high - low) / scan;
  const double golden = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 60; ++i) {
    const double m1 = hi - golden * (hi - lo), m2 = lo + golden * (hi - lo);
    if (sinusoid_amplitude(t, s, m1) > sinusoid_amplitude(t, s, m2))
      hi = m2;
    else
      lo = m1;
  }
  return 0.5 * (lo + hi);
}

BodyMaterial body_material(const Checkpoint& relaxed, const Config& config) {
  const DerivedQuantities q = derive_quantities(relaxed.body, relaxed.state, config.interior.radius);
  BodyMaterial m;
  m.youngs_modulus = q.E_I;
  m.p_wave_speed = q.V_IP;
  // A welded body's welded springs (kind cross) restore what the interior network lacks within d_I
  // of its surface, so eq. 15 over the whole interior ball (q.E_I) counts that layer short; its
  // modulus is eq. 15 over the springs deeper than d_I, the region its builder calibrates a
  // [material] body on (bodies/material_body.hpp).
  const double deep_radius = config.interior.radius - config.interior.spring_distance;
  if (config.shell.enabled && config.cross.coupling == CrossCoupling::welded && deep_radius > 0) {
    m.youngs_modulus = inner_network_youngs_modulus(relaxed.body, relaxed.state, deep_radius);
    m.p_wave_speed = p_wave_speed(m.youngs_modulus);
  }
  // R = 1 by the units when a crust makes the surface; an interior-only body (paper-N) ends at
  // its outermost node instead, and its mean density is that of the sphere this bounds.
  m.radius = 1.0;
  if (relaxed.body.count_species(Species::shell) == 0) {
    const Vec3 center = body_center_of_mass(relaxed.body, relaxed.state);
    double outer = 0;
    for (std::size_t i = 0; i < relaxed.body.particle_count(); ++i)
      outer = std::max(outer, (position_of(relaxed.state, i) - center).norm());
    m.radius = outer;
  }
  m.density = 3 / (4 * pi * m.radius * m.radius * m.radius);
  m.shell_spacing = q.L_S;
  m.shell_spring_constant = q.k_S;
  double sum = 0;
  for (double k : relaxed.body.hinge_stiffness) sum += k;
  m.hinge_stiffness = relaxed.body.hinge_count() ? sum / static_cast<double>(relaxed.body.hinge_count()) : 0.0;
  if (!(m.youngs_modulus > 0)) throw InputError("the body has no interior springs: no Young's modulus to validate");
  return m;
}

InteriorModuli measure_interior_moduli(const Checkpoint& relaxed, const BodyMaterial& eq15_material) {
  const Body& body = relaxed.body;
  const State& state = relaxed.state;
  const Vec3 center = body_center_of_mass(body, state);
  std::vector<Vec3> positions(body.particle_count());
  for (std::size_t i = 0; i < body.particle_count(); ++i) positions[i] = position_of(state, i);
  std::vector<NetworkSpring> springs;
  double longest = 0, outer = 0;
  for (std::size_t s = 0; s < body.spring_count(); ++s) {
    if (body.spring_kind[s] != static_cast<std::uint8_t>(SpringKind::interior) || state.springs.failed[s]) continue;
    const auto [i, j] = body.springs[s];
    springs.push_back({i, j, state.springs.rest_length[s], state.springs.stiffness[s]});
    longest = std::max(longest, (positions[i] - positions[j]).norm());
    outer = std::max({outer, (positions[i] - center).norm(), (positions[j] - center).norm()});
  }
  InteriorModuli r;
  r.hold_radius = outer - 0.5 * longest;
  r.measure_radius = r.hold_radius - 0.5 * longest;
  if (springs.empty() || !(r.measure_radius > 0))
    throw InputError(fmt::format(
        "the interior network is too small for its moduli: outermost node {:.3g} R, longest spring {:.3g} R", outer,
        longest));
  r.network = measure_network_moduli(positions, springs, center, r.hold_radius, r.measure_radius);
  std::vector<NetworkSpring> uniform = springs;
  for (auto& s : uniform) s = {s.i, s.j, (positions[s.i] - positions[s.j]).norm(), 1.0};
  r.geometric = measure_network_moduli(positions, uniform, center, r.hold_radius, r.measure_radius);
  r.bulk_factor = r.geometric.relaxed_moduli.bulk / r.geometric.affine_moduli.bulk;
  r.shear_factor = r.geometric.relaxed_moduli.shear / r.geometric.affine_moduli.shear;
  // Eq. 15 with nu = 1/4: lambda = mu = 2 E_I / 5, K_I = 2 E_I / 3.
  const IsotropicModuli body_moduli = isotropic_moduli_from_bulk_shear(
      r.bulk_factor * 2 * eq15_material.youngs_modulus / 3, r.shear_factor * 2 * eq15_material.youngs_modulus / 5);
  r.material = eq15_material;
  r.youngs_factor = body_moduli.youngs / eq15_material.youngs_modulus;
  r.material.youngs_modulus = body_moduli.youngs;
  r.material.poisson_ratio = body_moduli.poisson;
  r.material.p_wave_speed = p_wave_speed(body_moduli.youngs, body_moduli.poisson, eq15_material.density);
  return r;
}

ContinuumPrediction continuum_prediction(const BodyMaterial& material, double path_length) {
  const double E = material.youngs_modulus, nu = material.poisson_ratio, rho = material.density;
  ContinuumPrediction p;
  p.breathing_period = lamb_breathing_period(E, nu, rho, material.radius);
  p.self_gravitating_breathing_period = self_gravitating_breathing_period(E, nu, rho, material.radius);
  p.h2 = homogeneous_sphere_love_numbers(2, E, nu, rho, material.radius).h;
  p.p_wave_time = path_length / p_wave_speed(E, nu, rho);
  return p;
}

BreathingResult measure_breathing(const Checkpoint& relaxed, const Config& config, const BodyMaterial& material,
                                  double amplitude, double periods) {
  BreathingResult r;
  r.lamb_period = lamb_breathing_period(material.youngs_modulus, material.poisson_ratio, material.density,
                                        material.radius);
  r.self_gravitating_period = self_gravitating_breathing_period(material.youngs_modulus, material.poisson_ratio,
                                                                material.density, material.radius);
  const Body& body = relaxed.body;
  State reference = state_at_rest(relaxed);
  State scaled = reference;
  const Vec3 center = body_center_of_mass(body, reference);
  for (std::size_t i = 0; i < body.particle_count(); ++i)
    for (int c = 0; c < 3; ++c)
      scaled.position[3 * i + c] = center[c] + (1 + amplitude) * (reference.position[3 * i + c] - center[c]);

  ForceField reference_forces(body, force_options(config, 0.0));
  ForceField scaled_forces(body, force_options(config, 0.0));
  const StepClock clock{reference.time, reference.step, relaxed.stage.clock.dt};
  Leapfrog reference_step(reference_forces, clock), scaled_step(scaled_forces, clock);
  const std::int64_t steps = step_count(periods * r.lamb_period, clock.dt);
  for (std::int64_t s = 0; s <= steps; ++s) {
    throw_if_stopped("the breathing-mode measurement");
    if (s > 0) reference_step.step(reference), scaled_step.step(scaled);
    r.time.push_back(static_cast<double>(s) * clock.dt);
    r.signal.push_back(mean_radius(body, scaled) - mean_radius(body, reference));
  }
  // The scan range is wide (half to twice Lamb's frequency); the fit picks the mode itself.
  const double omega_lamb = 2 * pi / r.lamb_period;
  const double omega = dominant_frequency(r.time, r.signal, 0.5 * omega_lamb, 2 * omega_lamb);
  r.period = 2 * pi / omega;
  r.amplitude = sinusoid_amplitude(r.time, r.signal, omega);
  r.ratio = r.period / r.lamb_period;
  return r;
}

/// Relaxes `state` under the static tidal acceleration eps (-x, -y, 2z) about `center` with a drag
/// -drag v on every particle (v at the start of the step, as the spring damping takes it):
/// Leapfrog::step with the field and the drag as its extra acceleration, for `steps` steps of
/// clock.dt.
void relax_in_tidal_field(ForceField& forces, State& state, const Vec3& center, double eps, double drag,
                          const StepClock& clock, std::int64_t steps,
                          const std::function<void(std::int64_t)>& after_step) {
  Leapfrog leapfrog(forces, clock);
  leapfrog.set_extra_acceleration([&](const double* x, const double* v, std::vector<double>& a) {
    for (std::size_t p = 0; p < a.size() / 3; ++p) {
      a[3 * p] += -eps * (x[3 * p] - center[0]);
      a[3 * p + 1] += -eps * (x[3 * p + 1] - center[1]);
      a[3 * p + 2] += 2 * eps * (x[3 * p + 2] - center[2]);
    }
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = a[i] - drag * v[i];
  });
  for (std::int64_t s = 1; s <= steps; ++s) {
    throw_if_stopped("a static-tide measurement (love or tide)");
    leapfrog.step(state);
    if (after_step) after_step(s);
  }
}

namespace {

/// Coefficient a2 of the fit u_r = a0 + a2 P2(cos theta) of the radial displacement
/// (plus - minus)/2 over the surface nodes, directions from `rest`, and their mean radius. The
/// surface: the shell nodes, or without a shell the particles beyond 0.85 of the outermost one.
std::array<double, 2> fit_degree_two(const Body& body, const State& rest, const State& plus, const State& minus) {
  const Vec3 c0 = body_center_of_mass(body, rest), cp = body_center_of_mass(body, plus),
             cm = body_center_of_mass(body, minus);
  const bool has_shell = body.count_species(Species::shell) > 0;
  double outer = 0;
  for (std::size_t i = 0; i < body.particle_count(); ++i) outer = std::max(outer, (position_of(rest, i) - c0).norm());
  Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();
  Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
  double radius_sum = 0;
  int count = 0;
  for (std::size_t i = 0; i < body.particle_count(); ++i) {
    const Vec3 r = position_of(rest, i) - c0;
    if (has_shell ? body.species[i] != static_cast<std::uint8_t>(Species::shell) : r.norm() < 0.85 * outer) continue;
    const Vec3 rhat = r.normalized();
    const double u = 0.5 * ((position_of(plus, i) - cp) - (position_of(minus, i) - cm)).dot(rhat);
    const double mu = rhat.z();
    const Eigen::Vector2d basis(1.0, 0.5 * (3 * mu * mu - 1));
    normal += basis * basis.transpose();
    rhs += basis * u;
    radius_sum += r.norm();
    ++count;
  }
  const Eigen::Vector2d x = normal.ldlt().solve(rhs);
  return {x[1], radius_sum / count};
}

}  // namespace

LoveResult measure_love_h2(const Checkpoint& relaxed, const Config& config, const BodyMaterial& material,
                           double surface_displacement, double drag, double duration) {
  LoveResult r;
  const LoveNumbers theory = homogeneous_sphere_love_numbers(2, material.youngs_modulus, material.poisson_ratio,
                                                             material.density, material.radius);
  r.theory_h2 = theory.h;
  r.incompressible_h2 = incompressible_love_h2(material.youngs_modulus / (2 * (1 + material.poisson_ratio)),
                                               material.density, material.radius);
  r.tidal_strength = surface_displacement / theory.h;
  const double omega_lamb = 2 * pi / lamb_breathing_period(material.youngs_modulus, material.poisson_ratio,
                                                           material.density, material.radius);
  if (drag <= 0) drag = omega_lamb;
  if (duration <= 0) duration = std::max(3.0, 30 / omega_lamb);
  r.drag = drag;
  r.duration = duration;
  const Body& body = relaxed.body;
  const State rest = state_at_rest(relaxed);
  const Vec3 center = body_center_of_mass(body, rest);
  const double dt = relaxed.stage.clock.dt;
  const StepClock clock{rest.time, rest.step, dt};
  const std::int64_t steps = step_count(duration, dt);
  const std::int64_t early = 2 * steps / 3;
  ForceField forces(body, force_options(config, 0.0));
  State plus = rest, minus = rest;
  relax_in_tidal_field(forces, plus, center, r.tidal_strength, drag, clock, early);
  relax_in_tidal_field(forces, minus, center, -r.tidal_strength, drag, clock, early);
  auto fit = fit_degree_two(body, rest, plus, minus);
  const auto h2_of = [&](const std::array<double, 2>& f) {
    const double rs = f[1];
    return f[0] / (r.tidal_strength * rs * rs * rs * rs);  // W/g = eps r_s^2 / (1/r_s^2)
  };
  r.h2_early = h2_of(fit);
  relax_in_tidal_field(forces, plus, center, r.tidal_strength, drag, clock, steps - early);
  relax_in_tidal_field(forces, minus, center, -r.tidal_strength, drag, clock, steps - early);
  fit = fit_degree_two(body, rest, plus, minus);
  r.h2 = h2_of(fit);
  r.shell_radius = fit[1];
  r.ratio = r.h2 / r.theory_h2;
  return r;
}

FlexureResult measure_plate_flexure(double hinge_stiffness, double spacing, double spring_constant) {
  if (!(hinge_stiffness > 0 && spacing > 0 && spring_constant > 0))
    throw InputError("the flexure test needs a shell with hinges (k_e > 0, L_S > 0, k_S > 0)");
  // Skewed coordinates: node (i, j) at i e1 + j e2, e1 = (a, 0), e2 = (a/2, a sqrt(3)/2), periodic
  // in i mod nx and j mod ny; ny = 2 nx keeps the load sin(k x), k = 2 pi/(nx a), periodic in j.
  const int nx = 16, ny = 32;
  const double a = spacing;
  const Vec3 e1(a, 0, 0), e2(0.5 * a, 0.5 * std::sqrt(3.0) * a, 0);
  const int n = nx * ny;
  std::vector<Vec3> rest(n);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) rest[i + nx * j] = i * e1 + j * e2;
  struct Ref {
    int node;
    Vec3 shift;
  };
  const auto ref = [&](int i, int j) {
    const int wi = ((i % nx) + nx) % nx, wj = ((j % ny) + ny) % ny;
    return Ref{wi + nx * wj, ((i - wi) / nx) * nx * e1 + ((j - wj) / ny) * ny * e2};
  };
  struct Edge {
    Ref a, b;
  };
  struct Hinge {
    std::array<Ref, 4> v;  // wing_1, wing_2, edge_a, edge_b
  };
  std::vector<Edge> edges;
  std::vector<Hinge> hinges;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      // The three edges starting at (i, j), each with the wings of its two triangles.
      edges.push_back({ref(i, j), ref(i + 1, j)});
      hinges.push_back({{ref(i, j + 1), ref(i + 1, j - 1), ref(i, j), ref(i + 1, j)}});
      edges.push_back({ref(i, j), ref(i, j + 1)});
      hinges.push_back({{ref(i + 1, j), ref(i - 1, j + 1), ref(i, j), ref(i, j + 1)}});
      edges.push_back({ref(i, j), ref(i - 1, j + 1)});
      hinges.push_back({{ref(i - 1, j), ref(i, j + 1), ref(i, j), ref(i - 1, j + 1)}});
    }
  const auto at = [](const std::vector<Vec3>& x, const Ref& r) { return Vec3(x[r.node] + r.shift); };
  std::vector<HingeEvaluator> hinge_laws;
  for (const auto& h : hinges)
    hinge_laws.emplace_back(hinge_angle(at(rest, h.v[0]), at(rest, h.v[1]), at(rest, h.v[2]), at(rest, h.v[3])),
                            hinge_stiffness);
  const SpringEvaluator spring(a, spring_constant, 0.0);

  // Load q0 sin(k x) per unit area, each node carrying its area (sqrt(3)/2) a^2.
  const double k = 2 * pi / (nx * a);
  const double node_area = 0.5 * std::sqrt(3.0) * a * a;
  const double paper_rigidity = hinge_stiffness * spacing / 2;
  const double target_deflection = 1e-4 * a;
  const double q0 = target_deflection * paper_rigidity * std::pow(k, 4);
  // Damped dynamics with unit masses to the static equilibrium: the step resolves the stiffest
  // modes; the damping is critical for the loaded (slowest) mode and overdamps the rest.
  const double lattice_rigidity = hinge_lattice_flexural_rigidity(hinge_stiffness);
  // (A wrong rigidity would show as a result that changes between 2/3 of the run and its end.)
  const double omega_max = std::sqrt(12 * spring_constant + 40 * hinge_stiffness / (a * a));
  const double omega_min = std::sqrt(lattice_rigidity * std::pow(k, 4) * node_area);
  const double dt = 0.5 / omega_max;
  const double friction = 2 * omega_min;
  const auto steps = static_cast<std::int64_t>(std::ceil(30 / (omega_min * dt)));
  const std::int64_t early = 2 * steps / 3;
  std::vector<Vec3> x = rest, v(n, Vec3::Zero()), f(n);
  const auto sine_amplitude = [&] {
    double sine = 0;
    for (int p = 0; p < n; ++p) sine += x[p].z() * std::sin(k * rest[p].x());
    return 2 * sine / n;  // the nodes sample whole periods evenly
  };
  FlexureResult r;
  for (std::int64_t s = 0; s < steps; ++s) {
    throw_if_stopped("the flexure measurement");
    if (s == early) r.early_rigidity = q0 / (sine_amplitude() * std::pow(k, 4));
    for (int p = 0; p < n; ++p) f[p] = Vec3(0, 0, q0 * node_area * std::sin(k * rest[p].x()));
    for (const auto& e : edges) {
      const Vec3 d = at(x, e.a) - at(x, e.b);
      const Vec3 force = spring.force(d, Vec3::Zero());
      f[e.a.node] += force;
      f[e.b.node] -= force;
    }
    for (std::size_t h = 0; h < hinges.size(); ++h) {
      const auto& hv = hinges[h].v;
      const HingeForces hf = hinge_laws[h].force_and_energy(at(x, hv[0]), at(x, hv[1]), at(x, hv[2]), at(x, hv[3]));
      for (int q = 0; q < 4; ++q) f[hv[q].node] += hf.on[q];
    }
    for (int p = 0; p < n; ++p) {
      v[p] = (v[p] + dt * f[p]) * (1 - friction * dt);
      x[p] += dt * v[p];
    }
  }
  r.nodes = n;
  r.deflection = sine_amplitude();
  r.theory_deflection = plate_sinusoidal_deflection(q0, k, paper_rigidity);
  r.rigidity = q0 / (r.deflection * std::pow(k, 4));
  r.paper_rigidity = paper_rigidity;
  r.lattice_rigidity = lattice_rigidity;
  r.ratio = r.rigidity / paper_rigidity;
  r.lattice_ratio = r.rigidity / lattice_rigidity;
  return r;
}

std::vector<ElasticLayer> body_layers(const Checkpoint& relaxed, const Vec3& center, int layers, bool with_crust) {
  const Body& body = relaxed.body;
  const State& state = relaxed.state;
  const auto interior = static_cast<std::uint8_t>(Species::interior);
  double outer = 0;
  for (std::size_t i = 0; i < body.particle_count(); ++i)
    if (body.species[i] == interior) outer = std::max(outer, (position_of(state, i) - center).norm());
  const bool crust = with_crust && body.count_species(Species::shell) > 0 && outer < 1;
  const int count = layers + (crust ? 1 : 0);
  std::vector<double> modulus_sum(count, 0.0), mass(count, 0.0);
  const auto layer_of = [&](const Vec3& x) {
    const double r = (x - center).norm();
    return crust && r > outer ? layers : std::min(layers - 1, static_cast<int>(r / outer * layers));
  };
  for (std::size_t i = 0; i < body.particle_count(); ++i)
    if (body.species[i] == interior || crust) mass[layer_of(position_of(state, i))] += body.mass[i];
  for (std::size_t s = 0; s < body.spring_count(); ++s) {
    const auto kind = body.spring_kind[s];
    const bool counted = kind == static_cast<std::uint8_t>(SpringKind::interior) ||
                         (crust && kind == static_cast<std::uint8_t>(SpringKind::cross));
    if (!counted || state.springs.failed[s]) continue;
    const auto [i, j] = body.springs[s];
    const double rest = state.springs.rest_length[s];
    const int b = kind == static_cast<std::uint8_t>(SpringKind::cross)
                      ? layers
                      : layer_of(0.5 * (position_of(state, i) + position_of(state, j)));
    modulus_sum[b] += state.springs.stiffness[s] * rest * rest;
  }
  std::vector<ElasticLayer> result(count);
  for (int b = 0; b < count; ++b) {
    const double r1 = b < layers ? outer * b / layers : outer, r2 = b < layers ? outer * (b + 1) / layers : 1.0;
    const double volume = 4 * pi / 3 * (r2 * r2 * r2 - r1 * r1 * r1);
    if (!(mass[b] > 0 && modulus_sum[b] > 0))
      throw InputError("the interior has a layer without springs or mass: no P-wave speed there");
    result[b] = {r2, network_youngs_modulus(modulus_sum[b], volume), 0.25, mass[b] / volume};
  }
  return result;
}

std::vector<ElasticLayer> ocean_layers(const Checkpoint& relaxed, const Vec3& center, double crust_thickness, bool fluid) {
  const Body& body = relaxed.body;
  const State& state = relaxed.state;
  if (!body.liquid.present() || body.count_species(Species::shell) == 0)
    throw InputError("ocean layers: the body has no liquid layer under a crust");
  const auto interior = static_cast<std::uint8_t>(Species::interior);
  const auto shell = static_cast<std::uint8_t>(Species::shell);
  double floor = 0;
  for (std::size_t i = 0; i < body.particle_count(); ++i)
    if (body.species[i] == interior) floor = std::max(floor, (position_of(state, i) - center).norm());
  const double base = 1 - crust_thickness;
  double liquid_mass = 0, crust_mass = 0;
  for (std::size_t i = 0; i < body.particle_count(); ++i) {
    if (body.species[i] == shell) crust_mass += body.mass[i];
    else if (body.species[i] != interior) liquid_mass += body.mass[i];
  }
  double shell_stiffness = 0, liquid_stiffness_length2 = 0;
  std::size_t shell_springs = 0;
  for (std::size_t s = 0; s < body.spring_count(); ++s) {
    const double k = state.springs.stiffness[s], rest = state.springs.rest_length[s];
    if (body.spring_kind[s] == static_cast<std::uint8_t>(SpringKind::shell)) {
      shell_stiffness += k;
      ++shell_springs;
    } else if (body.spring_kind[s] == static_cast<std::uint8_t>(SpringKind::liquid) && !state.springs.failed[s]) {
      liquid_stiffness_length2 += k * rest * rest;
    }
  }
  auto volume = [](double r1, double r2) { return 4 * pi / 3 * (r2 * r2 * r2 - r1 * r1 * r1); };
  // The springs' eq. 15 modulus at nu = 1/4 (mu = E / 2.5, K = E / 1.5) beside the layer's K.
  const double springs_modulus = network_youngs_modulus(liquid_stiffness_length2, volume(floor, base));
  const double bulk = body.liquid.bulk_modulus + springs_modulus / 1.5;
  const double shear = fluid ? fluid_shear_fraction * bulk : springs_modulus / 2.5;
  const ElasticLayer liquid{base, 9 * bulk * shear / (3 * bulk + shear), (3 * bulk - 2 * shear) / (2 * (3 * bulk + shear)),
                            liquid_mass / volume(floor, base)};
  const double k_s = shell_stiffness / static_cast<double>(shell_springs);
  return {liquid, {1.0, 2.0 / std::sqrt(3.0) * k_s / crust_thickness, 1.0 / 3.0, crust_mass / volume(base, 1.0)}};
}

double layered_p_wave_time(const Checkpoint& relaxed, const Vec3& center, double z_from, double z_to, int layers) {
  const std::vector<ElasticLayer> profile = body_layers(relaxed, center, layers, false);
  const double outer = profile.back().outer_radius;
  std::vector<double> speed(layers);
  for (int b = 0; b < layers; ++b) speed[b] = p_wave_speed(profile[b].youngs_modulus, 0.25, profile[b].density);
  // Midpoint rule along the z axis through the centre.
  const int pieces = 2000;
  double time = 0;
  const double dz = (z_to - z_from) / pieces;
  for (int p = 0; p < pieces; ++p) {
    const double z = z_from + (p + 0.5) * dz;
    time += std::abs(dz) / speed[std::min(layers - 1, static_cast<int>(std::abs(z) / outer * layers))];
  }
  return time;
}

PWaveResult measure_p_wave(const Checkpoint& relaxed, const Config& config, const BodyMaterial& material,
                           double pulse_speed, double cap, double threshold_fraction) {
  const Body& body = relaxed.body;
  State quiet = state_at_rest(relaxed);
  const Vec3 center = body_center_of_mass(body, quiet);
  // Interior particles only: eq. 16 is the interior network's speed, and a pulse on the crust
  // would start its short flexural waves, which are dispersive and far faster (docs/validation.md).
  const auto is_interior = [&](std::size_t i) { return body.species[i] == static_cast<std::uint8_t>(Species::interior); };
  double top = -1e300, bottom = 1e300;
  for (std::size_t i = 0; i < body.particle_count(); ++i) {
    if (!is_interior(i)) continue;
    top = std::max(top, position_of(quiet, i).z() - center.z());
    bottom = std::min(bottom, position_of(quiet, i).z() - center.z());
  }
  std::vector<std::size_t> receivers;
  State pulsed = quiet;
  for (std::size_t i = 0; i < body.particle_count(); ++i) {
    if (!is_interior(i)) continue;
    const double z = position_of(quiet, i).z() - center.z();
    if (z > top - cap) pulsed.velocity[3 * i + 2] = -pulse_speed;
    if (z < bottom + cap) receivers.push_back(i);
  }
  PWaveResult r;
  r.path_length = (top - cap) - (bottom + cap);
  r.theory_time = r.path_length / material.p_wave_speed;
  r.layered_time = layered_p_wave_time(relaxed, center, bottom + cap, top - cap);
  ForceField quiet_forces(body, force_options(config, 0.0)), pulsed_forces(body, force_options(config, 0.0));
  const StepClock clock{quiet.time, quiet.step, relaxed.stage.clock.dt};
  Leapfrog quiet_step(quiet_forces, clock), pulsed_step(pulsed_forces, clock);
  const std::int64_t steps = step_count(2 * r.theory_time, clock.dt);
  for (std::int64_t s = 0; s <= steps; ++s) {
    throw_if_stopped("the P-wave measurement");
    if (s > 0) quiet_step.step(quiet), pulsed_step.step(pulsed);
    // The pulse's momentum moves the centre of mass too, but a receiver moves only once
    // the disturbance (or its gravity, far weaker) reaches it: no drift to remove.
    double sum = 0;
    for (std::size_t i : receivers)
      sum += std::hypot(pulsed.velocity[3 * i] - quiet.velocity[3 * i], pulsed.velocity[3 * i + 1] - quiet.velocity[3 * i + 1],
                        pulsed.velocity[3 * i + 2] - quiet.velocity[3 * i + 2]);
    r.time.push_back(static_cast<double>(s) * clock.dt);
    r.signal.push_back(sum / static_cast<double>(receivers.size()));
  }
  r.threshold = threshold_fraction * *std::max_element(r.signal.begin(), r.signal.end());
  for (std::size_t s = 0; s < r.signal.size(); ++s)
    if (r.signal[s] >= r.threshold) {
      // Linear interpolation between the samples around the crossing.
      const double before = s > 0 ? r.signal[s - 1] : 0.0;
      const double fraction = s > 0 ? (r.threshold - before) / (r.signal[s] - before) : 0.0;
      r.arrival_time = s > 0 ? r.time[s - 1] + fraction * (r.time[s] - r.time[s - 1]) : 0.0;
      break;
    }
  r.ratio = r.arrival_time / r.theory_time;
  r.layered_ratio = r.arrival_time / r.layered_time;
  return r;
}

}  // namespace tidalcrust
