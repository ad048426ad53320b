#include "analysis/ensemble_statistics.hpp"

#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "base/invariant.hpp"

namespace tidalcrust {

namespace {
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

/// The two-sided quantile t_{(1+c)/2, dof}.
double t_quantile(double confidence, double degrees_of_freedom) {
  return boost::math::quantile(boost::math::students_t(degrees_of_freedom), 0.5 * (1.0 + confidence));
}
}  // namespace

SampleSummary summarize_sample(std::span<const double> values, double confidence) {
  TIDALCRUST_ASSERT(confidence > 0 && confidence < 1, "confidence must be in (0, 1)");
  SampleSummary s;
  double sum = 0;
  for (double v : values)
    if (std::isfinite(v)) sum += v, ++s.count;
  s.mean = s.count > 0 ? sum / static_cast<double>(s.count) : nan;
  s.standard_deviation = s.standard_error = s.low = s.high = nan;
  if (s.count < 2) return s;
  double squares = 0;  // two passes: no cancellation for values far from 0 (energies ~ 1e-3 +- 1e-6)
  for (double v : values)
    if (std::isfinite(v)) squares += (v - s.mean) * (v - s.mean);
  const double n = static_cast<double>(s.count);
  s.standard_deviation = std::sqrt(squares / (n - 1));
  s.standard_error = s.standard_deviation / std::sqrt(n);
  s.degrees_of_freedom = n - 1;
  const double half = t_quantile(confidence, n - 1) * s.standard_error;
  s.low = s.mean - half;
  s.high = s.mean + half;
  return s;
}

SampleSummary summarize_about_trend(std::span<const double> values, std::span<const double> offsets,
                                    double confidence) {
  TIDALCRUST_ASSERT(values.size() == offsets.size(), "one offset per value");
  std::vector<double> v, x;
  for (std::size_t i = 0; i < values.size(); ++i)
    if (std::isfinite(values[i])) v.push_back(values[i]), x.push_back(offsets[i]);
  SampleSummary plain = summarize_sample(v, confidence);
  if (v.size() < 3) {
    plain.standard_deviation = plain.standard_error = plain.low = plain.high = nan;
    plain.degrees_of_freedom = 0;
    return plain;
  }
  const double n = static_cast<double>(v.size());
  double x_mean = 0;
  for (double xi : x) x_mean += xi;
  x_mean /= n;
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    sxx += (x[i] - x_mean) * (x[i] - x_mean);
    sxy += (x[i] - x_mean) * (v[i] - plain.mean);
  }
  if (!(sxx > 0)) return plain;
  SampleSummary s = plain;
  s.slope = sxy / sxx;
  s.mean = plain.mean - s.slope * x_mean;  // the line at offset 0
  double squares = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double r = v[i] - plain.mean - s.slope * (x[i] - x_mean);
    squares += r * r;
  }
  s.degrees_of_freedom = n - 2;
  s.standard_deviation = std::sqrt(squares / (n - 2));
  s.standard_error = s.standard_deviation * std::sqrt(1 / n + x_mean * x_mean / sxx);
  const double half = t_quantile(confidence, n - 2) * s.standard_error;
  s.low = s.mean - half;
  s.high = s.mean + half;
  return s;
}

ProportionInterval wilson_interval(std::size_t successes, std::size_t trials, double confidence) {
  TIDALCRUST_ASSERT(successes <= trials, "more successes than trials");
  ProportionInterval p{successes, trials, nan, nan, nan};
  if (trials == 0) return p;
  const double n = static_cast<double>(trials);
  const double f = static_cast<double>(successes) / n;
  const double z = boost::math::quantile(boost::math::normal(), 0.5 * (1.0 + confidence));
  const double centre = (f + z * z / (2 * n)) / (1 + z * z / n);
  const double half = z / (1 + z * z / n) * std::sqrt(f * (1 - f) / n + z * z / (4 * n * n));
  p.fraction = f;
  // The bounds are exact at 0 and 1 successes-of-n limits; clamp only the round-off.
  p.low = successes == 0 ? 0.0 : std::max(0.0, centre - half);
  p.high = successes == trials ? 1.0 : std::min(1.0, centre + half);
  return p;
}

MeanDifference compare_means(const SampleSummary& a, const SampleSummary& b, double confidence) {
  MeanDifference d{b.mean - a.mean, nan, nan, nan, nan, false};
  if (!(a.degrees_of_freedom >= 1 && b.degrees_of_freedom >= 1)) return d;
  const double va = a.standard_error * a.standard_error, vb = b.standard_error * b.standard_error;
  if (!(va + vb > 0)) return d;
  d.degrees_of_freedom = (va + vb) * (va + vb) / (va * va / a.degrees_of_freedom + vb * vb / b.degrees_of_freedom);
  const double se = std::sqrt(va + vb);
  const double half = t_quantile(confidence, d.degrees_of_freedom) * se;
  d.low = d.difference - half;
  d.high = d.difference + half;
  const double t = std::abs(d.difference) / se;
  d.p_value = 2 * boost::math::cdf(boost::math::complement(boost::math::students_t(d.degrees_of_freedom), t));
  d.beyond_noise = d.p_value < 1 - confidence;
  return d;
}

}  // namespace tidalcrust
