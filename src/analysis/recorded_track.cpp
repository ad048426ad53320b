#include "analysis/recorded_track.hpp"
#include "base/invariant.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <stdexcept>

namespace tidalcrust {

RecordedTrack::RecordedTrack(const std::vector<TimeseriesSample>& samples) {
  for (const TimeseriesSample& s : samples) {
    const Vec3 offset(s.perturber_offset[0], s.perturber_offset[1], s.perturber_offset[2]);
    if (offset == Vec3::Zero()) continue;
    times_.push_back(s.time);
    positions_.push_back(offset);
  }
}

bool RecordedTrack::covers(double t) const { return !empty() && t >= times_.front() && t <= times_.back(); }

Vec3 RecordedTrack::position_at(double t) const {
  TIDALCRUST_ASSERT(covers(t), fmt::format("RecordedTrack::position_at({}): outside the samples", t));
  const auto after = std::upper_bound(times_.begin(), times_.end(), t);
  if (after == times_.end()) return positions_.back();
  const auto i = static_cast<std::size_t>(std::distance(times_.begin(), after)) - 1;
  const double w = (t - times_[i]) / (times_[i + 1] - times_[i]);
  return (1 - w) * positions_[i] + w * positions_[i + 1];
}

}  // namespace tidalcrust
