#include "analysis/body_shape.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "base/errors.hpp"

namespace tidalcrust {

PrincipalAxes principal_axes(const std::vector<double>& mass, const std::vector<double>& position) {
  const std::size_t n = mass.size();
  if (position.size() != 3 * n)
    throw InputError(fmt::format("principal axes: {} masses but {} coordinates", n, position.size()));
  double total = 0;
  Vec3 center = Vec3::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    total += mass[i];
    center += mass[i] * Vec3(position[3 * i], position[3 * i + 1], position[3 * i + 2]);
  }
  if (!(total > 0) || !std::isfinite(total) || !center.allFinite())
    throw InputError("principal axes: the masses must be finite with a positive sum, the positions finite");
  center /= total;
  Eigen::Matrix3d second_moment = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 d = Vec3(position[3 * i], position[3 * i + 1], position[3 * i + 2]) - center;
    second_moment += mass[i] * d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(second_moment);  // eigenvalues ascending
  PrincipalAxes axes;
  for (int k = 0; k < 3; ++k) {
    const int ascending = 2 - k;
    axes.semi_axis[static_cast<std::size_t>(k)] = std::sqrt(std::max(0.0, 5 * solver.eigenvalues()[ascending] / total));
    axes.direction[static_cast<std::size_t>(k)] = solver.eigenvectors().col(ascending);
  }
  return axes;
}

}  // namespace tidalcrust
