#include <gtest/gtest.h>

#include <algorithm>

#include "bodies/cross_support.hpp"
#include "bodies/icosphere.hpp"

using namespace tidalcrust;

TEST(CrossSupport, DirectionSupportIsTheWeakestEigenvalue) {
  EXPECT_NEAR(weakest_direction_support({{1, 0, 0}, {0, 2, 0}, {0, 0, 3}}), 1.0, 1e-12);
  EXPECT_NEAR(weakest_direction_support({{1, 0, 0}, {0, 1, 0}, {1, 1, 0}}), 0.0, 1e-12);  // coplanar
}

TEST(CrossSupport, EveryShellNodeGetsThreeSpringsSpanningSpace) {
  const Icosphere shell = make_icosphere(2);  // 162 nodes
  // Interior nodes on a coarse cubic grid inside r = 0.8: most shell nodes are far from all.
  std::vector<Vec3> interior;
  for (int x = -3; x <= 3; ++x)
    for (int y = -3; y <= 3; ++y)
      for (int z = -3; z <= 3; ++z)
        if (Vec3(x, y, z).norm() * 0.25 < 0.8) interior.push_back(0.25 * Vec3(x, y, z));
  const std::vector<std::array<std::int32_t, 2>> existing{{0, 5}, {1, 5}};
  const auto added = supplementary_cross_springs(interior, shell.nodes, existing, 3);
  std::vector<std::vector<Vec3>> directions(shell.nodes.size());
  for (const auto& [i, s] : existing) directions[static_cast<std::size_t>(s)].push_back(shell.nodes[s] - interior[i]);
  for (const auto& [i, s] : added) {
    EXPECT_TRUE(std::find(existing.begin(), existing.end(), std::array<std::int32_t, 2>{i, s}) == existing.end());
    directions[static_cast<std::size_t>(s)].push_back(shell.nodes[s] - interior[i]);
  }
  for (std::size_t s = 0; s < shell.nodes.size(); ++s) {
    EXPECT_GE(directions[s].size(), 3u) << s;
    EXPECT_LE(directions[s].size(), 12u) << s;
    EXPECT_GE(weakest_direction_support(directions[s]), min_direction_support) << s;
  }
  // The same inputs give the same springs in the same order.
  EXPECT_EQ(supplementary_cross_springs(interior, shell.nodes, existing, 3), added);
  // Minimum 0 (the paper's rule) adds nothing; minimum 1 gives each node its nearest interior node.
  EXPECT_TRUE(supplementary_cross_springs(interior, shell.nodes, existing, 0).empty());
  EXPECT_EQ(supplementary_cross_springs(interior, shell.nodes, existing, 1).size(), shell.nodes.size() - 1);
}
