#include "forces/maxwell_liquid.hpp"

#include <fmt/format.h>

#include "base/errors.hpp"
#include "base/invariant.hpp"
#include "base/vec3.hpp"
#include "forces/spring_force.hpp"

namespace tidalcrust {
namespace {

bool is_liquid(const Body& body, std::size_t s) {
  return body.spring_kind[s] == static_cast<std::uint8_t>(SpringKind::liquid);
}

double length_of(const Body& body, const State& state, std::size_t s) {
  const auto i = static_cast<std::size_t>(body.springs[s][0]);
  const auto j = static_cast<std::size_t>(body.springs[s][1]);
  return (vec3_at(state.position, i) - vec3_at(state.position, j)).norm();
}

}  // namespace

double maxwell_creep_rate(const Body& body, double dt) {
  const double tau = body.liquid.maxwell_time;
  if (!body.liquid.present() || !(tau > 0)) return 0.0;
  if (tau < dt)
    throw InputError(fmt::format("ocean.maxwell_time = {} t_grav is shorter than the time step dt = {} t_grav: the "
                                 "liquid's creep needs tau_M >= dt",
                                 tau, dt));
  return dt / tau;
}

void set_liquid_support(const Body& body, State& state) {
  TIDALCRUST_ASSERT(body.liquid.present(), "a liquid support needs a body with a liquid layer");
  state.liquid_support.assign(3 * body.particle_count(), 0.0);
  for (std::size_t s = 0; s < body.spring_count(); ++s) {
    if (!is_liquid(body, s)) continue;
    const auto i = static_cast<std::size_t>(body.springs[s][0]);
    const auto j = static_cast<std::size_t>(body.springs[s][1]);
    const Vec3 d = vec3_at(state.position, i) - vec3_at(state.position, j);
    const Vec3 f = SpringEvaluator(state.springs.rest_length[s], state.springs.stiffness[s], 0.0).force(d, Vec3::Zero());
    for (int k = 0; k < 3; ++k) {
      state.liquid_support[3 * i + static_cast<std::size_t>(k)] += f[k];
      state.liquid_support[3 * j + static_cast<std::size_t>(k)] -= f[k];
    }
    state.springs.rest_length[s] = d.norm();
  }
}

double creep_liquid_springs(const Body& body, State& state, double rate) {
  TIDALCRUST_ASSERT(rate > 0 && rate <= 1, "the creep fraction dt / tau_M must lie in (0, 1]");
  const double kept = (1 - rate) * (1 - rate);
  double dissipated = 0;
  for (std::size_t s = 0; s < body.spring_count(); ++s) {
    if (!is_liquid(body, s)) continue;
    const double stretch = length_of(body, state, s) - state.springs.rest_length[s];
    dissipated += 0.5 * state.springs.stiffness[s] * stretch * stretch * (1 - kept);
    state.springs.rest_length[s] += rate * stretch;
  }
  return dissipated;
}

double liquid_support_energy(const std::vector<double>& support, const double* position) {
  double e = 0;
  for (std::size_t k = 0; k < support.size(); ++k) e -= support[k] * position[k];
  return e;
}

}  // namespace tidalcrust
