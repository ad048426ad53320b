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

double angle_from_subsatellite_deg(const Vec3& r) {
  const double norm = r.norm();
  if (norm == 0) return 90;
  return std::acos(std::clamp(r.dot(subsatellite_direction) / norm, -1.0, 1.0)) * degrees_per_radian;
}

}  // namespace tidalcrust
