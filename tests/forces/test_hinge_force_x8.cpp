// hinge_forces_x8 (eight hinges in one AVX-512 pass) against HingeEvaluator, bit for bit: random
// hinges from flat to folded past 90 degrees (both half-angle branches), any rest angle (both
// energy branches), nearly collapsed and fully degenerate faces (NaN forces, the collapse flag).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "base/random.hpp"
#include "forces/hinge_force.hpp"
#include "forces/hinge_force_x8.hpp"

using namespace tidalcrust;

#if defined(__AVX512F__)
namespace {

/// The same bits, or both NaN (a NaN's sign and payload are not part of the contract).
bool same_bits(double a, double b) {
  if (std::isnan(a) && std::isnan(b)) return true;
  return std::memcmp(&a, &b, sizeof(double)) == 0;
}

}  // namespace

TEST(HingeForceX8, SameBitsAsTheEvaluatorForEveryShapeOfHinge) {
  Random random(2026);
  const std::size_t hinges = 8 * 4000;
  std::vector<double> position;
  std::vector<std::int32_t> corners;
  std::vector<HalfRestAngle> rest;
  std::vector<double> stiffness;
  const auto add = [&](const Vec3& p) {
    position.insert(position.end(), {p.x(), p.y(), p.z()});
    return static_cast<std::int32_t>(position.size() / 3 - 1);
  };
  for (std::size_t h = 0; h < hinges; ++h) {
    // Edge along x of length ~L, wings on either side, folded by an angle up to ~pi, jittered.
    const double length = random.uniform(0.01, 0.2);
    const double fold = random.uniform(-3.1, 3.1);
    const Vec3 a(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1));
    const int kind = static_cast<int>(h % 16);
    // Kinds 14 and 15 are exact shapes (no jitter): a jitter of 0.05 L would lift the low wing.
    const double spread = kind >= 14 ? 0.0 : 0.05 * length;
    const auto jitter = [&]() -> Vec3 {  // a Vec3, not an expression of a dead temporary
      return Vec3(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)) * spread;
    };
    const Vec3 b = a + Vec3(length, 0, 0) + jitter();
    double height = 0.87 * length;
    if (kind == 14) height = 1e-4 * length;  // nearly collapsed: |N| below 1e-3 L^2
    const Vec3 w1 = a + Vec3(0.5 * length, height, 0) + jitter();
    Vec3 w2 = a + Vec3(0.5 * length, -height * std::cos(fold), height * std::sin(fold)) + jitter();
    if (kind == 15) w2 = a + 0.5 * (b - a);  // degenerate: the wing on the edge, N2 = 0
    corners.insert(corners.end(), {add(w1), add(w2), add(a), add(b)});
    rest.push_back(HalfRestAngle::of(random.uniform(-3.1, 3.1)));
    stiffness.push_back(random.uniform(1e-6, 1e-2));
  }
  std::vector<double> force(12 * hinges), work_rate(hinges);
  std::vector<unsigned> collapsed_lanes;
  for (std::size_t first = 0; first < hinges; first += 8)
    collapsed_lanes.push_back(hinge_forces_x8(first, corners.data(), position.data(), rest.data(), stiffness.data(),
                                              force.data(), work_rate.data()));
  std::size_t collapsed = 0, upper = 0, lower = 0;
  for (std::size_t h = 0; h < hinges; ++h) {
    const auto at = [&](int v) {
      const std::size_t p = 3 * static_cast<std::size_t>(corners[4 * h + static_cast<std::size_t>(v)]);
      return Vec3(position[p], position[p + 1], position[p + 2]);
    };
    const HingeForces f = HingeEvaluator(rest[h], stiffness[h]).force_and_energy(at(0), at(1), at(2), at(3));
    for (int v = 0; v < 4; ++v)
      for (int k = 0; k < 3; ++k)
        ASSERT_TRUE(same_bits(force[12 * h + 3 * static_cast<std::size_t>(v) + static_cast<std::size_t>(k)], f.on[v][k]))
            << "hinge " << h << " vertex " << v << " component " << k;
    ASSERT_TRUE(same_bits(work_rate[h], f.energy_per_prefactor)) << "hinge " << h;
    ASSERT_EQ(((collapsed_lanes[h / 8] >> (h % 8)) & 1u) != 0, f.collapsed) << "hinge " << h;
    collapsed += f.collapsed;
    const Vec3 n1 = (at(0) - at(2)).cross(at(0) - at(3)), n2 = (at(1) - at(3)).cross(at(1) - at(2));
    (n1.dot(n2) >= 0 ? upper : lower) += 1;
  }
  // Every branch was taken: both half-angle formulas, and the collapse flag (kinds 14 and 15).
  EXPECT_EQ(collapsed, 2 * hinges / 16);
  EXPECT_GT(upper, hinges / 4);
  EXPECT_GT(lower, hinges / 4);
}
#else
TEST(HingeForceX8, SameBitsAsTheEvaluatorForEveryShapeOfHinge) {
  GTEST_SKIP() << "built without AVX-512: ForceField uses HingeEvaluator alone";
}
#endif
