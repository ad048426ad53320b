#include "model/center_of_mass.hpp"

namespace tidalcrust {

Vec3 mass_weighted_mean(const Body& body, const double* flat) {
  Vec3 sum = Vec3::Zero();
  double mass = 0;
  for (std::size_t i = 0; i < body.particle_count(); ++i) {
    sum += body.mass[i] * Vec3(flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]);
    mass += body.mass[i];
  }
  return mass > 0 ? Vec3(sum / mass) : Vec3::Zero();
}

Vec3 body_center_of_mass(const Body& body, const State& state) {
  return mass_weighted_mean(body, state.position.data());
}

Vec3 body_center_of_mass_velocity(const Body& body, const State& state) {
  return mass_weighted_mean(body, state.velocity.data());
}

}  // namespace tidalcrust
