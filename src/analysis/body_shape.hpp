#pragma once
// The shape of the body as a whole: the principal axes of its mass distribution, for the tidally
// stretched interior-only body of the paper's Figure 5 (run N) and its axis ratios over time.
// Units: G = M = R = 1 (lengths R).
#include <array>
#include <vector>

#include "base/vec3.hpp"

namespace tidalcrust {

/// The homogeneous ellipsoid with the same second moments as a set of point masses.
struct PrincipalAxes {
  /// Semi-axes a >= b >= c (R): sqrt(5 lambda_k / M_total), lambda_k the eigenvalues of the
  /// second-moment tensor S = sum_i m_i (x_i - x_cm)(x_i - x_cm)^T. The inertia tensor
  /// I = tr(S) 1 - S has the same axes, with principal moments M (b^2 + c^2)/5, ... (a solid
  /// ellipsoid of semi-axes a, b, c has exactly these moments).
  std::array<double, 3> semi_axis{};
  std::array<Vec3, 3> direction{};  ///< unit vectors along a, b, c (each up to its sign)
  double b_over_a() const { return semi_axis[1] / semi_axis[0]; }
  double c_over_a() const { return semi_axis[2] / semi_axis[0]; }
};

/// Principal axes of point masses mass [N] (M) at position [N*3] (R), about their centre of mass.
/// InputError when the sizes disagree, no mass is positive, or a value is not finite.
PrincipalAxes principal_axes(const std::vector<double>& mass, const std::vector<double>& position);

}  // namespace tidalcrust
