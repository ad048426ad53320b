#include "bodies/cross_support.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "bodies/neighbor_grid.hpp"

namespace tidalcrust {
namespace {

constexpr int max_springs_per_node = 12;

/// The interior nodes in the order (squared distance from p, index), produced lazily in rings
/// of doubling radius on a NeighborGrid: a shell node usually needs only its few nearest
/// nodes, so sorting all N_I of them for each node (O(N_S N_I log N_I) at level 6) is wasted.
/// Each ring holds the nodes with inner^2 <= d^2 < outer^2 (d^2 computed as the plain
/// definition computes it), sorted by (d^2, index); rings partition the d^2 axis, so their
/// concatenation is exactly the full sort.
class NearestFirst {
 public:
  NearestFirst(const NeighborGrid& grid, const std::vector<Vec3>& interior, const Vec3& p, double first_radius,
               double reach)
      : grid_(grid), interior_(interior), p_(p), radius_(first_radius), reach_(reach) {}

  /// The next (d^2, index) in order; false once every interior node has been produced.
  bool next(std::pair<double, std::int32_t>& out) {
    while (position_ == ring_.size()) {
      if (exhausted_) return false;
      fill_next_ring();
    }
    out = ring_[position_++];
    return true;
  }

 private:
  void fill_next_ring() {
    ring_.clear();
    position_ = 0;
    auto take = [&](std::int32_t i, double outer2) {
      const double d2 = (p_ - interior_[static_cast<std::size_t>(i)]).squaredNorm();
      if (d2 >= inner2_ && d2 < outer2) ring_.push_back({d2, i});
    };
    if (radius_ > reach_) {
      // The ball holds every node: the last ring is all that is left.
      for (std::size_t i = 0; i < interior_.size(); ++i)
        take(static_cast<std::int32_t>(i), std::numeric_limits<double>::infinity());
      exhausted_ = true;
    } else {
      const double outer2 = radius_ * radius_;
      // A slightly larger query radius: the grid's own distance test must not decide membership.
      for (std::int32_t i : grid_.closer_than(p_, radius_ * (1 + 1e-9))) take(i, outer2);
      inner2_ = outer2;
      radius_ *= 2;
    }
    std::sort(ring_.begin(), ring_.end());
  }

  const NeighborGrid& grid_;
  const std::vector<Vec3>& interior_;
  Vec3 p_;
  double radius_, reach_;
  double inner2_ = -1;  ///< below every d^2: the first ring starts at 0
  bool exhausted_ = false;
  std::vector<std::pair<double, std::int32_t>> ring_;
  std::size_t position_ = 0;
};

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

  Vec3 lo = interior.front(), hi = interior.front();
  double max_norm = 0;
  for (const Vec3& p : interior) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    max_norm = std::max(max_norm, p.norm());
  }
  // First ring and cells: two mean spacings of nodes filling their bounding box, so the first
  // ring of a shell node just outside the interior already holds a few dozen nodes.
  const Vec3 extent = hi - lo;
  const double volume = std::max(extent.x(), 1e-12) * std::max(extent.y(), 1e-12) * std::max(extent.z(), 1e-12);
  const double first_radius = 2 * std::cbrt(volume / static_cast<double>(interior.size()));
  NeighborGrid grid(lo, hi, first_radius);
  for (const Vec3& p : interior) grid.insert(p);

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
    // Interior nodes nearest first (distance, then index); no node lies farther than reach.
    NearestFirst nearest(grid, interior, shell[s], first_radius, shell[s].norm() + max_norm);
    for (std::pair<double, std::int32_t> candidate; nearest.next(candidate);) {
      const std::int32_t i = candidate.second;
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

std::vector<std::array<std::int32_t, 2>> cross_springs_within(const std::vector<Vec3>& interior,
                                                              const std::vector<Vec3>& shell, double distance,
                                                              int minimum) {
  NeighborGrid shell_grid(Vec3(-1, -1, -1), Vec3(1, 1, 1), distance);
  for (const auto& p : shell) shell_grid.insert(p);
  std::vector<std::array<std::int32_t, 2>> cross;
  for (std::size_t i = 0; i < interior.size(); ++i)
    for (std::int32_t s : shell_grid.closer_than(interior[i], distance)) cross.push_back({static_cast<std::int32_t>(i), s});
  const auto extra = supplementary_cross_springs(interior, shell, cross, minimum);
  cross.insert(cross.end(), extra.begin(), extra.end());
  return cross;
}

}  // namespace tidalcrust
