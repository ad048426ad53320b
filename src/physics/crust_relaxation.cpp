#include "physics/crust_relaxation.hpp"

#include <cstdint>

#include "forces/hinge_geometry.hpp"
#include "model/center_of_mass.hpp"
#include "base/vec3.hpp"

namespace tidalcrust {

void creep_shell_rest_lengths(const Body& body, State& state, double rate) {
  for (std::size_t n = 0; n < body.spring_count(); ++n) {
    if (body.spring_kind[n] != static_cast<std::uint8_t>(SpringKind::shell)) continue;
    const auto i = static_cast<std::size_t>(body.springs[n][0]);
    const auto j = static_cast<std::size_t>(body.springs[n][1]);
    const double length = (vec3_at(state.position, i) - vec3_at(state.position, j)).norm();
    double& rest = state.springs.rest_length[n];
    rest = rate == 1.0 ? length : rest + rate * (length - rest);
  }
}

void reset_hinge_rest_angles(const Body& body, State& state) {
  for (std::size_t h = 0; h < body.hinge_count(); ++h) {
    const auto& v = body.hinges[h];
    auto at = [&](int k) { return vec3_at(state.position, static_cast<std::size_t>(v[k])); };
    state.hinges.rest_angle[h] = hinge_angle(at(0), at(1), at(2), at(3));
  }
}

double mean_shell_radius(const Body& body, const State& state) {
  const Vec3 centre = body_center_of_mass(body, state);
  double sum = 0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < body.particle_count(); ++i) {
    if (body.species[i] != static_cast<std::uint8_t>(Species::shell)) continue;
    sum += (vec3_at(state.position, i) - centre).norm();
    ++count;
  }
  return count ? sum / static_cast<double>(count) : 0.0;
}

}  // namespace tidalcrust
