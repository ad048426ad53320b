#include "bodies/cross_support.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <utility>

namespace tidalcrust {
namespace {

constexpr int max_springs_per_node = 12;

}  // namespace

double weakest_direction_support(const std::vector<Vec3>& directions) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (const Vec3& d : directions) {
    const Vec3 u = d.normalized();
    m += u * u.transpose();
  }
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m, Eigen::EigenvaluesOnly).eigenvalues()(0);
}

std::vector<std::array<std::int32_t, 2>> supplementary_cross_springs(
    const std::vector<Vec3>& interior, const std::vector<Vec3>& shell,
    const std::vector<std::array<std::int32_t, 2>>& existing, int minimum) {
  std::vector<std::array<std::int32_t, 2>> added;
  if (minimum <= 0 || interior.empty()) return added;
  std::vector<std::vector<std::int32_t>> partners(shell.size());
  for (const auto& [i, s] : existing) partners[static_cast<std::size_t>(s)].push_back(i);

  std::vector<std::pair<double, std::int32_t>> by_distance(interior.size());
  for (std::size_t s = 0; s < shell.size(); ++s) {
    auto& joined = partners[s];
    auto directions = [&] {
      std::vector<Vec3> out;
      for (std::int32_t i : joined) out.push_back(shell[s] - interior[static_cast<std::size_t>(i)]);
      return out;
    };
    auto satisfied = [&] {
      const auto count = static_cast<int>(joined.size());
      if (count >= max_springs_per_node) return true;
      if (count < minimum) return false;
      return minimum < 3 || weakest_direction_support(directions()) >= min_direction_support;
    };
    if (satisfied()) continue;
    // All interior nodes by distance: O(N_I) per node that needs springs (few), no grid needed.
    for (std::size_t i = 0; i < interior.size(); ++i)
      by_distance[i] = {(shell[s] - interior[i]).squaredNorm(), static_cast<std::int32_t>(i)};
    std::sort(by_distance.begin(), by_distance.end());
    for (const auto& [d2, i] : by_distance) {
      if (satisfied()) break;
      if (std::find(joined.begin(), joined.end(), i) != joined.end()) continue;
      // Past the count, a candidate is taken only if it strengthens the weakest direction.
      if (static_cast<int>(joined.size()) >= minimum) {
        const double before = weakest_direction_support(directions());
        joined.push_back(i);
        const double after = weakest_direction_support(directions());
        joined.pop_back();
        if (!(after > before)) continue;
      }
      joined.push_back(i);
      added.push_back({i, static_cast<std::int32_t>(s)});
    }
  }
  return added;
}

}  // namespace tidalcrust
