#include "analysis/conservation_drift.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tidalcrust {

namespace {
double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}
}  // namespace

ConservationDrift conservation_drift(const std::vector<TimeseriesSample>& samples) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  ConservationDrift drift;
  drift.samples = samples.size();
  if (samples.empty()) {
    drift.max_momentum_change = drift.max_angular_momentum_change = nan;
    drift.max_relative_angular_momentum_change = drift.final_kinetic_energy_change = nan;
    drift.max_kinetic_energy_change = nan;
    return drift;
  }
  const TimeseriesSample& first = samples.front();
  const double l0 = distance(first.angular_momentum, {0, 0, 0});
  const double k0 = first.kinetic_energy;
  for (const auto& s : samples) {
    drift.max_momentum_change = std::max(drift.max_momentum_change, distance(s.momentum, first.momentum));
    drift.max_angular_momentum_change =
        std::max(drift.max_angular_momentum_change, distance(s.angular_momentum, first.angular_momentum));
    drift.max_kinetic_energy_change = std::max(drift.max_kinetic_energy_change, std::abs(s.kinetic_energy - k0));
  }
  drift.max_relative_angular_momentum_change = l0 > 0 ? drift.max_angular_momentum_change / l0 : nan;
  drift.final_kinetic_energy_change = k0 != 0 ? (samples.back().kinetic_energy - k0) / k0 : nan;
  drift.max_kinetic_energy_change = k0 != 0 ? drift.max_kinetic_energy_change / std::abs(k0) : nan;
  return drift;
}

}  // namespace tidalcrust
