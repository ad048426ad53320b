#include "physics/crust_relaxation.hpp"

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "forces/hinge_geometry.hpp"
#include "model/center_of_mass.hpp"
#include "base/errors.hpp"
#include "base/vec3.hpp"
#include "base/invariant.hpp"
#include "model/derived_quantities.hpp"
#include "physics/continuum_elasticity.hpp"

namespace tidalcrust {

void creep_shell_rest_lengths(const Body& body, State& state, double rate) {
  for (std::size_t n = 0; n < body.spring_count(); ++n) {
    if (body.spring_kind[n] != static_cast<std::uint8_t>(SpringKind::shell)) continue;
    const auto i = static_cast<std::size_t>(body.springs[n][0]);
    const auto j = static_cast<std::size_t>(body.springs[n][1]);
    const double length = (vec3_at(state.position, i) - vec3_at(state.position, j)).norm();
    double& rest = state.springs.rest_length[n];
    rest = rate == 1.0 ? length : rest + rate * (length - rest);
  }
}

void reset_hinge_rest_angles(const Body& body, State& state, bool portable) {
  for (std::size_t h = 0; h < body.hinge_count(); ++h) {
    const auto& v = body.hinges[h];
    auto at = [&](int k) { return vec3_at(state.position, static_cast<std::size_t>(v[k])); };
    state.hinges.rest_angle[h] = hinge_angle(at(0), at(1), at(2), at(3), portable);
  }
}

CrossBalance balance_cross_springs(const Body& body, State& state, const std::vector<double>& gravity,
                                   bool stiffness_weighted, const std::vector<double>* crust_force) {
  // The cross springs of each shell node, in spring index order.
  std::vector<std::vector<std::size_t>> cross_of(body.particle_count());
  for (std::size_t n = 0; n < body.spring_count(); ++n) {
    if (body.spring_kind[n] != static_cast<std::uint8_t>(SpringKind::cross)) continue;
    for (int end : {0, 1}) {
      const auto p = static_cast<std::size_t>(body.springs[n][end]);
      if (body.species[p] == static_cast<std::uint8_t>(Species::shell)) cross_of[p].push_back(n);
    }
  }
  CrossBalance result;
  for (std::size_t s = 0; s < body.particle_count(); ++s) {
    if (body.species[s] != static_cast<std::uint8_t>(Species::shell)) continue;
    // What the cross springs carry: the weight, and the crust's push when it is pre-stressed.
    Vec3 load = body.mass[s] * vec3_at(gravity, s);
    if (crust_force) load += vec3_at(*crust_force, s);
    const auto& springs = cross_of[s];
    const std::size_t m = springs.size();
    std::vector<Vec3> direction(m);
    std::vector<double> tension(m), length(m);
    Eigen::Matrix3d gram = Eigen::Matrix3d::Zero();
    Vec3 pushed = Vec3::Zero();  // A t: what the springs now do
    for (std::size_t c = 0; c < m; ++c) {
      const std::size_t n = springs[c];
      const auto other = static_cast<std::size_t>(body.springs[n][body.springs[n][0] == static_cast<std::int32_t>(s) ? 1 : 0]);
      const Vec3 d = vec3_at(state.position, s) - vec3_at(state.position, other);
      length[c] = d.norm();
      direction[c] = d / length[c];
      tension[c] = state.springs.stiffness[n] * (length[c] - state.springs.rest_length[n]);
      const double share = stiffness_weighted ? state.springs.stiffness[n] : 1.0;
      gram += share * direction[c] * direction[c].transpose();
      pushed += tension[c] * direction[c];
    }
    // y = (A A^T)^+ (m g - A t0): the pseudo-inverse from the eigen-decomposition of the 3x3
    // Gram matrix, dropping directions no spring can push along.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(gram);
    const Eigen::Vector3d lambda = eigen.eigenvalues();
    const Eigen::Vector3d projected = eigen.eigenvectors().transpose() * (load - pushed);
    Eigen::Vector3d scaled = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k)
      if (lambda(k) > 1e-12 * lambda(2)) scaled(k) = projected(k) / lambda(k);
    const Vec3 y = eigen.eigenvectors() * scaled;
    Vec3 carried = Vec3::Zero();
    for (std::size_t c = 0; c < m; ++c) {
      const double share = stiffness_weighted ? state.springs.stiffness[springs[c]] : 1.0;
      tension[c] += share * direction[c].dot(y);
      carried += tension[c] * direction[c];
    }
    const double relative = (carried - load).norm() / load.norm();
    result.max_residual = std::max(result.max_residual, relative);
    if (relative > 1e-9) ++result.unbalanced_nodes;
    for (std::size_t c = 0; c < m; ++c) {
      const std::size_t n = springs[c];
      const double rest = length[c] - tension[c] / state.springs.stiffness[n];
      if (!(rest > 0.5 * length[c]) || !(rest < 2 * length[c]))
        throw InputError(fmt::format(
            "balanced crust support: cross spring {} would need rest length {} for length {} (strain beyond "
            "+-50%): the cross springs are too weak for the shell's weight (raise cross.spring_constant), or the "
            "relaxation went unstable (integrator.dt above the stability bound: see the warning at the start)",
            n, rest, length[c]));
      state.springs.rest_length[n] = rest;
    }
  }
  return result;
}

