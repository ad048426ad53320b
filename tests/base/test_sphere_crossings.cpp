#include "base/sphere_crossings.hpp"

#include <gtest/gtest.h>

namespace tidalcrust {
namespace {

// Exact cases: the distances are small integers, so every comparison is exact.
TEST(SphereCrossings, FromOutsideThroughTheCentreBothCrossingsAscending) {
  const auto t = sphere_crossings(Vec3(-3, 0, 0), Vec3(1, 0, 0), 1.0);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0], 2.0);
  EXPECT_EQ(t[1], 4.0);
}

TEST(SphereCrossings, FromInsideOnlyTheExitAhead) {
  const auto t = sphere_crossings(Vec3(0, 0, 0.5), Vec3(0, 0, 1), 2.0);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0], 1.5);
}

TEST(SphereCrossings, PointingAwayMissingOrTangentGivesNone) {
  EXPECT_TRUE(sphere_crossings(Vec3(3, 0, 0), Vec3(1, 0, 0), 1.0).empty());   // sphere behind
  EXPECT_TRUE(sphere_crossings(Vec3(-3, 2, 0), Vec3(1, 0, 0), 1.0).empty());  // passes by
  EXPECT_TRUE(sphere_crossings(Vec3(-3, 1, 0), Vec3(1, 0, 0), 1.0).empty());  // tangent
}

}  // namespace
}  // namespace tidalcrust
