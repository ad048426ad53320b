#include <gtest/gtest.h>

#include <array>
#include <set>
#include <stdexcept>

#include "bodies/icosphere.hpp"
#include "bodies/shell_hinges.hpp"
#include "forces/hinge_geometry.hpp"
#include "base/invariant.hpp"

using namespace tidalcrust;

TEST(ShellHinges, OnePerEdgeWithBothWingsCounterClockwiseAndSameSign) {
  const Icosphere s = make_icosphere(2);
  const auto hinges = make_hinges(s.edges, s.faces);
  ASSERT_EQ(hinges.size(), s.edges.size());
  std::set<std::array<std::int32_t, 3>> faces;  // rotated so the smallest index comes first
  auto canonical = [](std::array<std::int32_t, 3> f) {
    while (f[0] > f[1] || f[0] > f[2]) f = {f[1], f[2], f[0]};
    return f;
  };
  for (const auto& f : s.faces) faces.insert(canonical(f));
  for (std::size_t h = 0; h < hinges.size(); ++h) {
    const auto [w1, w2, a, b] = hinges[h];
    EXPECT_EQ(a, s.edges[h][0]);
    EXPECT_EQ(b, s.edges[h][1]);
    EXPECT_TRUE(faces.count(canonical({w1, a, b}))) << "hinge " << h;
    EXPECT_TRUE(faces.count(canonical({w2, b, a}))) << "hinge " << h;
    const double theta = hinge_angle(s.nodes[w1], s.nodes[w2], s.nodes[a], s.nodes[b]);
    EXPECT_GT(theta, 0.0) << "hinge " << h;  // convex shell: every hinge bends the same way
    EXPECT_LT(theta, 0.8);
  }
}

TEST(ShellHinges, OpenSurfaceIsRejected) {
  const Icosphere s = make_icosphere(0);
  auto faces = s.faces;
  faces.pop_back();
  EXPECT_THROW(make_hinges(s.edges, faces), InternalError);
}
