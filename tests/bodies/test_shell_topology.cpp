#include <gtest/gtest.h>

#include "base/errors.hpp"
#include "bodies/shell_topology.hpp"
#include "support/synthetic_encounter.hpp"

using namespace tidalcrust;
using tidalcrust::test_support::spring_between;
using tidalcrust::test_support::synthetic_encounter;

TEST(ShellTopology, EveryShellEdgeHasTwoFaces) {
  const Checkpoint c = synthetic_encounter(2);
  const ShellTopology t = shell_topology(c.body);
  EXPECT_EQ(c.body.count_springs(SpringKind::shell), 30u * 16u);
  for (std::size_t s = 0; s < c.body.spring_count(); ++s) {
    const bool shell = c.body.spring_kind[s] == static_cast<std::uint8_t>(SpringKind::shell);
    EXPECT_EQ(t.spring_faces[s][0] >= 0 && t.spring_faces[s][1] >= 0, shell) << s;
  }
  for (std::size_t f = 0; f < c.body.faces.size(); ++f)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(t.face_edge_spring[f][k], spring_between(c.body, c.body.faces[f][k], c.body.faces[f][(k + 1) % 3]));
}

TEST(ShellTopology, FaceEdgeWithoutSpringIsInputError) {
  Checkpoint c = synthetic_encounter(1);
  c.body.spring_kind[0] = static_cast<std::uint8_t>(SpringKind::interior);
  EXPECT_THROW(shell_topology(c.body), InputError);
}
