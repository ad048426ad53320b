#include "bodies/icosphere.hpp"
#include "base/invariant.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

namespace tidalcrust {
namespace {

Icosphere icosahedron() {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;  // golden ratio
  Icosphere s;
  const double v[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                           {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (const auto& p : v) s.nodes.push_back(Vec3(p[0], p[1], p[2]).normalized());
  s.faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
             {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  return s;
}

/// Splits every face into four; new vertices are the edge midpoints projected onto R = 1.
void subdivide(Icosphere& s) {
  std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> midpoint_of;
  auto midpoint = [&](std::int32_t a, std::int32_t b) {
    const auto key = std::minmax(a, b);
    auto it = midpoint_of.find(key);
    if (it != midpoint_of.end()) return it->second;
    const auto id = static_cast<std::int32_t>(s.nodes.size());
    s.nodes.push_back((0.5 * (s.nodes[static_cast<std::size_t>(a)] + s.nodes[static_cast<std::size_t>(b)])).normalized());
    midpoint_of.emplace(key, id);
    return id;
  };
  std::vector<std::array<std::int32_t, 3>> faces;
  faces.reserve(4 * s.faces.size());
  for (const auto& [a, b, c] : s.faces) {
    const std::int32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    faces.push_back({a, ab, ca});
    faces.push_back({b, bc, ab});
    faces.push_back({c, ca, bc});
    faces.push_back({ab, bc, ca});
  }
  s.faces = std::move(faces);
}

}  // namespace

Icosphere make_icosphere(int level) {
  TIDALCRUST_ASSERT(level >= 0 && level <= 10, "make_icosphere: level must be in [0, 10]");
  Icosphere s = icosahedron();
  for (int l = 0; l < level; ++l) subdivide(s);
  s.edges.reserve(3 * s.faces.size() / 2);
  for (const auto& f : s.faces)
    for (int k = 0; k < 3; ++k) {
      const auto [i, j] = std::minmax(f[k], f[(k + 1) % 3]);
      s.edges.push_back({i, j});
    }
  std::sort(s.edges.begin(), s.edges.end());
  s.edges.erase(std::unique(s.edges.begin(), s.edges.end()), s.edges.end());
  return s;
}

}  // namespace tidalcrust
