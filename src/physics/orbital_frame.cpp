#include "physics/orbital_frame.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tidalcrust {

namespace {
constexpr double degrees_per_radian = 180.0 / std::numbers::pi;

Vec3 mass_weighted_mean(const Body& body, const std::vector<double>& flat) {
  Vec3 sum = Vec3::Zero();
  double mass = 0;
  for (std::size_t i = 0; i < body.particle_count(); ++i) {
    sum += body.mass[i] * vec3_at(flat, i);
    mass += body.mass[i];
  }
  return mass > 0 ? Vec3(sum / mass) : Vec3::Zero();
}
}  // namespace

Vec3 body_center_of_mass(const Body& body, const State& state) {
  return mass_weighted_mean(body, state.position);
}

Vec3 body_center_of_mass_velocity(const Body& body, const State& state) {
  return mass_weighted_mean(body, state.velocity);
}

double longitude_deg(const Vec3& r) { return std::atan2(r.y(), r.x()) * degrees_per_radian; }

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
