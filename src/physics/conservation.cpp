#include "physics/conservation.hpp"

#include "model/center_of_mass.hpp"

namespace tidalcrust {

namespace {
void add_particle(Conservation& c, double m, const double* x, const double* v) {
  for (int k = 0; k < 3; ++k) c.momentum[k] += m * v[k];
  c.angular_momentum[0] += m * (x[1] * v[2] - x[2] * v[1]);
  c.angular_momentum[1] += m * (x[2] * v[0] - x[0] * v[2]);
  c.angular_momentum[2] += m * (x[0] * v[1] - x[1] * v[0]);
  c.kinetic_energy += 0.5 * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}
}  // namespace

Conservation measure_conservation(const Body& body, const State& state) {
  Conservation c;
  for (std::size_t i = 0; i < body.particle_count(); ++i)
    add_particle(c, body.mass[i], &state.position[3 * i], &state.velocity[3 * i]);
  if (state.perturber.present)
    add_particle(c, state.perturber.mass, state.perturber.position.data(), state.perturber.velocity.data());
  return c;
}

double internal_kinetic_energy(const Body& body, const State& state) {
  const Vec3 center_velocity = body_center_of_mass_velocity(body, state);
  double energy = 0;
  for (std::size_t i = 0; i < body.particle_count(); ++i) {
    double v2 = 0;
    for (int k = 0; k < 3; ++k) {
      double dv = state.velocity[3 * i + k] - center_velocity[k];
      v2 += dv * dv;
    }
    energy += 0.5 * body.mass[i] * v2;
  }
  return energy;
}

}  // namespace tidalcrust
