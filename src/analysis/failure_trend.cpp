#include "analysis/failure_trend.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace tidalcrust {

FailureTrend failure_trend(const std::vector<FailureEvent>& failures, double start_time, double end_time) {
  FailureTrend trend;
  trend.failures = failures.size();
  trend.end_time = end_time;
  trend.window_start = end_time - failure_trend_window * (end_time - start_time);
  trend.failures_in_window = static_cast<std::size_t>(std::count_if(
      failures.begin(), failures.end(), [&](const FailureEvent& f) { return f.time > trend.window_start; }));
  trend.share_in_window =
      trend.failures == 0 ? 0.0 : static_cast<double>(trend.failures_in_window) / static_cast<double>(trend.failures);
  trend.still_rising = trend.failures_in_window >= failure_trend_min_count && trend.share_in_window >= failure_trend_share;
  return trend;
}

std::string failure_trend_warning(const std::string& name, const FailureTrend& trend, double end_distance) {
  if (!trend.still_rising) return "";
  return fmt::format("{}: failures still rising at the end: {} of {} ({:.0f}%) in the last {:.0f}% of the encounter's "
                     "time; raise encounter.end_distance (now {:g} R), e.g. --set encounter.end_distance={:g}",
                     name, trend.failures_in_window, trend.failures, 100 * trend.share_in_window,
                     100 * failure_trend_window, end_distance, 2 * end_distance);
}

}  // namespace tidalcrust
