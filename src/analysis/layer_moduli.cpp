#include "analysis/layer_moduli.hpp"

#include <cmath>
#include <numbers>

#include "base/sphere_crossings.hpp"

namespace tidalcrust {

std::vector<CrossingModuli> crossing_moduli(const std::vector<double>& positions, const Vec3& center,
                                            const std::vector<std::array<std::int32_t, 2>>& springs,
                                            const std::vector<double>& stiffness,
                                            const std::vector<double>& rest_length, const std::vector<bool>& use,
                                            const std::vector<double>& radii) {
  std::vector<CrossingModuli> out;
  for (double r : radii) out.push_back({r, 0.0, 0.0});
  for (std::size_t s = 0; s < springs.size(); ++s) {
    if (!use[s]) continue;
    const Vec3 a = vec3_at(positions, static_cast<std::size_t>(springs[s][0])) - center;
    const Vec3 b = vec3_at(positions, static_cast<std::size_t>(springs[s][1])) - center;
    const double length = (b - a).norm();
    const Vec3 n = (b - a) / length;
    const double weight = stiffness[s] * rest_length[s];
    for (auto& m : out) {
      for (double t : sphere_crossings(a, n, m.radius)) {
        if (t > length) continue;
        const Vec3 p = a + t * n;
        const double n_r = std::abs(n.dot(p) / p.norm());  // outward orientation
        m.compression += weight * n_r * n_r * n_r;
        m.shear += weight * n_r * (1 - n_r * n_r) / 2;
      }
    }
  }
  for (auto& m : out) {
    const double area = 4 * std::numbers::pi * m.radius * m.radius;
    m.compression /= area;
    m.shear /= area;
  }
  return out;
}

}  // namespace tidalcrust
