#include <gtest/gtest.h>

#include <bit>
#include <cmath>

#include "bodies/interior_builder.hpp"

using namespace tidalcrust;

namespace {
InteriorConfig small_interior() {
  InteriorConfig c;
  c.count = 250;
  c.radius = 0.8;
  c.min_separation = 0.14;
  c.spring_distance = 0.32;
  c.max_trials = 1000000;
  return c;
}
}  // namespace

TEST(InteriorBuilder, ReachesCountInsideBallWithMinimumSeparation) {
  const InteriorConfig c = small_interior();
  const InteriorNetwork net = build_interior(c, 5);
  ASSERT_EQ(net.nodes.size(), 250u);
  EXPECT_GE(net.trials, 250);
  for (std::size_t i = 0; i < net.nodes.size(); ++i) {
    EXPECT_LE(net.nodes[i].norm(), c.radius);
    for (std::size_t j = i + 1; j < net.nodes.size(); ++j)
      EXPECT_GE((net.nodes[i] - net.nodes[j]).norm(), c.min_separation) << i << " " << j;
  }
}

TEST(InteriorBuilder, SpringsAreExactlyThePairsCloserThanTheDistanceSorted) {
  const InteriorConfig c = small_interior();
  const InteriorNetwork net = build_interior(c, 5);
  std::vector<std::array<std::int32_t, 2>> expected;
  for (std::size_t i = 0; i < net.nodes.size(); ++i)
    for (std::size_t j = i + 1; j < net.nodes.size(); ++j)
      if ((net.nodes[i] - net.nodes[j]).norm() < c.spring_distance)
        expected.push_back({static_cast<std::int32_t>(i), static_cast<std::int32_t>(j)});
  EXPECT_EQ(net.springs, expected);  // brute force emits i < j in lexicographic order
  EXPECT_GT(net.springs.size(), 5 * net.nodes.size());
}

TEST(InteriorBuilder, SameSeedSameBitsOtherSeedOtherPositions) {
  const InteriorConfig c = small_interior();
  const InteriorNetwork a = build_interior(c, 42), b = build_interior(c, 42), other = build_interior(c, 43);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (std::size_t i = 0; i < a.nodes.size(); ++i)
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(std::bit_cast<std::uint64_t>(a.nodes[i][k]), std::bit_cast<std::uint64_t>(b.nodes[i][k]));
  EXPECT_EQ(a.springs, b.springs);
  EXPECT_EQ(a.trials, b.trials);
  EXPECT_NE(a.nodes[0], other.nodes[0]);
}

TEST(InteriorBuilder, StopsAtMaxTrialsAndReportsTheShortfall) {
  InteriorConfig c = small_interior();
  c.count = 100000;  // cannot fit: the ball holds at most a few hundred nodes this far apart
  c.max_trials = 20000;
  const InteriorNetwork net = build_interior(c, 5);
  EXPECT_EQ(net.trials, 20000);
  EXPECT_LT(net.nodes.size(), 1000u);
  EXPECT_GT(net.nodes.size(), 250u);
}
