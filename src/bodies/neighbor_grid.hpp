#pragma once
// Fixed-radius neighbour queries on a uniform cell grid, so that building a body never loops
// over all pairs (random sequential addition, spring search, minimum spacing).
#include <cstdint>
#include <vector>

#include "base/vec3.hpp"

namespace tidalcrust {

class NeighborGrid {
 public:
  /// Cubic cells of side `cell_size` (R) covering the box [lo, hi]. Points outside the box
  /// are still found (they go to the border cells), only more slowly.
  NeighborGrid(const Vec3& lo, const Vec3& hi, double cell_size);

  /// Stores a point; its id is the number of points inserted before it.
  std::int32_t insert(const Vec3& point);

  /// True if a stored point lies at distance < r from p.
  bool any_closer_than(const Vec3& p, double r) const;

  /// Ids of the stored points at distance < r from p, in increasing order.
  std::vector<std::int32_t> closer_than(const Vec3& p, double r) const;

  std::size_t size() const { return points_.size(); }
  const Vec3& point(std::int32_t id) const { return points_[static_cast<std::size_t>(id)]; }

 private:
  /// Cell coordinate along one axis, clamped to the grid.
  int cell_coordinate(double x, int axis) const;
  std::size_t cell_index(int cx, int cy, int cz) const;
  /// Calls visit(id) for every stored point in the cells that can hold points closer than r;
  /// stops early when visit returns true. Returns whether it stopped early.
  template <class Visit>
  bool visit_candidates(const Vec3& p, double r, Visit&& visit) const;

  Vec3 lo_;
  double cell_size_;
  int dims_[3];
  std::vector<std::vector<std::int32_t>> cells_;
  std::vector<Vec3> points_;
};

/// Smallest distance between two distinct points (R); 0 for fewer than two points.
/// Grid based: a cell size near the mean spacing, doubled until a pair is found.
double min_pair_distance(const std::vector<Vec3>& points);

}  // namespace tidalcrust
