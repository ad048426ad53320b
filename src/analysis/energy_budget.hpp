#pragma once
// The energy budget of an encounter from its timeseries (docs/energy-budget.md): how well the
// conserved total is kept, and how much energy the encounter put into the body, next to the
// impulse estimate of the paper's section 1.1. Units: G = M = R = 1, energies G M^2/R.
#include <vector>

#include "model/checkpoint.hpp"
#include "model/encounter.hpp"

namespace tidalcrust {

struct EnergyBudget {
  /// max over samples of |E - E_0| / (3/5), E = TimeseriesSample::conserved_energy(); NaN
  /// when the timeseries has no energy budget (or no samples).
  double max_error = 0;
  double final_error = 0;          ///< (E_end - E_0) / (3/5); NaN likewise
  /// Internal energy after minus before (last sample minus first), in its parts: kinetic energy
  /// about the body's centre of mass, elastic (springs + hinges) and self-gravity.
  double internal_kinetic_change = 0;
  double elastic_change = 0;
  double self_gravity_change = 0;
  double internal_change = 0;      ///< the sum of the three: what the encounter left in the body
  /// Lost from the body's motion on the way (ledger at the end): damping + failures - hinge work.
  double dissipated = 0;
  /// Eq. 4 of the paper (kinetic energy per unit mass ~ Delta v^2) times M, with Delta v of
  /// eq. 3: M Delta v^2 = M (2 G m R/(q^2 V_q))^2. An order of magnitude.
  double impulse_estimate = 0;
  /// The same tidal impulse field integrated over a uniform sphere (Spitzer 1958's straight-line
  /// impulse approximation: Delta E = (4/3) G^2 m^2 M <r^2>/(q^4 V_q^2), <r^2> = 3/5 R^2):
  /// M Delta v^2 / 5.
  double impulse_estimate_uniform_sphere = 0;
};

/// The budget of `samples` (the encounter's timeseries) for the encounter `encounter`.
EnergyBudget energy_budget(const std::vector<TimeseriesSample>& samples, const Encounter& encounter);

}  // namespace tidalcrust
