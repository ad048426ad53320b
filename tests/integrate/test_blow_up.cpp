#include <gtest/gtest.h>

#include <string>

#include "integrate/blow_up.hpp"
#include "model/derived_quantities.hpp"
#include "support/force_test_bodies.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;

TEST(BlowUp, NamesATimeStepAboveTheSpringStabilityBound) {
  Checkpoint c = small_body();
  const double bound = derive_quantities(c.body, c.state, 1.0).dt_max;
  ASSERT_GT(bound, 0);
  const std::string above = likely_blow_up_cause(c.body, c.state, 2 * bound);
  EXPECT_NE(above.find("larger than the stability bound"), std::string::npos) << above;
  EXPECT_NE(above.find("dt_max"), std::string::npos) << above;
  const std::string within = likely_blow_up_cause(c.body, c.state, 0.5 * bound);
  EXPECT_NE(within.find("within the spring stability bound"), std::string::npos) << within;
  EXPECT_NE(within.find("collapsing shell triangle"), std::string::npos) << within;
}

// A Maxwell liquid's support in the state: its growing modes are named first, the time step after.
TEST(BlowUp, NamesAMaxwellLiquidsGrowingModesFirst) {
  Checkpoint c = small_body();
  c.state.liquid_support.assign(3 * c.body.particle_count(), 0.0);
  const double bound = derive_quantities(c.body, c.state, 1.0).dt_max;
  const std::string cause = likely_blow_up_cause(c.body, c.state, 0.5 * bound);
  EXPECT_EQ(cause.find("likely cause: the Maxwell liquid's growing modes"), 0u) << cause;
  EXPECT_NE(cause.find("docs/ocean.md"), std::string::npos) << cause;
  EXPECT_NE(cause.find("within the spring stability bound"), std::string::npos) << cause;
}
