#include <gtest/gtest.h>

#include "physics/shell_failure.hpp"

using namespace tidalcrust;

namespace {

/// Four particles on the x axis at 0, 1, 2, 4 and springs 0-1 (shell), 1-2 (shell),
/// 2-3 (interior), 0-2 (shell, failed already). Rest lengths chosen per test.
struct Line {
  Body body;
  State state;
  Line() {
    body.mass = {0.25, 0.25, 0.25, 0.25};
    body.species = {1, 1, 1, 0};
    body.springs = {{0, 1}, {1, 2}, {2, 3}, {0, 2}};
    body.spring_kind = {1, 1, 0, 1};
    state.time = 1.5;
    state.step = 42;
    state.position = {0, 0, 0, 1, 0, 0, 2, 0, 0, 4, 0, 0};
    state.velocity.assign(12, 0.0);
    state.springs.rest_length = {1.0, 1.0, 2.0, 2.0};
    state.springs.stiffness = {2.0, 3.0, 4.0, 5.0};
    state.springs.failed = {0, 0, 0, 1};
  }
};

}  // namespace

TEST(ShellFailure, StrainAndExtremesIgnoreInteriorAndFailedSprings) {
  Line l;
  l.state.springs.rest_length = {0.99, 1.02, 1.0, 1.0};  // +1.01%, -1.96%; interior +100%; failed +100%
  EXPECT_NEAR(spring_strain(l.body, l.state, 0), 1.0 / 0.99 - 1.0, 1e-15);
  EXPECT_NEAR(max_shell_tension(l.body, l.state), 1.0 / 0.99 - 1.0, 1e-15);
  EXPECT_NEAR(max_abs_shell_strain(l.body, l.state), 1.0 - 1.0 / 1.02, 1e-15);
}

TEST(ShellFailure, NothingFailsAtOrBelowThreshold) {
  Line l;
  l.state.springs.rest_length = {1.0, 1.0 / 1.002, 2.0, 1.0};
  // Spring 1 has strain 0.002 (up to rounding), spring 0 none, spring 3 failed already.
  EXPECT_FALSE(fail_most_strained_shell_spring(l.body, l.state, 0.0021, 0.005));
  EXPECT_EQ(l.state.springs.stiffness[1], 3.0);
  // Compression never fails.
  l.state.springs.rest_length = {1.5, 1.5, 2.0, 2.0};
  EXPECT_FALSE(fail_most_strained_shell_spring(l.body, l.state, 0.0, 0.005));
}

TEST(ShellFailure, OnlyTheMostStrainedShellSpringFails) {
  Line l;
  // Strains: spring 0 +0.5%, spring 1 +1%, interior spring 2 +100%, failed spring 3 +100%.
  l.state.springs.rest_length = {1.0 / 1.005, 1.0 / 1.01, 1.0, 1.0};
  auto event = fail_most_strained_shell_spring(l.body, l.state, 0.003, 0.005);
  ASSERT_TRUE(event);
  EXPECT_EQ(event->spring, 1);
  EXPECT_NEAR(event->strain, 0.01, 1e-12);
  EXPECT_EQ(event->step, 42);
  EXPECT_EQ(event->time, 1.5);
  EXPECT_EQ(event->position[0], 1.5);
  EXPECT_EQ(l.state.springs.failed, (std::vector<std::uint8_t>{0, 1, 0, 1}));
  EXPECT_EQ(l.state.springs.stiffness, (std::vector<double>{2.0, 3.0 * 0.005, 4.0, 5.0}));
  // Next check: spring 0 is the only candidate left.
  event = fail_most_strained_shell_spring(l.body, l.state, 0.003, 0.005);
  ASSERT_TRUE(event);
  EXPECT_EQ(event->spring, 0);
  EXPECT_FALSE(fail_most_strained_shell_spring(l.body, l.state, 0.003, 0.005));
}

TEST(ShellFailure, TiesGoToTheLowestIndex) {
  Line l;
  l.state.springs.rest_length = {0.9, 0.9, 2.0, 2.0};
  auto event = fail_most_strained_shell_spring(l.body, l.state, 0.003, 0.005);
  ASSERT_TRUE(event);
  EXPECT_EQ(event->spring, 0);
}
