#pragma once
// Where a ray crosses a sphere about the origin: shared by the welded coupling (bodies/) and the
// layer moduli measured across spheres (analysis/).

#include <cmath>
#include <vector>

#include "base/vec3.hpp"

namespace tidalcrust {

/// Distances t >= 0 along the unit vector n from the point x (R) at which |x + t n| = r (R):
/// 0, 1 or 2 of them, ascending. A tangent ray (discriminant 0) counts as no crossing.
inline std::vector<double> sphere_crossings(const Vec3& x, const Vec3& n, double r) {
  const double b = x.dot(n), c = x.squaredNorm() - r * r;
  const double disc = b * b - c;
  if (disc <= 0) return {};
  const double root = std::sqrt(disc);
  std::vector<double> t;
  for (double s : {-b - root, -b + root})
    if (s >= 0) t.push_back(s);
  return t;
}

}  // namespace tidalcrust
