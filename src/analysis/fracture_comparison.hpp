#pragma once
// How alike the fractures of two encounters are (tidalcrust compare). Spring-by-spring overlap
// only means something when both encounters branch from the same body, so that is checked first.
#include <string>
#include <vector>

#include "model/checkpoint.hpp"
#include "analysis/fracture_analysis.hpp"

namespace tidalcrust {

struct FractureComparison {
  FractureSummary a, b;
  std::size_t common_failed = 0;  ///< springs failed in both
  std::size_t either_failed = 0;  ///< springs failed in at least one
  double jaccard = 0;             ///< common / either; 1 when neither has failures
  double ks_distance = 0;         ///< Kolmogorov-Smirnov distance of the angle-from-subsatellite
                                  ///< distributions, both measured on one geometry (the mean of
                                  ///< the two states' positions): 0 for identical failure sets and
                                  ///< when both are empty, NaN when one is
};

/// Throws InputError (naming `name_a` and `name_b`) unless both bodies have the same particles,
/// species, springs, spring kinds, hinges and faces.
void require_same_body(const Body& a, const Body& b, const std::string& name_a, const std::string& name_b);

/// Largest distance between the empirical distribution functions of two samples.
double kolmogorov_smirnov_distance(std::vector<double> a, std::vector<double> b);

/// Compares the failed shell springs of two states of one body (require_same_body first).
FractureComparison compare_fractures(const Body& body, const State& a, const State& b);

}  // namespace tidalcrust
