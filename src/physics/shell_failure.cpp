#include "physics/shell_failure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "base/vec3.hpp"
#include "forces/spring_force.hpp"

namespace tidalcrust {
namespace {

bool is_unfailed_shell(const Body& body, const State& state, std::size_t n) {
  return body.spring_kind[n] == static_cast<std::uint8_t>(SpringKind::shell) && !state.springs.failed[n];
}

}  // namespace

double spring_strain(const Body& body, const State& state, std::size_t n) {
  const auto i = static_cast<std::size_t>(body.springs[n][0]);
  const auto j = static_cast<std::size_t>(body.springs[n][1]);
  const double length = (vec3_at(state.position, i) - vec3_at(state.position, j)).norm();
  const double rest = state.springs.rest_length[n];
  return (length - rest) / rest;
}

double max_abs_shell_strain(const Body& body, const State& state) {
  double largest = 0;
  for (std::size_t n = 0; n < body.spring_count(); ++n)
    if (is_unfailed_shell(body, state, n)) largest = std::max(largest, std::abs(spring_strain(body, state, n)));
  return largest;
}

double max_shell_tension(const Body& body, const State& state) {
  double largest = 0;
  for (std::size_t n = 0; n < body.spring_count(); ++n)
    if (is_unfailed_shell(body, state, n)) largest = std::max(largest, spring_strain(body, state, n));
  return largest;
}

std::optional<FailureEvent> fail_most_strained_shell_spring(const Body& body, State& state, double failure_strain,
                                                            double failed_stiffness_factor) {
  std::optional<std::size_t> worst;
  double worst_strain = failure_strain;
  for (std::size_t n = 0; n < body.spring_count(); ++n) {
    if (!is_unfailed_shell(body, state, n)) continue;
    const double strain = spring_strain(body, state, n);
    if (strain > worst_strain) {  // strict: ties keep the lowest index
      worst_strain = strain;
      worst = n;
    }
  }
  if (!worst) return std::nullopt;
  const std::size_t n = *worst;
  const auto i = static_cast<std::size_t>(body.springs[n][0]);
  const auto j = static_cast<std::size_t>(body.springs[n][1]);
  // The energy budget's failure term: the spring's elastic energy at this strain before and
  // after its stiffness drops (the same evaluator as the force law; shell springs are linear).
  const double length = (vec3_at(state.position, i) - vec3_at(state.position, j)).norm();
  auto elastic_energy = [&] {
    return SpringEvaluator(state.springs.rest_length[n], state.springs.stiffness[n], 0.0).force_and_energy(length, 0).energy;
  };
  const double energy_before = elastic_energy();
  state.springs.stiffness[n] *= failed_stiffness_factor;
  state.springs.failed[n] = 1;
  const Vec3 mid = 0.5 * (vec3_at(state.position, i) + vec3_at(state.position, j));
  FailureEvent event;
  event.time = state.time;
  event.step = state.step;
  event.spring = static_cast<std::int32_t>(n);
  event.strain = worst_strain;
  event.position = {mid.x(), mid.y(), mid.z()};
  event.released_energy = energy_before - elastic_energy();
  return event;
}

}  // namespace tidalcrust
