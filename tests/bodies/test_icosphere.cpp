#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <set>

#include "forces/hinge_geometry.hpp"
#include "bodies/icosphere.hpp"
#include "bodies/shell_hinges.hpp"

using namespace tidalcrust;

TEST(Icosphere, ExactCountsAndEulerCharacteristicForLevelsZeroToFour) {
  for (int level = 0; level <= 4; ++level) {
    const Icosphere s = make_icosphere(level);
    const long p = 1L << (2 * level);  // 4^L
    EXPECT_EQ(s.nodes.size(), static_cast<std::size_t>(10 * p + 2)) << "level " << level;
    EXPECT_EQ(s.edges.size(), static_cast<std::size_t>(30 * p)) << "level " << level;
    EXPECT_EQ(s.faces.size(), static_cast<std::size_t>(20 * p)) << "level " << level;
    EXPECT_EQ(static_cast<long>(s.nodes.size()) - static_cast<long>(s.edges.size()) +
                  static_cast<long>(s.faces.size()),
              2);
  }
}

TEST(Icosphere, NodesOnUnitSphereFacesOutwardCounterClockwise) {
  const Icosphere s = make_icosphere(3);
  for (const auto& p : s.nodes) EXPECT_NEAR(p.norm(), 1.0, 1e-15);
  for (const auto& [a, b, c] : s.faces) {
    const Vec3 &x = s.nodes[a], &y = s.nodes[b], &z = s.nodes[c];
    EXPECT_GT((y - x).cross(z - x).dot(x + y + z), 0.0);
  }
}

TEST(Icosphere, EdgesUniqueSortedAndEachSharedByTwoFaces) {
  const Icosphere s = make_icosphere(2);
  for (std::size_t e = 0; e < s.edges.size(); ++e) {
    EXPECT_LT(s.edges[e][0], s.edges[e][1]);
    if (e > 0) {
      EXPECT_LT(s.edges[e - 1], s.edges[e]);
    }
  }
  std::multiset<std::pair<int, int>> face_edges;
  for (const auto& f : s.faces)
    for (int k = 0; k < 3; ++k) face_edges.insert(std::minmax(f[k], f[(k + 1) % 3]));
  for (const auto& [i, j] : s.edges) EXPECT_EQ(face_edges.count({i, j}), 2u);
}

TEST(Icosphere, LevelZeroIsTheRegularIcosahedron) {
  const Icosphere s = make_icosphere(0);
  const double first = (s.nodes[s.edges[0][0]] - s.nodes[s.edges[0][1]]).norm();
  for (const auto& [i, j] : s.edges) EXPECT_NEAR((s.nodes[i] - s.nodes[j]).norm(), first, 1e-15);
  // Each vertex has five neighbours.
  std::vector<int> degree(12, 0);
  for (const auto& [i, j] : s.edges) ++degree[i], ++degree[j];
  for (int d : degree) EXPECT_EQ(d, 5);
}

TEST(Icosphere, DeterministicBitForBit) {
  const Icosphere a = make_icosphere(3), b = make_icosphere(3);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (std::size_t i = 0; i < a.nodes.size(); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(std::bit_cast<std::uint64_t>(a.nodes[i][k]), std::bit_cast<std::uint64_t>(b.nodes[i][k]));
  EXPECT_EQ(a.edges, b.edges);
  EXPECT_EQ(a.faces, b.faces);
}
