#include "integrate/stability_bound.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "base/vec3.hpp"

namespace tidalcrust {
namespace {

/// Per node: the Gershgorin row sum by element kind and the diagonal 3x3 block.
struct NodeStiffness {
  double row_springs = 0, row_cross = 0, row_hinges = 0;  ///< sum ||K_ij|| / sqrt(m_i m_j)
  double row_damping = 0;  ///< sum ||C_ij|| / sqrt(m_i m_j), 1/t_grav
  double diag_springs = 0, diag_cross = 0, diag_hinges = 0;  ///< trace shares of K_ii / m_i
  Eigen::Matrix3d diagonal = Eigen::Matrix3d::Zero();     ///< K_ii, G M^2/R^3
};

/// theta's gradients of a hinge {wing_1, wing_2, edge_a, edge_b} (hinge_force.hpp u_i) and
/// c = k_e C / 2, the curvature of E_h in theta.
struct HingeGradients {
  std::array<Vec3, 4> u;
  double c = 0;
};

HingeGradients hinge_gradients(const Vec3& x1, const Vec3& x2, const Vec3& x3, const Vec3& x4, double k_e) {
  const Vec3 e = x4 - x3;
  const double length = e.norm();
  const Vec3 n1 = (x1 - x3).cross(x1 - x4);
  const Vec3 n2 = (x2 - x4).cross(x2 - x3);
  const double a1 = n1.squaredNorm(), a2 = n2.squaredNorm();
  HingeGradients g;
  if (!(a1 > 0 && a2 > 0 && length > 0)) return g;
  g.u[0] = length * n1 / a1;
  g.u[1] = length * n2 / a2;
  g.u[2] = (x1 - x4).dot(e) / length * n1 / a1 + (x2 - x4).dot(e) / length * n2 / a2;
  g.u[3] = -(x1 - x3).dot(e) / length * n1 / a1 - (x2 - x3).dot(e) / length * n2 / a2;
  g.c = 0.5 * k_e * length * length / (std::sqrt(a1) + std::sqrt(a2));
  return g;
}

double bound_dt(double omega2) { return omega2 > 0 ? 2.0 / std::sqrt(omega2) : 0.0; }

/// The largest dt with omega2 dt^2 + 2 c dt <= 4 (both >= 0); 2/omega without damping. Written as
/// 4 / (c + sqrt(c^2 + 4 omega2)) so that c = 0 gives exactly 2/sqrt(omega2).
double damped_bound_dt(double omega2, double c) {
  return omega2 > 0 ? 4.0 / (c + std::sqrt(c * c + 4.0 * omega2)) : 0.0;
}

}  // namespace

std::string LimitingNode::describe(const Body& body, const State& state) const {
  const bool shell = body.species[node] == static_cast<std::uint8_t>(Species::shell);
  return fmt::format("{} node {} (r = {:.3f} R; {:.0f}% hinges, {:.0f}% springs, {:.0f}% cross springs)",
                     shell ? "shell" : "interior", node, vec3_at(state.position, node).norm(), 100 * hinges,
                     100 * springs, 100 * cross);
}

StabilityBound stability_bound(const Body& body, const State& state, double damping) {
  const std::size_t n = body.particle_count();
  std::vector<NodeStiffness> nodes(n);
  const auto& m = body.mass;
  for (std::size_t s = 0; s < body.spring_count(); ++s) {
    const auto i = static_cast<std::size_t>(body.springs[s][0]);
    const auto j = static_cast<std::size_t>(body.springs[s][1]);
    if (damping > 0) {  // every spring, failed or not, damps with gamma mu (force_field.cpp)
      const double c = damping * m[i] * m[j] / (m[i] + m[j]);
      const double cross_term = c / std::sqrt(m[i] * m[j]);
      nodes[i].row_damping += c / m[i] + cross_term;
      nodes[j].row_damping += c / m[j] + cross_term;
    }
    const double k = state.springs.stiffness[s];
    if (!(k > 0)) continue;
    const Vec3 d = vec3_at(state.position, i) - vec3_at(state.position, j);
    const double len = d.norm();
    const Vec3 u = len > 0 ? Vec3(d / len) : Vec3(1, 0, 0);
    const Eigen::Matrix3d block = k * u * u.transpose();
    const bool cross = body.spring_kind[s] == static_cast<std::uint8_t>(SpringKind::cross);
    for (auto [a, b] : {std::array<std::size_t, 2>{i, j}, std::array<std::size_t, 2>{j, i}}) {
      NodeStiffness& node = nodes[a];
      node.diagonal += block;
      const double row = k / m[a] + k / std::sqrt(m[a] * m[b]);
      (cross ? node.row_cross : node.row_springs) += row;
      (cross ? node.diag_cross : node.diag_springs) += k / m[a];
    }
  }
  for (std::size_t h = 0; h < body.hinge_count(); ++h) {
    const auto& v = body.hinges[h];
    std::array<Vec3, 4> x;
    for (int a = 0; a < 4; ++a) x[a] = vec3_at(state.position, static_cast<std::size_t>(v[a]));
    const HingeGradients g = hinge_gradients(x[0], x[1], x[2], x[3], body.hinge_stiffness[h]);
    if (!(g.c > 0)) continue;
    for (int a = 0; a < 4; ++a) {
      const auto i = static_cast<std::size_t>(v[a]);
      NodeStiffness& node = nodes[i];
      node.diagonal += g.c * g.u[a] * g.u[a].transpose();
      node.diag_hinges += g.c * g.u[a].squaredNorm() / m[i];
      for (int b = 0; b < 4; ++b)
        node.row_hinges += g.c * g.u[a].norm() * g.u[b].norm() / std::sqrt(m[i] * m[static_cast<std::size_t>(v[b])]);
    }
  }
  StabilityBound bound;
  bound.damping = damping;
  for (std::size_t i = 0; i < n; ++i) {
    const NodeStiffness& node = nodes[i];
    bound.damping_rate = std::max(bound.damping_rate, node.row_damping);
    const double row = node.row_springs + node.row_cross + node.row_hinges;
    if (row > bound.safe_limit.omega2 && row > 0)
      bound.safe_limit = {i, row, node.row_springs / row, node.row_cross / row, node.row_hinges / row};
    const double quotient =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(node.diagonal, Eigen::EigenvaluesOnly).eigenvalues()(2) / m[i];
    const double trace = node.diag_springs + node.diag_cross + node.diag_hinges;
    if (quotient > bound.unstable_limit.omega2 && trace > 0)
      bound.unstable_limit = {i, quotient, node.diag_springs / trace, node.diag_cross / trace,
                              node.diag_hinges / trace};
  }
  bound.safe_dt = damped_bound_dt(bound.safe_limit.omega2, bound.damping_rate);
  bound.undamped_safe_dt = bound_dt(bound.safe_limit.omega2);
  bound.unstable_dt = bound_dt(bound.unstable_limit.omega2);
  return bound;
}

}  // namespace tidalcrust
