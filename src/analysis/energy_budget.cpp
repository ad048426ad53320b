#include "analysis/energy_budget.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/conservation.hpp"
#include "physics/encounter_estimates.hpp"

namespace tidalcrust {

EnergyBudget energy_budget(const std::vector<TimeseriesSample>& samples, const Encounter& encounter) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  EnergyBudget b;
  // Delta v of eq. 3 does not depend on Young's modulus (any value > 0 will do).
  const double delta_v = estimate_encounter(encounter, 1.0).delta_v;
  const double body_mass = 1.0;  // M, the unit of mass
  b.impulse_estimate = body_mass * delta_v * delta_v;
  b.impulse_estimate_uniform_sphere = b.impulse_estimate / 5;
  if (samples.empty() || !std::isfinite(samples.front().conserved_energy())) {
    b.max_error = b.final_error = b.internal_kinetic_change = b.elastic_change = b.self_gravity_change =
        b.internal_change = b.dissipated = nan;
    return b;
  }
  const TimeseriesSample& first = samples.front();
  const TimeseriesSample& last = samples.back();
  const double e0 = first.conserved_energy();
  for (const auto& s : samples) b.max_error = std::max(b.max_error, std::abs(s.conserved_energy() - e0));
  b.max_error /= uniform_sphere_binding_energy;
  b.final_error = (last.conserved_energy() - e0) / uniform_sphere_binding_energy;
  b.internal_kinetic_change = last.internal_kinetic_energy - first.internal_kinetic_energy;
  b.elastic_change = (last.spring_energy + last.hinge_energy) - (first.spring_energy + first.hinge_energy);
  b.self_gravity_change = last.self_gravity_energy - first.self_gravity_energy;
  b.internal_change = b.internal_kinetic_change + b.elastic_change + b.self_gravity_change;
  b.dissipated = (last.damping_dissipated + last.failure_released - last.hinge_residual_work) -
                 (first.damping_dissipated + first.failure_released - first.hinge_residual_work);
  return b;
}

}  // namespace tidalcrust
