#include "physics/orbital_frame.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tidalcrust {

namespace {
constexpr double degrees_per_radian = 180.0 / std::numbers::pi;
}  // namespace

double longitude_deg(const Vec3& r) { return std::atan2(r.y(), r.x()) * degrees_per_radian; }

double planetocentric_longitude_deg(double orbital_longitude_deg) {
  const double longitude = orbital_longitude_deg - subsatellite_longitude_deg;
  return longitude > 180 ? longitude - 360 : longitude <= -180 ? longitude + 360 : longitude;
}

double latitude_deg(const Vec3& r) {
  const double norm = r.norm();
  if (norm == 0) return 0;
  return std::asin(std::clamp(r.z() / norm, -1.0, 1.0)) * degrees_per_radian;
}

double angle_from_subsatellite_deg(const Vec3& r, const Vec3& subsatellite) {
  const double norm = r.norm();
  if (norm == 0) return 90;
  return std::acos(std::clamp(r.dot(subsatellite) / norm, -1.0, 1.0)) * degrees_per_radian;
}

namespace {
/// Rotation by `deg` degrees about z or x; exactly the identity for 0.
Matrix3 rotation_z(double deg) {
  const double a = deg / degrees_per_radian, c = std::cos(a), s = std::sin(a);
  Matrix3 m;
  m << c, -s, 0, s, c, 0, 0, 0, 1;
  return m;
}
Matrix3 rotation_x(double deg) {
  const double a = deg / degrees_per_radian, c = std::cos(a), s = std::sin(a);
  Matrix3 m;
  m << 1, 0, 0, 0, c, -s, 0, s, c;
  return m;
}
}  // namespace

Matrix3 orbit_rotation(const OrbitOrientation& o) {
  if (o.is_default()) return Matrix3::Identity();
  return rotation_z(o.ascending_node) * rotation_x(o.inclination) * rotation_z(o.argument_of_pericenter - 90.0);
}

Vec3 subsatellite_direction_of(const OrbitOrientation& o) {
  if (o.is_default()) return subsatellite_direction;
  return orbit_rotation(o) * subsatellite_direction;
}

}  // namespace tidalcrust