double lithostatic_crust_strain(const Body& body, const State& state, const std::vector<double>& gravity,
                                double interior_radius, double interior_spring_distance) {
  const double shell_radius = mean_shell_radius(body, state);
  double weight = 0;
  for (std::size_t i = 0; i < body.particle_count(); ++i)
    if (body.species[i] == static_cast<std::uint8_t>(Species::shell)) weight += body.mass[i] * vec3_at(gravity, i).norm();
  double stiffness_length2 = 0;
  for (std::size_t n = 0; n < body.spring_count(); ++n) {
    if (body.spring_kind[n] != static_cast<std::uint8_t>(SpringKind::shell)) continue;
    const double rest = state.springs.rest_length[n];
    stiffness_length2 += state.springs.stiffness[n] * rest * rest;
  }
  const double deep = interior_radius - interior_spring_distance;
  TIDALCRUST_ASSERT(shell_radius > 0 && stiffness_length2 > 0, "lithostatic crust strain needs a shell");
  if (!(deep > 0 && deep < shell_radius))
    throw InputError(fmt::format("relax.crust_support = \"lithostatic\": interior.radius - interior.spring_distance = {} "
                                 "leaves no interior springs deeper than d_I to take the interior's modulus from",
                                 deep));
  // Shells of about d_I / 2 (the springs' own reach) out to r_I - d_I, below which eq. 15 counts every
  // spring; the outermost continued to the shell.
  const auto shells = static_cast<std::size_t>(std::max(1.0, std::round(deep / (0.5 * interior_spring_distance))));
  std::vector<double> radii(shells);
  for (std::size_t b = 0; b < shells; ++b) radii[b] = deep * static_cast<double>(b + 1) / static_cast<double>(shells);
  const std::vector<double> modulus = interior_modulus_profile(body, state, radii);
  std::vector<ElasticLayer> layers;
  // A shell without spring midpoints (a small body's centre) is left out: the next one reaches down.
  for (std::size_t b = 0; b < shells; ++b)
    if (modulus[b] > 0) layers.push_back({b + 1 < shells ? radii[b] : shell_radius, modulus[b], 0.25, 0});
  if (layers.empty() || !(modulus.back() > 0))
    throw InputError(fmt::format("relax.crust_support = \"lithostatic\": no interior springs within {} of the "
                                 "centre, below the welded layer, to take the interior's modulus from", deep));
  layers.back().outer_radius = shell_radius;
  const double compliance = layered_sphere_compression(layers);
  const double area = 4 * std::numbers::pi * shell_radius * shell_radius;
  const double membrane = stiffness_length2 / (2 * area);
  return -(weight / area) / (1 / compliance + 2 * membrane / shell_radius);
}

void set_shell_strain(const Body& body, State& state, double strain) {
  for (std::size_t n = 0; n < body.spring_count(); ++n) {
    if (body.spring_kind[n] != static_cast<std::uint8_t>(SpringKind::shell)) continue;
    const auto i = static_cast<std::size_t>(body.springs[n][0]);
    const auto j = static_cast<std::size_t>(body.springs[n][1]);
    state.springs.rest_length[n] = (vec3_at(state.position, i) - vec3_at(state.position, j)).norm() / (1 + strain);
  }
}

std::vector<double> shell_spring_forces(const Body& body, const State& state) {
  std::vector<double> force(state.position.size(), 0.0);
  for (std::size_t n = 0; n < body.spring_count(); ++n) {
    if (body.spring_kind[n] != static_cast<std::uint8_t>(SpringKind::shell)) continue;
    const auto i = static_cast<std::size_t>(body.springs[n][0]);
    const auto j = static_cast<std::size_t>(body.springs[n][1]);
    const Vec3 d = vec3_at(state.position, i) - vec3_at(state.position, j);
    const double length = d.norm();
    const Vec3 on_i = -state.springs.stiffness[n] * (length - state.springs.rest_length[n]) / length * d;
    for (int k = 0; k < 3; ++k) {
      force[3 * i + static_cast<std::size_t>(k)] += on_i(k);
      force[3 * j + static_cast<std::size_t>(k)] -= on_i(k);
    }
  }
  return force;
}

double mean_shell_radius(const Body& body, const State& state) {
  const Vec3 centre = body_center_of_mass(body, state);
  double sum = 0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < body.particle_count(); ++i) {
    if (body.species[i] != static_cast<std::uint8_t>(Species::shell)) continue;
    sum += (vec3_at(state.position, i) - centre).norm();
    ++count;
  }
  return count ? sum / static_cast<double>(count) : 0.0;
}

}  // namespace tidalcrust
