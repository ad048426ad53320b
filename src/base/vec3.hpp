#pragma once
// 3-vectors and 3x3 matrices for geometry outside the hot loops. State arrays stay flat [N*3] doubles.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace tidalcrust {

using Vec3 = Eigen::Vector3d;
using Matrix3 = Eigen::Matrix3d;  ///< rotations of the frame (physics/orbital_frame.hpp)

/// Reads particle i of a flat [N*3] array.
inline Vec3 vec3_at(const std::vector<double>& flat, std::size_t i) {
  return {flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
}

/// Writes particle i of a flat [N*3] array.
inline void set_vec3(std::vector<double>& flat, std::size_t i, const Vec3& v) {
  flat[3 * i] = v.x();
  flat[3 * i + 1] = v.y();
  flat[3 * i + 2] = v.z();
}

}  // namespace tidalcrust
