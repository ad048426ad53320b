#pragma once
// The perturber's simulated track relative to the body's centre of mass: the perturber_offset of
// the timeseries samples (checkpoint.hpp), which includes the body's recoil and the tidal
// effects that the analytic two-body orbit (two_body_orbit.hpp) leaves out. Between samples the
// track is interpolated linearly (samples are a few hundredths of t_grav apart).
#include <vector>

#include "model/checkpoint.hpp"
#include "base/vec3.hpp"

namespace tidalcrust {

class RecordedTrack {
 public:
  /// Keeps the samples that have a perturber (non-zero perturber_offset), in their order, which
  /// must be increasing in time.
  explicit RecordedTrack(const std::vector<TimeseriesSample>& samples);

  bool empty() const { return times_.empty(); }
  const std::vector<double>& times() const { return times_; }       ///< t_grav
  const std::vector<Vec3>& positions() const { return positions_; }  ///< R, perturber minus centre of mass

  /// True if t lies between the first and the last kept sample (inclusive).
  bool covers(double t) const;
  /// Linear interpolation between the samples around t; the sample itself at a sample time.
  /// InternalError (TIDALCRUST_ASSERT) unless covers(t).
  Vec3 position_at(double t) const;

 private:
  std::vector<double> times_;
  std::vector<Vec3> positions_;
};

}  // namespace tidalcrust
