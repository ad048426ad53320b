#pragma once
// One row of /observables/timeseries: the conserved totals (conservation.hpp) and the number
// of failed springs at the current step. Shared by the time-stepping stages.
#include <cstdint>

#include "checkpoint.hpp"
#include "conservation.hpp"

namespace tidalcrust {

inline TimeseriesSample sample_timeseries(const Body& body, const State& state) {
  const Conservation c = measure_conservation(body, state);
  TimeseriesSample s;
  s.time = state.time;
  for (auto f : state.springs.failed) s.failed += (f != 0);
  s.kinetic_energy = c.kinetic_energy;
  s.momentum = c.momentum;
  s.angular_momentum = c.angular_momentum;
  return s;
}

}  // namespace tidalcrust
