#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "analysis/ensemble_statistics.hpp"
#include "base/random.hpp"

using namespace tidalcrust;

// Reference values: scipy 1.10 (stats.t.ppf, ttest_ind); Newcombe (1998), Statistics in Medicine 17, 857, Table I.
TEST(EnsembleStatistics, StudentIntervalMatchesTheTQuantile) {
  // x = 1..5: mean 3, sd sqrt(2.5); t_{0.975, 4} = 2.776445 (stats.t.ppf): 3 -+ 2.776445 sqrt(1/2).
  const std::vector<double> x = {1, 2, 3, 4, 5};
  const SampleSummary s = summarize_sample(x);
  EXPECT_EQ(s.count, 5u);
  EXPECT_DOUBLE_EQ(s.mean, 3.0);
  EXPECT_DOUBLE_EQ(s.standard_deviation, std::sqrt(2.5));
  EXPECT_NEAR(s.low, 1.036757, 1e-6);
  EXPECT_NEAR(s.high, 4.963243, 1e-6);
  // NaN values are left out; one value has no spread.
  const std::vector<double> with_nan = {1, std::numeric_limits<double>::quiet_NaN(), 2, 3, 4, 5};
  EXPECT_EQ(summarize_sample(with_nan).count, 5u);
  EXPECT_DOUBLE_EQ(summarize_sample(with_nan).high, s.high);
  const std::vector<double> one = {7};
  EXPECT_EQ(summarize_sample(one).mean, 7);
  EXPECT_TRUE(std::isnan(summarize_sample(one).low));
}

// The interval covers the true mean of a known distribution at its level: 4,000 samples of 6
// uniform draws (mean 1/2), our own generator; coverage 95% +- 3 binomial sigma (1.0%).
TEST(EnsembleStatistics, IntervalCoversTheMeanOfAKnownDistributionAtItsLevel) {
  Random random(12345);
  int covered = 0;
  const int samples = 4000;
  for (int i = 0; i < samples; ++i) {
    std::vector<double> draws;
    for (int k = 0; k < 6; ++k) draws.push_back(random.uniform());
    const SampleSummary s = summarize_sample(draws);
    covered += s.low <= 0.5 && 0.5 <= s.high;
  }
  const double coverage = static_cast<double>(covered) / samples;
  EXPECT_NEAR(coverage, 0.95, 3 * std::sqrt(0.95 * 0.05 / samples)) << coverage;
}

TEST(EnsembleStatistics, WilsonIntervalMatchesNewcombe) {
  // Newcombe 1998 Table I, method 3: 81/263 -> 0.2553, 0.3662; 15/148 -> 0.0624, 0.1605;
  // 0/20 -> 0, 0.1611; 1/29 -> 0.0061, 0.1718.
  const struct { std::size_t r, n; double low, high; } cases[] = {
      {81, 263, 0.2553, 0.3662}, {15, 148, 0.0624, 0.1605}, {0, 20, 0.0, 0.1611}, {1, 29, 0.0061, 0.1718}};
  for (const auto& c : cases) {
    const ProportionInterval p = wilson_interval(c.r, c.n);
    EXPECT_NEAR(p.low, c.low, 6e-5) << c.r << "/" << c.n;
    EXPECT_NEAR(p.high, c.high, 6e-5) << c.r << "/" << c.n;
  }
  const ProportionInterval all = wilson_interval(5, 5);
  EXPECT_EQ(all.high, 1.0);
  EXPECT_NEAR(all.low, 0.5655, 1e-4);  // 5 of 5: a crack more likely than not, beyond the noise
  EXPECT_TRUE(std::isnan(wilson_interval(0, 0).fraction));
}

TEST(EnsembleStatistics, WelchComparisonMatchesScipy) {
  // x = 1..5, y = 3..8: df = (1/2 + 7/12)^2 / ((1/2)^2/4 + (7/12)^2/5) = 845/94 exactly; scipy 1.10
  // (Debian bookworm) stats.ttest_ind(y, x, equal_var=False): t = 2.401922, p = 0.03980308;
  // stats.t.ppf(0.975, 845/94) * sqrt(1/2 + 7/12) around 2.5: 0.1450474 .. 4.8549526.
  const std::vector<double> x = {1, 2, 3, 4, 5}, y = {3, 4, 5, 6, 7, 8};
  const MeanDifference d = compare_means(summarize_sample(x), summarize_sample(y));
  EXPECT_DOUBLE_EQ(d.difference, 2.5);
  EXPECT_NEAR(d.degrees_of_freedom, 845.0 / 94.0, 1e-12);
  EXPECT_NEAR(d.p_value, 0.03980308, 1e-8);
  EXPECT_NEAR(d.low, 0.1450474, 1e-7);
  EXPECT_NEAR(d.high, 4.8549526, 1e-7);
  EXPECT_TRUE(d.beyond_noise);
  // Overlapping samples: inside the noise.
  const std::vector<double> z = {2, 3, 4, 5, 6};
  const MeanDifference same = compare_means(summarize_sample(x), summarize_sample(z));
  EXPECT_FALSE(same.beyond_noise);
  EXPECT_LT(same.low, 0);
  EXPECT_GT(same.high, 0);
}

// The ensemble's summary about the members' trend in q (docs/ensembles.md): x = -1, 0, 1 and
// v = 1, 3, 2 by hand: slope 1/2, line at 0 = 2, residuals -1/2, 1, -1/2, sd = sqrt(3/2) with 1
// degree of freedom, se = sd / sqrt(3), t_{0.975, 1} = 12.706205.
TEST(EnsembleStatistics, SummaryAboutTheTrendRemovesTheSmoothDependenceOnTheOffset) {
  const std::vector<double> x = {-1, 0, 1}, v = {1, 3, 2};
  const SampleSummary s = summarize_about_trend(v, x);
  EXPECT_DOUBLE_EQ(s.slope, 0.5);
  EXPECT_DOUBLE_EQ(s.mean, 2.0);
  EXPECT_DOUBLE_EQ(s.standard_deviation, std::sqrt(1.5));
  EXPECT_EQ(s.degrees_of_freedom, 1.0);
  EXPECT_NEAR(s.high - s.mean, 12.706205 * std::sqrt(1.5 / 3), 1e-5);
  // A pure trend has no scatter about it, while the plain sd counts the trend as spread.
  const std::vector<double> offsets = {-0.004, -0.002, 0, 0.002, 0.004}, line = {10, 12, 14, 16, 18};
  const SampleSummary t = summarize_about_trend(line, offsets);
  EXPECT_NEAR(t.standard_deviation, 0, 1e-12);
  EXPECT_NEAR(t.slope, 1000, 1e-9);
  EXPECT_DOUBLE_EQ(t.mean, 14);
  EXPECT_GT(summarize_sample(line).standard_deviation, 3);
  // A member without the value is left out, the line fitted through the others.
  const std::vector<double> gap = {10, std::numeric_limits<double>::quiet_NaN(), 14, 16, 18};
  EXPECT_EQ(summarize_about_trend(gap, offsets).count, 4u);
  EXPECT_NEAR(summarize_about_trend(gap, offsets).mean, 14, 1e-12);
  // Two values: no scatter can be measured.
  const std::vector<double> two = {1, 2}, two_x = {-1, 1};
  EXPECT_TRUE(std::isnan(summarize_about_trend(two, two_x).standard_deviation));
}
