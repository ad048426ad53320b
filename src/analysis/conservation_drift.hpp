#pragma once
// How far the sampled conserved quantities drift over a stage (analyze's conservation errors):
// changes relative to the first timeseries sample (body + perturber, about the origin).
#include <cstddef>
#include <vector>

#include "model/checkpoint.hpp"

namespace tidalcrust {

struct ConservationDrift {
  std::size_t samples = 0;
  double max_momentum_change = 0;          ///< max |P - P0|, M sqrt(GM/R)
  double max_angular_momentum_change = 0;  ///< max |L - L0|, M R sqrt(GM/R)
  double max_relative_angular_momentum_change = 0;  ///< max |L - L0| / |L0| (NaN if L0 = 0)
  double final_kinetic_energy_change = 0;  ///< (K_end - K0) / K0 (NaN if K0 = 0)
  double max_kinetic_energy_change = 0;    ///< max |K - K0| / K0 (NaN if K0 = 0)
};

/// All NaN except `samples` when there are no samples.
ConservationDrift conservation_drift(const std::vector<TimeseriesSample>& samples);

}  // namespace tidalcrust
