#include "bodies/neighbor_grid.hpp"
#include "base/invariant.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tidalcrust {

NeighborGrid::NeighborGrid(const Vec3& lo, const Vec3& hi, double cell_size) : lo_(lo), cell_size_(cell_size) {
  TIDALCRUST_ASSERT(cell_size > 0 && std::isfinite(cell_size), "NeighborGrid: cell size must be finite and > 0");
  std::size_t cells = 1;
  for (int a = 0; a < 3; ++a) {
    const double extent = std::max(hi[a] - lo[a], 0.0);
    // Cap the resolution: beyond ~256 cells per axis memory grows without speeding queries.
    dims_[a] = static_cast<int>(std::clamp(std::ceil(extent / cell_size), 1.0, 256.0));
    cells *= static_cast<std::size_t>(dims_[a]);
  }
  cells_.resize(cells);
}

int NeighborGrid::cell_coordinate(double x, int axis) const {
  const double c = std::floor((x - lo_[axis]) / cell_size_);
  return static_cast<int>(std::clamp(c, 0.0, static_cast<double>(dims_[axis] - 1)));
}

std::size_t NeighborGrid::cell_index(int cx, int cy, int cz) const {
  return (static_cast<std::size_t>(cz) * static_cast<std::size_t>(dims_[1]) + static_cast<std::size_t>(cy)) *
             static_cast<std::size_t>(dims_[0]) +
         static_cast<std::size_t>(cx);
}

std::int32_t NeighborGrid::insert(const Vec3& point) {
  const auto id = static_cast<std::int32_t>(points_.size());
  points_.push_back(point);
  cells_[cell_index(cell_coordinate(point.x(), 0), cell_coordinate(point.y(), 1), cell_coordinate(point.z(), 2))]
      .push_back(id);
  return id;
}

template <class Visit>
bool NeighborGrid::visit_candidates(const Vec3& p, double r, Visit&& visit) const {
  // Clamping both stored points and the query range to the grid keeps points outside the box
  // findable: a point beyond the border is within r of p only if p + r also reaches past it.
  int from[3], to[3];
  for (int a = 0; a < 3; ++a) {
    from[a] = cell_coordinate(p[a] - r, a);
    to[a] = cell_coordinate(p[a] + r, a);
  }
  for (int cz = from[2]; cz <= to[2]; ++cz)
    for (int cy = from[1]; cy <= to[1]; ++cy)
      for (int cx = from[0]; cx <= to[0]; ++cx)
        for (std::int32_t id : cells_[cell_index(cx, cy, cz)])
          if (visit(id)) return true;
  return false;
}

bool NeighborGrid::any_closer_than(const Vec3& p, double r) const {
  const double r2 = r * r;
  return visit_candidates(p, r, [&](std::int32_t id) { return (point(id) - p).squaredNorm() < r2; });
}

std::vector<std::int32_t> NeighborGrid::closer_than(const Vec3& p, double r) const {
  const double r2 = r * r;
  std::vector<std::int32_t> found;
  visit_candidates(p, r, [&](std::int32_t id) {
    if ((point(id) - p).squaredNorm() < r2) found.push_back(id);
    return false;
  });
  std::sort(found.begin(), found.end());
  return found;
}

double min_pair_distance(const std::vector<Vec3>& points) {
  if (points.size() < 2) return 0.0;
  Vec3 lo = points.front(), hi = points.front();
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec3 extent = hi - lo;
  const double span = std::max({extent.x(), extent.y(), extent.z()});
  if (span == 0) return 0.0;  // all points coincide
  // Start near the mean spacing of points filling the bounding box.
  double cell = span / std::cbrt(static_cast<double>(points.size()));
  for (;;) {
    NeighborGrid grid(lo, hi, cell);
    double best2 = std::numeric_limits<double>::infinity();
    for (const auto& p : points) {
      for (std::int32_t j : grid.closer_than(p, cell)) best2 = std::min(best2, (grid.point(j) - p).squaredNorm());
      grid.insert(p);
    }
    if (std::isfinite(best2)) return std::sqrt(best2);
    cell *= 2;  // no pair closer than the cell size: widen and retry
  }
}

}  // namespace tidalcrust
