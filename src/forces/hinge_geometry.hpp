#pragma once
// The bending angle of a hinge (Bridson, Marino & Fedkiw 2003, section 4; paper eq. 22).
#include <Eigen/Geometry>  // cross()
#include <cmath>

#include "base/portable_math.hpp"
#include "base/vec3.hpp"

namespace tidalcrust {

/// Signed angle theta (radians, in (-pi, pi]) between the normals of the two faces of a hinge:
/// x1, x2 the wing vertices, x3-x4 the shared edge (Body::hinges order). With
/// N1 = (x1-x3) x (x1-x4), N2 = (x2-x4) x (x2-x3), E = x4-x3:
/// theta = atan2((n1 x n2) . e, n1 . n2). Zero for a flat hinge; the dihedral angle is pi - |theta|.
/// `portable`: atan2 from portable_math (the portable mode).
inline double hinge_angle(const Vec3& x1, const Vec3& x2, const Vec3& x3, const Vec3& x4, bool portable = false) {
  const Vec3 n1 = (x1 - x3).cross(x1 - x4).normalized();
  const Vec3 n2 = (x2 - x4).cross(x2 - x3).normalized();
  const Vec3 e = (x4 - x3).normalized();
  return portable_math::atan2(n1.cross(n2).dot(e), n1.dot(n2), portable);
}

}  // namespace tidalcrust
