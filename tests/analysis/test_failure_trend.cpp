// Whether an encounter ended while its crust was still failing (analysis/failure_trend.hpp,
// docs/failure-rule.md): a run whose failures stopped does not warn, one still failing at its end
// warns once, naming encounter.end_distance, and summary.json records the numbers.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "analysis/failure_trend.hpp"
#include "io/checkpoint_file.hpp"
#include "io/json.hpp"
#include "stages/analysis_stage.hpp"
#include "support/files.hpp"
#include "support/synthetic_encounter.hpp"

namespace tidalcrust {
namespace {

namespace fs = std::filesystem;
using namespace test_support;

std::vector<FailureEvent> failures_at(const std::vector<double>& times) {
  std::vector<FailureEvent> out;
  for (double t : times) out.push_back(FailureEvent{t, 0, 0, 0.0, {}, 0.0});
  return out;
}

/// `count` failures evenly over [from, to).
std::vector<double> evenly(int count, double from, double to) {
  std::vector<double> out;
  for (int k = 0; k < count; ++k) out.push_back(from + (to - from) * k / count);
  return out;
}

TEST(FailureTrend, FailuresThatStoppedDoNotWarn) {
  // The quick-balanced "strong" pattern: failures from 30% to 80% of the time, none later.
  const FailureTrend trend = failure_trend(failures_at(evenly(300, 3.0, 8.0)), 0.0, 10.0);
  EXPECT_EQ(trend.failures, 300u);
  EXPECT_EQ(trend.failures_in_window, 0u);
  EXPECT_DOUBLE_EQ(trend.window_start, 9.0);
  EXPECT_FALSE(trend.still_rising);
  EXPECT_EQ(failure_trend_warning("A", trend, 3.0), "");
  // Two late failures are no trend; nor is no failure at all.
  std::vector<double> times = evenly(20, 3.0, 8.0);
  times.insert(times.end(), {9.5, 9.8});
  EXPECT_FALSE(failure_trend(failures_at(times), 0.0, 10.0).still_rising);
  EXPECT_FALSE(failure_trend({}, 0.0, 10.0).still_rising);
}

TEST(FailureTrend, FailuresAtASteadyRateToTheEndWarnAndNameTheEndDistance) {
  // A steady rate from 30% of the time to the end: 10/70 of them in the last tenth.
  const FailureTrend trend = failure_trend(failures_at(evenly(70, 3.0, 10.0)), 0.0, 10.0);
  EXPECT_EQ(trend.failures_in_window, 9u);  // (9, 10]: the failure at exactly 9.0 is before the window
  EXPECT_TRUE(trend.still_rising);
  EXPECT_EQ(failure_trend_warning("A", trend, 3.0),
            "A: failures still rising at the end: 9 of 70 (13%) in the last 10% of the encounter's time; raise "
            "encounter.end_distance (now 3 R), e.g. --set encounter.end_distance=6");
}

TEST(FailureTrend, SummaryJsonRecordsItAndTheWarningLineFollowsIt) {
  const ScratchFolder scratch("failure_trend_summary");
  for (const bool rising : {false, true}) {
    Checkpoint c = synthetic_encounter(2);  // from t = 0 to t = 2
    // Rising: 3 of 10 after 1.8 (the last tenth); stopped: none after 1.5.
    c.observables.failures = failures_at(rising ? evenly(10, 1.4, 2.0) : evenly(10, 0.5, 1.5));
    const fs::path file = scratch.path / (rising ? "rising.h5" : "stopped.h5");
    const fs::path out = scratch.path / (rising ? "rising" : "stopped");
    write_checkpoint(file, c);
    analyze_encounter(file, c, out);
    const Json summary = Json::parse(read_file(out / "summary.json"));
    const Json& trend = summary.at("failure_trend");
    EXPECT_EQ(trend.at("still_rising").get<bool>(), rising);
    EXPECT_EQ(trend.at("failures").get<std::size_t>(), 10u);
    EXPECT_EQ(trend.at("failures_in_window").get<std::size_t>(), rising ? 3u : 0u) << trend.dump();
    EXPECT_EQ(failure_trend_line("E", c).empty(), !rising);
    EXPECT_TRUE(analysis_is_current(out, c));
  }
}

}  // namespace
}  // namespace tidalcrust
