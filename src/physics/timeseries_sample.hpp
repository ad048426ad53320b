#pragma once
// One row of /checkpoint/timeseries: the conserved totals (conservation.hpp), the number of
// failed springs, the perturber's offset from the body's centre of mass and, where the stage
// keeps an energy budget, every term of it (docs/energy-budget.md) at the current step.
// Shared by the time-stepping stages.
#include <cstdint>

#include "forces/force_field.hpp"
#include "model/checkpoint.hpp"
#include "physics/conservation.hpp"
#include "physics/orbital_frame.hpp"

namespace tidalcrust {

/// The sample without the energy budget (its energy terms NaN: not measured).
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

/// The sample with the energy budget: each law's potential energy from `forces` (the stage's
/// force field; self-gravity is O(N^2), one thread) and the stage's accumulated `ledger`.
inline TimeseriesSample sample_timeseries(const Body& body, const State& state, ForceField& forces,
                                          const EnergyLedger& ledger) {
  TimeseriesSample s = sample_timeseries(body, state);
  const Energies e = forces.energies(state);
  s.internal_kinetic_energy = internal_kinetic_energy(body, state);
  s.spring_energy = e.spring + e.liquid;  // a liquid layer's volume energy is elastic too (0 without one)
  s.hinge_energy = e.hinge;
  s.self_gravity_energy = e.self_gravity;
  s.perturber_energy = e.perturber;
  s.damping_dissipated = ledger.damping_dissipated;
  s.failure_released = ledger.failure_released;
  s.hinge_residual_work = ledger.hinge_residual_work;
  return s;
}

}  // namespace tidalcrust
