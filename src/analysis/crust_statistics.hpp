#pragma once
// What a crust that varies ([crust], docs/crust.md) did to the failures, and the field the maps
// draw under the cracks: read from the body as built (a shell node's thickness factor is its mass
// over the mean shell node mass, a shell spring's strength factor is Body::strength_factor), so a
// checkpoint answers without its configuration.
#include <cstddef>
#include <vector>

#include "analysis/fracture_analysis.hpp"
#include "io/json.hpp"
#include "model/body.hpp"
#include "model/state.hpp"

namespace tidalcrust {

/// The shares of one part of the crust: the springs in it and the counted failures in it.
struct CrustPartShares {
  std::size_t springs = 0;   ///< shell springs in the part
  std::size_t failures = 0;  ///< of the FractureSummary's failures, those in the part
  double spring_share = 0;   ///< springs / shell springs (NaN without shell springs)
  double failure_share = 0;  ///< failures / all failures (NaN without failures)
  double capture_ratio = 0;  ///< failure_share / spring_share: 1 when the part fails as often as the rest (NaN)
};

struct CrustStatistics {
  bool varies = false;  ///< some thickness or strength factor differs from 1
  double thickness_factor_min = 1, thickness_factor_max = 1;  ///< over the shell nodes
  double strength_factor_min = 1, strength_factor_max = 1;    ///< over the shell springs
  CrustPartShares weak;  ///< springs of strength factor < 1 (a weak line: within its half-width)
  CrustPartShares thin;  ///< springs whose nodes' mean thickness factor is < 1
};

/// Thickness factor of each particle: shell nodes m_i / (mean shell node mass), 0 for interior nodes.
std::vector<double> shell_thickness_factors(const Body& body);

/// The statistics of `fractures` (analyze_fractures of this body) on the body's crust.
CrustStatistics crust_statistics(const Body& body, const FractureSummary& fractures);
/// summary.json's `crust` object: varies, the factors' ranges, and for `weak` and `thin`: springs,
/// failures, spring_share, failure_share, capture_ratio (null where undefined).
Json crust_statistics_json(const CrustStatistics& statistics);
/// cracks.json's `crust` object, what the maps draw under the cracks: `thickness` {lon, lat,
/// factor} of every shell node and `strength` {lon, lat, factor} of every shell spring's midpoint
/// (degrees in the maps' body frame, relative to the centre of mass), each only where some factor
/// of its kind differs from 1 (empty lists for a uniform crust).
Json crust_field_json(const Body& body, const State& state);

}  // namespace tidalcrust
