#include <gtest/gtest.h>

#include "physics/orbital_frame.hpp"

using namespace tidalcrust;

TEST(OrbitalFrame, SubsatellitePointIsAtLongitude90) {
  EXPECT_DOUBLE_EQ(longitude_deg({0, 1, 0}), 90.0);
  EXPECT_DOUBLE_EQ(longitude_deg({1, 0, 0}), 0.0);
  EXPECT_DOUBLE_EQ(longitude_deg({-1, 0, 0}), 180.0);
  EXPECT_DOUBLE_EQ(longitude_deg({0, -1, 0}), -90.0);
  EXPECT_DOUBLE_EQ(latitude_deg({0, 0, 2}), 90.0);
  EXPECT_DOUBLE_EQ(latitude_deg({3, 0, 0}), 0.0);
  EXPECT_DOUBLE_EQ(angle_from_subsatellite_deg({0, 4, 0}), 0.0);
  EXPECT_DOUBLE_EQ(angle_from_subsatellite_deg({0, 0, 1}), 90.0);
  EXPECT_DOUBLE_EQ(angle_from_subsatellite_deg({0, -1, 0}), 180.0);
}
