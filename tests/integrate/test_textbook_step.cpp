#include <gtest/gtest.h>

#include <cmath>

#include "forces/force_field.hpp"
#include "integrate/leapfrog.hpp"
#include "integrate/textbook_step.hpp"
#include "support/force_test_bodies.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;

TEST(TextbookStep, FollowsTheLeapfrogToRoundingOverManySteps) {
  // The independent reference: its own loops and particle structs, the same evaluators, the same
  // drift-kick-drift, with every law on.
  const Checkpoint c = every_law_body(8);
  const ForceOptions options = every_law_options();
  ForceField field(c.body, options);
  State state = c.state;
  Leapfrog leapfrog(field, c.stage.clock);
  TextbookStep textbook(c.body, c.state, options);
  const int steps = 50;
  leapfrog.advance(state, steps);
  for (int s = 0; s < steps; ++s) textbook.step(c.state.springs, c.state.hinges, c.stage.clock.dt);

  double worst_x = 0, worst_v = 0, scale_v = 0;
  for (std::size_t i = 0; i < c.body.particle_count(); ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      worst_x = std::max(worst_x, std::abs(state.position[3 * i + k] - textbook.particles()[i].x[k]));
      worst_v = std::max(worst_v, std::abs(state.velocity[3 * i + k] - textbook.particles()[i].v[k]));
      scale_v = std::max(scale_v, std::abs(state.velocity[3 * i + k]));
    }
  EXPECT_LT(worst_x, 1e-12);
  EXPECT_LT(worst_v, 1e-10 * scale_v);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(state.perturber.position[k], textbook.perturber().position[k], 1e-12);
    EXPECT_NEAR(state.perturber.velocity[k], textbook.perturber().velocity[k], 1e-12);
  }
}
