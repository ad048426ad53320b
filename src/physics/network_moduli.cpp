#include "physics/network_moduli.hpp"

#include <fmt/format.h>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <cmath>
#include <numbers>

#include "base/errors.hpp"
#include "base/invariant.hpp"
#include "model/derived_quantities.hpp"

namespace tidalcrust {

namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Vector6 = Eigen::Matrix<double, 6, 1>;

/// The unit strain of Voigt component c (xx, yy, zz, yz, xz, xy; a shear component as an
/// engineering strain, so the tensor holds 1/2 off the diagonal).
Eigen::Matrix3d voigt_unit_strain(int c) {
  static constexpr int row[6] = {0, 1, 2, 1, 0, 0}, column[6] = {0, 1, 2, 2, 2, 1};
  Eigen::Matrix3d e = Eigen::Matrix3d::Zero();
  e(row[c], column[c]) = e(column[c], row[c]) = c < 3 ? 1.0 : 0.5;
  return e;
}

Vector6 voigt_stress(const Eigen::Matrix3d& s) {
  Vector6 v;
  v << s(0, 0), s(1, 1), s(2, 2), s(1, 2), s(0, 2), s(0, 1);
  return v;
}

/// Euclidean norm by a plain loop (Eigen's vectorised reduction of a dynamic vector warns
/// -Wmaybe-uninitialized inside GCC 12's AVX-512 headers).
double euclidean_norm(const Eigen::VectorXd& v) {
  double sum = 0;
  for (Eigen::Index i = 0; i < v.size(); ++i) sum += v[i] * v[i];
  return std::sqrt(sum);
}

/// Fraction of the segment a-b inside the sphere of `radius` about `center`.
double fraction_inside(const Vec3& a, const Vec3& b, const Vec3& center, double radius) {
  const Vec3 p = a - center, d = b - a;
  const double qa = d.squaredNorm(), qb = 2 * p.dot(d), qc = p.squaredNorm() - radius * radius;
  const double discriminant = qb * qb - 4 * qa * qc;
  if (discriminant <= 0 || qa <= 0) return 0.0;
  const double root = std::sqrt(discriminant);
  const double t1 = (-qb - root) / (2 * qa), t2 = (-qb + root) / (2 * qa);
  return std::max(0.0, std::min(t2, 1.0) - std::max(t1, 0.0));
}

/// The springs' tension and geometry, with the virial of a set of positions.
class Virial {
 public:
  Virial(const std::vector<NetworkSpring>& springs, std::vector<double> rest, std::vector<double> weight,
         double volume)
      : springs_(springs), rest_(std::move(rest)), weight_(std::move(weight)), volume_(volume) {}

  /// sigma = (1/V) sum_s w_s T_s r_s r_s^T / l_s with T_s = k (l_s - L0_s), tension positive.
  Eigen::Matrix3d stress(const std::vector<Vec3>& x) const {
    Eigen::Matrix3d sigma = Eigen::Matrix3d::Zero();
    for (std::size_t s = 0; s < springs_.size(); ++s) {
      if (weight_[s] == 0) continue;
      const Vec3 r = x[springs_[s].i] - x[springs_[s].j];
      const double l = r.norm();
      const double tension = springs_[s].stiffness * (l - rest_[s]);
      sigma += (weight_[s] * tension / l) * (r * r.transpose());
    }
    return sigma / volume_;
  }

 private:
  const std::vector<NetworkSpring>& springs_;
  std::vector<double> rest_;
  std::vector<double> weight_;
  double volume_;
};

/// One column of C: the stress response to strain u = +-h `unit` per unit strain, e_g.
Vector6 stress_response(const Virial& virial, const std::vector<Vec3>& x0, const std::vector<Vec3>& u, double h) {
  std::vector<Vec3> plus(x0.size()), minus(x0.size());
  for (std::size_t n = 0; n < x0.size(); ++n) plus[n] = x0[n] + u[n], minus[n] = x0[n] - u[n];
  return voigt_stress(virial.stress(plus) - virial.stress(minus)) / (2 * h);
}

}  // namespace

IsotropicModuli isotropic_moduli_from_bulk_shear(double bulk, double shear) {
  if (!(bulk > 0 && shear > 0 && std::isfinite(bulk) && std::isfinite(shear)))
    throw InputError(fmt::format("isotropic moduli need K > 0 and G > 0, got K = {}, G = {}", bulk, shear));
  IsotropicModuli m;
  m.bulk = bulk;
  m.shear = shear;
  m.youngs = 9 * bulk * shear / (3 * bulk + shear);
  m.poisson = (3 * bulk - 2 * shear) / (2 * (3 * bulk + shear));
  return m;
}

IsotropicModuli voigt_isotropic_moduli(const Matrix6& c) {
  const double normal = c(0, 0) + c(1, 1) + c(2, 2);
  const double cross = c(0, 1) + c(1, 2) + c(0, 2);
  const double shear = c(3, 3) + c(4, 4) + c(5, 5);
  return isotropic_moduli_from_bulk_shear((normal + 2 * cross) / 9, (normal - cross + 3 * shear) / 15);
}

