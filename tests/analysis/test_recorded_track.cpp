#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "analysis/recorded_track.hpp"
#include "base/invariant.hpp"

using namespace tidalcrust;

namespace {
TimeseriesSample sample_at(double time, std::array<double, 3> offset) {
  TimeseriesSample s;
  s.time = time;
  s.perturber_offset = offset;
  return s;
}
}  // namespace

TEST(RecordedTrack, KeepsOnlySamplesWithAPerturber) {
  const RecordedTrack track({sample_at(0.0, {0, 0, 0}), sample_at(0.5, {3, -1, 0}), sample_at(0.7, {2, 0, 0.5})});
  ASSERT_EQ(track.times(), (std::vector<double>{0.5, 0.7}));
  EXPECT_EQ(track.positions()[0], Vec3(3, -1, 0));
  EXPECT_EQ(track.positions()[1], Vec3(2, 0, 0.5));
  EXPECT_TRUE(RecordedTrack({sample_at(1.0, {0, 0, 0})}).empty());
  EXPECT_TRUE(RecordedTrack({}).empty());
}

TEST(RecordedTrack, InterpolatesLinearlyBetweenSamples) {
  const RecordedTrack track({sample_at(1.0, {2, 0, 0}), sample_at(1.5, {1, 1, 0}), sample_at(2.0, {0, 3, 1})});
  EXPECT_EQ(track.position_at(1.0), Vec3(2, 0, 0));
  EXPECT_EQ(track.position_at(1.5), Vec3(1, 1, 0));
  EXPECT_EQ(track.position_at(2.0), Vec3(0, 3, 1));
  EXPECT_TRUE(track.position_at(1.25).isApprox(Vec3(1.5, 0.5, 0), 1e-15));
  EXPECT_TRUE(track.position_at(1.875).isApprox(Vec3(0.25, 2.5, 0.75), 1e-15));
  EXPECT_TRUE(track.covers(1.0) && track.covers(2.0));
  EXPECT_FALSE(track.covers(0.999) || track.covers(2.001));
  EXPECT_THROW(track.position_at(2.1), InternalError);
  EXPECT_THROW(RecordedTrack({}).position_at(0), InternalError);
}
