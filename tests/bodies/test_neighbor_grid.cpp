#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bodies/neighbor_grid.hpp"
#include "base/random.hpp"

using namespace tidalcrust;

namespace {
std::vector<Vec3> random_points(std::size_t n, double half_width, std::uint64_t seed) {
  Random random(seed);
  std::vector<Vec3> points;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = random.uniform(-half_width, half_width);
    const double y = random.uniform(-half_width, half_width);
    const double z = random.uniform(-half_width, half_width);
    points.emplace_back(x, y, z);
  }
  return points;
}
}  // namespace

TEST(NeighborGrid, QueriesMatchBruteForceIncludingPointsOutsideTheBox) {
  // The box covers only [-1, 1]^3, the points spread over [-1.5, 1.5]^3.
  const auto points = random_points(400, 1.5, 3);
  NeighborGrid grid(Vec3(-1, -1, -1), Vec3(1, 1, 1), 0.2);
  for (const auto& p : points) grid.insert(p);
  for (double r : {0.05, 0.2, 0.45}) {
    for (std::size_t q = 0; q < points.size(); q += 7) {
      std::vector<std::int32_t> expected;
      for (std::size_t j = 0; j < points.size(); ++j)
        if ((points[j] - points[q]).squaredNorm() < r * r) expected.push_back(static_cast<std::int32_t>(j));
      EXPECT_EQ(grid.closer_than(points[q], r), expected) << "r " << r << " query " << q;
      EXPECT_TRUE(grid.any_closer_than(points[q], r));  // finds the point itself
    }
  }
  EXPECT_FALSE(grid.any_closer_than(Vec3(5, 5, 5), 0.5));
}

TEST(NeighborGrid, MinPairDistanceMatchesBruteForce) {
  const auto points = random_points(300, 1.0, 11);
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t j = i + 1; j < points.size(); ++j) best = std::min(best, (points[i] - points[j]).norm());
  EXPECT_EQ(min_pair_distance(points), best);
  // Two far-apart points: the first cell size finds no pair and must widen.
  EXPECT_DOUBLE_EQ(min_pair_distance({Vec3(0, 0, 0), Vec3(3, 4, 0)}), 5.0);
  EXPECT_EQ(min_pair_distance({Vec3(1, 2, 3)}), 0.0);
}