NetworkModuli measure_network_moduli(const std::vector<Vec3>& positions, const std::vector<NetworkSpring>& springs,
                                     const Vec3& center, double hold_radius, double measure_radius, double strain,
                                     bool with_prestress) {
  // The arguments are the caller's (analysis/elastic_validation.cpp), not a user's.
  TIDALCRUST_ASSERT(hold_radius > 0 && measure_radius > 0 && measure_radius <= hold_radius && strain > 0,
                    fmt::format("network moduli: need 0 < measure_radius <= hold_radius and strain > 0, got {}, {} "
                                "and {}",
                                measure_radius, hold_radius, strain));
  const auto n = static_cast<std::int32_t>(positions.size());
  for (const auto& s : springs)
    TIDALCRUST_ASSERT(s.i >= 0 && s.j >= 0 && s.i < n && s.j < n && s.i != s.j,
                      fmt::format("network moduli: spring ({}, {}) names no pair of the {} nodes", s.i, s.j, n));

  // Which nodes relax: those inside hold_radius that carry a spring (a node without one does
  // not take part); their index in the linear system.
  NetworkModuli result;
  std::vector<char> in_network(positions.size(), 0);
  for (const auto& s : springs) in_network[s.i] = in_network[s.j] = 1;
  std::vector<int> free_index(positions.size(), -1);
  int free_count = 0;
  for (std::size_t p = 0; p < positions.size(); ++p) {
    if (!in_network[p]) continue;
    if ((positions[p] - center).norm() <= hold_radius)
      free_index[p] = free_count++;
    else
      ++result.held_nodes;
  }
  result.free_nodes = free_count;
  if (free_count == 0 || result.held_nodes == 0)
    throw InputError(fmt::format("network moduli: {} nodes free and {} held at hold_radius {}: need both",
                                 free_count, result.held_nodes, hold_radius));

  // Rest lengths (without pre-stress: the lengths at x0), region weights, eq. 15 in the region.
  const double volume = 4 * std::numbers::pi / 3 * measure_radius * measure_radius * measure_radius;
  std::vector<double> rest(springs.size()), weight(springs.size());
  double stiffness_length2 = 0;
  for (std::size_t s = 0; s < springs.size(); ++s) {
    const Vec3& a = positions[springs[s].i];
    const Vec3& b = positions[springs[s].j];
    rest[s] = with_prestress ? springs[s].rest_length : (a - b).norm();
    weight[s] = fraction_inside(a, b, center, measure_radius);
    stiffness_length2 += weight[s] * springs[s].stiffness * rest[s] * rest[s];
    result.springs_in_region += weight[s];
  }
  result.eq15_youngs = network_youngs_modulus(stiffness_length2, volume);
  const Virial virial(springs, rest, weight, volume);
  result.reference_pressure = -virial.stress(positions).trace() / 3;

  // The stiffness matrix of the free nodes, linearised at x0: per spring
  // H = k n n^T + (T/l)(I - n n^T); the force on i is -H (u_i - u_j).
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<Eigen::Matrix3d> block(springs.size());
  for (std::size_t s = 0; s < springs.size(); ++s) {
    const Vec3 r = positions[springs[s].i] - positions[springs[s].j];
    const double l = r.norm();
    const Vec3 nhat = r / l;
    const double tension = springs[s].stiffness * (l - rest[s]);
    const Eigen::Matrix3d nn = nhat * nhat.transpose();
    block[s] = springs[s].stiffness * nn + (tension / l) * (Eigen::Matrix3d::Identity() - nn);
    const int fi = free_index[springs[s].i], fj = free_index[springs[s].j];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const double h = block[s](a, b);
        if (fi >= 0) triplets.emplace_back(3 * fi + a, 3 * fi + b, h);
        if (fj >= 0) triplets.emplace_back(3 * fj + a, 3 * fj + b, h);
        if (fi >= 0 && fj >= 0) {
          triplets.emplace_back(3 * fi + a, 3 * fj + b, -h);
          triplets.emplace_back(3 * fj + a, 3 * fi + b, -h);
        }
      }
  }
  Eigen::SparseMatrix<double> stiffness(3 * free_count, 3 * free_count);
  stiffness.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(stiffness);
  if (solver.info() != Eigen::Success)
    throw InputError("network moduli: the springs do not hold the free nodes in place (singular stiffness matrix)");

  for (int c = 0; c < 6; ++c) {
    const Eigen::Matrix3d e = strain * voigt_unit_strain(c);
    std::vector<Vec3> affine(positions.size());
    for (std::size_t p = 0; p < positions.size(); ++p) affine[p] = e * (positions[p] - center);
    result.affine.col(c) = stress_response(virial, positions, affine, strain);
    // The held nodes pull the free ones: H u_i = H u_j for each spring to a held node j.
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(3 * free_count);
    for (std::size_t s = 0; s < springs.size(); ++s) {
      const int fi = free_index[springs[s].i], fj = free_index[springs[s].j];
      if (fi >= 0 && fj < 0) rhs.segment<3>(3 * fi) += block[s] * affine[springs[s].j];
      if (fj >= 0 && fi < 0) rhs.segment<3>(3 * fj) += block[s] * affine[springs[s].i];
    }
    const Eigen::VectorXd u = solver.solve(rhs);
    const Eigen::VectorXd difference = stiffness * u - rhs;
    const double residual = euclidean_norm(difference);
    if (solver.info() != Eigen::Success || !std::isfinite(residual) || residual > 1e-8 * euclidean_norm(rhs))
      throw InputError("network moduli: the springs do not hold the free nodes in place (no static equilibrium)");
    std::vector<Vec3> relaxed = affine;
    for (std::size_t p = 0; p < positions.size(); ++p)
      if (free_index[p] >= 0) relaxed[p] = u.segment<3>(3 * free_index[p]);
    result.relaxed.col(c) = stress_response(virial, positions, relaxed, strain);
  }
  result.relaxed_moduli = voigt_isotropic_moduli(result.relaxed);
  result.affine_moduli = voigt_isotropic_moduli(result.affine);
  return result;
}

}  // namespace tidalcrust
