#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "analysis/conservation_drift.hpp"

using namespace tidalcrust;

TEST(ConservationDrift, ChangesRelativeToTheFirstSample) {
  std::vector<TimeseriesSample> samples(3);
  samples[0].kinetic_energy = 2.0;
  samples[0].angular_momentum = {0, 0, 4.0};
  samples[1].kinetic_energy = 2.5;
  samples[1].momentum = {3e-15, 4e-15, 0};
  samples[1].angular_momentum = {0, 0, 4.0 + 2e-12};
  samples[2].kinetic_energy = 1.0;
  samples[2].angular_momentum = {0, 0, 4.0};
  const ConservationDrift d = conservation_drift(samples);
  EXPECT_EQ(d.samples, 3u);
  EXPECT_DOUBLE_EQ(d.max_momentum_change, 5e-15);
  EXPECT_NEAR(d.max_angular_momentum_change, 2e-12, 1e-15);  // ulp(4) ~ 9e-16
  EXPECT_NEAR(d.max_relative_angular_momentum_change, 5e-13, 1e-15 / 4);
  EXPECT_DOUBLE_EQ(d.final_kinetic_energy_change, -0.5);
  EXPECT_DOUBLE_EQ(d.max_kinetic_energy_change, 0.5);
  EXPECT_TRUE(std::isnan(conservation_drift({}).max_momentum_change));
}
