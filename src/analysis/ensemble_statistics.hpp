#pragma once
// Statistics of an ensemble (docs/ensembles.md): the mean of a quantity over the members with a
// confidence interval, the share of members that cracked with its interval, and whether two
// ensembles differ beyond their spread. Quantiles of Student's t and of the normal distribution
// from Boost.Math. Pure functions of their inputs; no units (a quantity keeps its own).
#include <cstddef>
#include <span>

namespace tidalcrust {

/// The interval level used throughout (95%).
inline constexpr double ensemble_confidence = 0.95;

/// One quantity over an ensemble's members (its finite values; NaN values, e.g. the median angle of
/// a member without failures, are left out and not counted).
struct SampleSummary {
  std::size_t count = 0;          ///< finite values
  double mean = 0;                ///< NaN when count = 0
  double standard_deviation = 0;  ///< sample standard deviation (n - 1); NaN when count < 2
  double standard_error = 0;      ///< standard_deviation / sqrt(count); NaN when count < 2
  /// Student-t interval of the mean at `confidence`: mean -+ t_{(1+c)/2, n-1} standard_error
  /// (the members as independent draws of one distribution); NaN when count < 2.
  double low = 0;
  double high = 0;
  double degrees_of_freedom = 0;  ///< of standard_deviation: count - 1, or count - 2 about a trend
  /// Of summarize_about_trend: the fitted slope d value / d offset (per unit relative change of
  /// q: d value / d ln q); 0 for summarize_sample.
  double slope = 0;
};

/// The summary of `values` with a Student-t interval of the mean at `confidence` (0, 1).
SampleSummary summarize_sample(std::span<const double> values, double confidence = ensemble_confidence);

/// The summary of `values` measured at `offsets` (the members' relative pericenter offsets, one
/// per value) about their least-squares line v = a + b x (docs/ensembles.md): mean = a, the value
/// at the unperturbed encounter (with symmetric offsets and every value finite, exactly the plain
/// mean); standard_deviation = the scatter about the line, sqrt(sum r^2 / (count - 2)), the
/// trajectory noise without the smooth dependence on q the offsets also bring; standard_error =
/// that of a; the interval a -+ t_{(1+c)/2, count-2} standard_error; slope = b. NaN spread when
/// count < 3; the plain summary when the finite values' offsets are all equal.
SampleSummary summarize_about_trend(std::span<const double> values, std::span<const double> offsets,
                                    double confidence = ensemble_confidence);

/// The share of `trials` members with an outcome (a crack) and its Wilson score interval
/// (Wilson 1927; Newcombe 1998, Statistics in Medicine 17, 857, method 3): exact bounds 0 and 1
/// stay inside [0, 1], and it keeps close to its level for small n where the normal
/// approximation does not.
struct ProportionInterval {
  std::size_t successes = 0;
  std::size_t trials = 0;
  double fraction = 0;  ///< successes / trials; NaN when trials = 0
  double low = 0;
  double high = 0;
};
ProportionInterval wilson_interval(std::size_t successes, std::size_t trials, double confidence = ensemble_confidence);

/// Whether two ensembles' means differ beyond their spread: Welch's unequal-variance t test
/// (Welch 1947, Biometrika 34, 28) with the Welch-Satterthwaite degrees of freedom (each sample's
/// own degrees_of_freedom in it).
struct MeanDifference {
  double difference = 0;         ///< mean of b - mean of a
  double low = 0, high = 0;      ///< its interval at `confidence`
  double degrees_of_freedom = 0;
  double p_value = 0;            ///< two-sided
  bool beyond_noise = false;     ///< p_value < 1 - confidence (the interval excludes 0)
};
/// NaN fields (beyond_noise false) when either sample has no spread measured (degrees_of_freedom
/// < 1), or both have zero spread (then difference alone is set).
MeanDifference compare_means(const SampleSummary& a, const SampleSummary& b, double confidence = ensemble_confidence);

}  // namespace tidalcrust
