#pragma once
// Whether an encounter ended while its crust was still failing (docs/failure-rule.md, "Did the
// encounter run long enough?"): the share of its failures in the last tenth of its time. A run
// whose failures have stopped has none there; one at a steady rate has a tenth of them there.
#include <cstddef>
#include <string>
#include <vector>

#include "model/checkpoint.hpp"

namespace tidalcrust {

/// The window: the last this share of the encounter's time.
inline constexpr double failure_trend_window = 0.1;
/// Still rising: at least this share of the failures in the window (the final rate at least half
/// the encounter's mean rate) ...
inline constexpr double failure_trend_share = 0.05;
/// ... and at least this many (one or two late failures are no trend).
inline constexpr std::size_t failure_trend_min_count = 3;

struct FailureTrend {
  std::size_t failures = 0;            ///< failures of the encounter
  std::size_t failures_in_window = 0;  ///< of them, at times > window_start
  double window_start = 0;             ///< t_grav
  double end_time = 0;                 ///< t_grav
  double share_in_window = 0;          ///< failures_in_window / failures (0 without failures)
  bool still_rising = false;
};

/// The trend of `failures` (one stage's log) over the stage from start_time to end_time.
FailureTrend failure_trend(const std::vector<FailureEvent>& failures, double start_time, double end_time);

/// The warning line for an encounter still failing at its end ("" when it is not), naming the key
/// to raise: "NAME: failures still rising at the end (...); raise encounter.end_distance ...".
std::string failure_trend_warning(const std::string& name, const FailureTrend& trend, double end_distance);

}  // namespace tidalcrust
