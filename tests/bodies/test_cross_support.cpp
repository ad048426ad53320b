#include <gtest/gtest.h>

#include <algorithm>

#include "bodies/cross_support.hpp"
#include "bodies/icosphere.hpp"
#include "bodies/interior_builder.hpp"

using namespace tidalcrust;

namespace {

/// The plain definition supplementary_cross_springs had before it searched on a grid (kept
/// here as the reference only): for each shell node that needs springs, ALL interior nodes
/// sorted by (squared distance, index), walked in that order.
std::vector<std::array<std::int32_t, 2>> reference_supplementary_cross_springs(
    const std::vector<Vec3>& interior, const std::vector<Vec3>& shell,
    const std::vector<std::array<std::int32_t, 2>>& existing, int minimum) {
  std::vector<std::array<std::int32_t, 2>> added;
  if (minimum <= 0 || interior.empty()) return added;
  std::vector<std::vector<std::int32_t>> partners(shell.size());
  for (const auto& [i, s] : existing) partners[static_cast<std::size_t>(s)].push_back(i);
  std::vector<std::pair<double, std::int32_t>> by_distance(interior.size());
  for (std::size_t s = 0; s < shell.size(); ++s) {
    auto& joined = partners[s];
    auto directions = [&] {
      std::vector<Vec3> out;
      for (std::int32_t i : joined) out.push_back(shell[s] - interior[static_cast<std::size_t>(i)]);
      return out;
    };
    auto satisfied = [&] {
      const auto count = static_cast<int>(joined.size());
      if (count >= 12) return true;
      if (count < minimum) return false;
      return minimum < 3 || weakest_direction_support(directions()) >= min_direction_support;
    };
    if (satisfied()) continue;
    for (std::size_t i = 0; i < interior.size(); ++i)
      by_distance[i] = {(shell[s] - interior[i]).squaredNorm(), static_cast<std::int32_t>(i)};
    std::sort(by_distance.begin(), by_distance.end());
    for (const auto& [d2, i] : by_distance) {
      if (satisfied()) break;
      if (std::find(joined.begin(), joined.end(), i) != joined.end()) continue;
      if (static_cast<int>(joined.size()) >= minimum) {
        const double before = weakest_direction_support(directions());
        joined.push_back(i);
        const double after = weakest_direction_support(directions());
        joined.pop_back();
        if (!(after > before)) continue;
      }
      joined.push_back(i);
      added.push_back({i, static_cast<std::int32_t>(s)});
    }
  }
  return added;
}

/// Every (interior, shell) pair closer than d: the paper's cross springs, as the builder makes them.
std::vector<std::array<std::int32_t, 2>> pairs_closer_than(const std::vector<Vec3>& interior,
                                                          const std::vector<Vec3>& shell, double d) {
  std::vector<std::array<std::int32_t, 2>> pairs;
  for (std::size_t i = 0; i < interior.size(); ++i)
    for (std::size_t s = 0; s < shell.size(); ++s)
      if ((interior[i] - shell[s]).norm() < d) pairs.push_back({static_cast<std::int32_t>(i), static_cast<std::int32_t>(s)});
  return pairs;
}

std::vector<Vec3> random_interior(int count, double radius, double min_separation) {
  InteriorConfig c;
  c.count = count;
  c.radius = radius;
  c.min_separation = min_separation;
  c.spring_distance = 2 * min_separation;
  c.max_trials = 1000000;
  return build_interior(c, 7).nodes;
}

}  // namespace

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

TEST(CrossSupport, GridSearchSelectsExactlyWhatTheFullSortSelects) {
  const Icosphere shell = make_icosphere(3);  // 642 nodes
  // A body like the built ones (interior just inside the shell, some cross springs from d_C),
  // one whose interior is a small ball far from the shell (many rings, then the all-nodes
  // ring), and a cubic lattice (many exactly equal distances: ties broken by index).
  std::vector<Vec3> lattice;
  for (int x = -3; x <= 3; ++x)
    for (int y = -3; y <= 3; ++y)
      for (int z = -3; z <= 3; ++z)
        if (Vec3(x, y, z).norm() * 0.25 < 0.8) lattice.push_back(0.25 * Vec3(x, y, z));
  const std::vector<Vec3> near_shell = random_interior(1500, 0.93, 0.06);
  const std::vector<Vec3> far_ball = random_interior(200, 0.3, 0.03);
  struct Case {
    const char* name;
    const std::vector<Vec3>& interior;
    double cross_distance;
  };
  for (const Case& c : {Case{"near shell", near_shell, 0.12}, Case{"far ball", far_ball, 0.0},
                        Case{"lattice", lattice, 0.3}}) {
    const auto existing = pairs_closer_than(c.interior, shell.nodes, c.cross_distance);
    for (int minimum : {1, 2, 3, 4, 6, 12}) {
      const auto expected = reference_supplementary_cross_springs(c.interior, shell.nodes, existing, minimum);
      ASSERT_FALSE(expected.empty()) << c.name << ", minimum " << minimum;
      EXPECT_EQ(supplementary_cross_springs(c.interior, shell.nodes, existing, minimum), expected)
          << c.name << ", minimum " << minimum;
    }
  }
}
