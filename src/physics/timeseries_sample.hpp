#pragma once
// One row of /checkpoint/timeseries: the conserved totals (conservation.hpp), the number of
// failed springs and the perturber's offset from the body's centre of mass at the current step.
// Shared by the time-stepping stages.
#include <cstdint>

#include "model/checkpoint.hpp"
#include "physics/conservation.hpp"
#include "physics/orbital_frame.hpp"

namespace tidalcrust {

inline TimeseriesSample sample_timeseries(const Body& body, const State& state) {
  const Conservation c = measure_conservation(body, state);
  TimeseriesSample s;
  s.time = state.time;
  for (auto f : state.springs.failed) s.failed += (f != 0);
  s.kinetic_energy = c.kinetic_energy;
  s.momentum = c.momentum;
  s.angular_momentum = c.angular_momentum;
  if (state.perturber.present) {
    const Vec3 com = body_center_of_mass(body, state);
    for (int k = 0; k < 3; ++k) s.perturber_offset[k] = state.perturber.position[k] - com[k];
  }
  return s;
}

}  // namespace tidalcrust
