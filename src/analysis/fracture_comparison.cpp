#include "analysis/fracture_comparison.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/errors.hpp"

namespace tidalcrust {

void require_same_body(const Body& a, const Body& b, const std::string& name_a, const std::string& name_b) {
  auto refuse = [&](const char* what) {
    throw InputError(fmt::format("{} and {} do not branch from the same body: their {} differ", name_a,
                                 name_b, what));
  };
  if (a.particle_count() != b.particle_count()) refuse("particle counts");
  if (a.species != b.species) refuse("particle species");
  if (a.spring_count() != b.spring_count()) refuse("spring counts");
  if (a.springs != b.springs) refuse("spring connectivities");
  if (a.spring_kind != b.spring_kind) refuse("spring kinds");
  if (a.hinges != b.hinges) refuse("hinges");
  if (a.faces != b.faces) refuse("shell faces");
}

double kolmogorov_smirnov_distance(std::vector<double> a, std::vector<double> b) {
  if (a.empty() && b.empty()) return 0;
  if (a.empty() || b.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  const double na = static_cast<double>(a.size()), nb = static_cast<double>(b.size());
  std::size_t i = 0, j = 0;
  double largest = 0;
  // Step through the merged sample; evaluate the gap only after all copies of a value passed.
  while (i < a.size() || j < b.size()) {
    const double x = (j == b.size() || (i < a.size() && a[i] <= b[j])) ? a[i] : b[j];
    while (i < a.size() && a[i] == x) ++i;
    while (j < b.size() && b[j] == x) ++j;
    largest = std::max(largest, std::abs(static_cast<double>(i) / na - static_cast<double>(j) / nb));
  }
  return largest;
}

FractureComparison compare_fractures(const Body& body, const State& a, const State& b) {
  FractureComparison result;
  result.a = analyze_fractures(body, a);
  result.b = analyze_fractures(body, b);
  for (std::size_t s = 0; s < body.spring_count(); ++s) {
    if (body.spring_kind[s] != static_cast<std::uint8_t>(SpringKind::shell)) continue;
    const bool in_a = a.springs.failed[s] != 0, in_b = b.springs.failed[s] != 0;
    result.common_failed += in_a && in_b;
    result.either_failed += in_a || in_b;
  }
  result.jaccard = result.either_failed
                       ? static_cast<double>(result.common_failed) / static_cast<double>(result.either_failed)
                       : 1.0;
  // The two states may be at different times (a snapshot and the end, two dt): the same spring
  // then sits at slightly different angles. The distributions are compared on ONE geometry, the
  // mean of both states' positions, so that only the failure sets differ: identical sets give 0.
  State shared = a;
  for (std::size_t k = 0; k < shared.position.size(); ++k) shared.position[k] = 0.5 * (a.position[k] + b.position[k]);
  const FractureSummary on_shared_a = analyze_fractures(body, shared);
  shared.springs.failed = b.springs.failed;
  const FractureSummary on_shared_b = analyze_fractures(body, shared);
  result.ks_distance = kolmogorov_smirnov_distance(on_shared_a.angles_from_subsatellite_deg(),
                                                   on_shared_b.angles_from_subsatellite_deg());
  return result;
}

}  // namespace tidalcrust
