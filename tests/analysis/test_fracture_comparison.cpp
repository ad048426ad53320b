#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

#include "analysis/fracture_comparison.hpp"
#include "base/errors.hpp"
#include "support/synthetic_encounter.hpp"

using namespace tidalcrust;
using tidalcrust::test_support::synthetic_encounter;

TEST(FractureComparison, SelfComparisonIsIdentical) {
  Checkpoint c = synthetic_encounter(2);
  for (std::size_t s = 0; s < 480; s += 7) c.state.springs.failed[s] = 1;
  const FractureComparison r = compare_fractures(c.body, c.state, c.state);
  EXPECT_EQ(r.jaccard, 1.0);
  EXPECT_EQ(r.ks_distance, 0.0);
  EXPECT_EQ(r.common_failed, r.a.count());
  EXPECT_EQ(r.either_failed, r.b.count());
}

// The same failure set in two states whose positions differ slightly (a snapshot and the end, or
// two time steps) is the same distribution of fractures: KS distance 0, not 1/n.
TEST(FractureComparison, SameFailuresAtDifferentPositionsHaveDistanceZero) {
  Checkpoint a = synthetic_encounter(2);
  for (std::size_t s = 0; s < 480; s += 7) a.state.springs.failed[s] = 1;
  Checkpoint b = a;
  for (std::size_t k = 0; k < b.state.position.size(); ++k)
    b.state.position[k] += 1e-4 * std::sin(static_cast<double>(k) * 1.7);
  b.state.time += 0.5;
  const FractureComparison r = compare_fractures(a.body, a.state, b.state);
  ASSERT_GT(r.a.count(), 10u);
  EXPECT_EQ(r.jaccard, 1.0);
  EXPECT_EQ(r.ks_distance, 0.0);
}

TEST(FractureComparison, OverlapAndDistance) {
  Checkpoint a = synthetic_encounter(1), b = synthetic_encounter(1);
  for (std::size_t s : {0, 1, 2, 3}) a.state.springs.failed[s] = 1;
  for (std::size_t s : {2, 3, 4, 5, 6, 7}) b.state.springs.failed[s] = 1;
  const FractureComparison r = compare_fractures(a.body, a.state, b.state);
  EXPECT_EQ(r.common_failed, 2u);
  EXPECT_EQ(r.either_failed, 8u);
  EXPECT_DOUBLE_EQ(r.jaccard, 0.25);
  EXPECT_GE(r.ks_distance, 0.0);
  EXPECT_LE(r.ks_distance, 1.0);
}

TEST(FractureComparison, KolmogorovSmirnovDistance) {
  EXPECT_EQ(kolmogorov_smirnov_distance({1, 2, 3}, {4, 5, 6}), 1.0);
  EXPECT_EQ(kolmogorov_smirnov_distance({1, 2, 3, 4}, {3, 4, 5, 6}), 0.5);
  EXPECT_EQ(kolmogorov_smirnov_distance({3, 1, 2}, {2, 3, 1}), 0.0);
  EXPECT_EQ(kolmogorov_smirnov_distance({1, 1, 2}, {1, 2, 2}), 1.0 / 3);
  EXPECT_EQ(kolmogorov_smirnov_distance({}, {}), 0.0);
  EXPECT_TRUE(std::isnan(kolmogorov_smirnov_distance({}, {1.0})));
}

TEST(FractureComparison, DifferentBodiesAreRefused) {
  const Checkpoint a = synthetic_encounter(1), b = synthetic_encounter(2);
  try {
    require_same_body(a.body, b.body, "A.h5", "B.h5");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("A.h5"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("particle counts"), std::string::npos);
  }
  Checkpoint c = synthetic_encounter(1);
  std::swap(c.body.springs[0], c.body.springs[1]);
  EXPECT_THROW(require_same_body(a.body, c.body, "A.h5", "C.h5"), InputError);
  EXPECT_NO_THROW(require_same_body(a.body, synthetic_encounter(1).body, "A.h5", "A2.h5"));
}
