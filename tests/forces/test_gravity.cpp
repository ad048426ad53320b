#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "forces/gravity.hpp"
#include "forces/perturber_gravity.hpp"
#include "base/random.hpp"

using namespace tidalcrust;

namespace {

struct Cloud {
  std::vector<double> mass, position;
};

/// n particles in the unit ball-ish cube with unequal masses.
Cloud random_cloud(std::size_t n, std::uint64_t seed) {
  Random random(seed);
  Cloud c;
  for (std::size_t i = 0; i < n; ++i) {
    c.mass.push_back(random.uniform(0.5, 1.5) / static_cast<double>(n));
    for (int k = 0; k < 3; ++k) c.position.push_back(random.uniform(-1, 1));
  }
  return c;
}

/// Plain reference: every i sums over every j != i, with sqrt and division.
std::vector<double> reference(const Cloud& c, double eps) {
  const std::size_t n = c.mass.size();
  std::vector<double> a(3 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      if (i == j) continue;
      double d[3], r2 = 0;
      for (int k = 0; k < 3; ++k) {
        d[k] = c.position[3 * j + k] - c.position[3 * i + k];
        r2 += d[k] * d[k];
      }
      const double f = c.mass[j] / std::pow(r2 + eps * eps, 1.5);
      for (int k = 0; k < 3; ++k) a[3 * i + k] += f * d[k];
    }
  return a;
}

std::vector<double> direct(const Cloud& c, double eps) {
  DirectGravity gravity(c.mass, eps);
  std::vector<double> a(c.position.size());
  gravity.accelerations(c.position.data(), a.data());
  return a;
}

}  // namespace

TEST(Gravity, TwoParticlesMatchTheAnalyticPlummerPull) {
  const Cloud c{{0.3, 0.7}, {0.1, -0.2, 0.3, 0.6, 0.4, -0.1}};
  const double eps = 0.05;
  const std::vector<double> a = direct(c, eps);
  const double d[3] = {0.5, 0.6, -0.4};
  const double s = 0.25 + 0.36 + 0.16 + eps * eps;
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(a[k], 0.7 * d[k] / std::pow(s, 1.5), 1e-15);
    EXPECT_NEAR(a[3 + k], -0.3 * d[k] / std::pow(s, 1.5), 1e-15);
  }
}

TEST(Gravity, MatchesThePlainDoubleLoop) {
  for (std::size_t n : {1u, 7u, 8u, 9u, 301u, 1100u}) {  // around the SIMD width and chunk size
    const Cloud c = random_cloud(n, 11 + n);
    const std::vector<double> a = direct(c, 0.01), expected = reference(c, 0.01);
    double worst = 0, scale = 0;
    for (std::size_t k = 0; k < a.size(); ++k) {
      worst = std::max(worst, std::abs(a[k] - expected[k]));
      scale = std::max(scale, std::abs(expected[k]));
    }
    EXPECT_LE(worst, 1e-13 * scale) << "n = " << n;
  }
}

TEST(Gravity, TotalMomentumChangeVanishes) {
  const Cloud c = random_cloud(500, 5);
  const std::vector<double> a = direct(c, 0.01);
  double total[3] = {0, 0, 0}, scale = 0;
  for (std::size_t i = 0; i < c.mass.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      total[k] += c.mass[i] * a[3 * i + k];
      scale += std::abs(c.mass[i] * a[3 * i + k]);
    }
  for (double t : total) EXPECT_LT(std::abs(t), 1e-14 * scale);
}

TEST(Gravity, BitwiseIndependentOfTheThreadCount) {
  const Cloud c = random_cloud(1234, 9);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const std::vector<double> one = direct(c, 0.01);
  omp_set_num_threads(2);
  const std::vector<double> two = direct(c, 0.01);
  omp_set_num_threads(3);
  const std::vector<double> three = direct(c, 0.01);
  omp_set_num_threads(threads);
  EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(one.data(), three.data(), one.size() * sizeof(double)), 0);
}

TEST(PerturberGravity, PullsBothWaysWithEqualAndOppositeMomentumChange) {
  const Cloud c = random_cloud(50, 3);
  Perturber p;
  p.present = true;
  p.mass = 0.5;
  p.position = {2.5, -1.0, 0.3};
  std::vector<double> a(c.position.size(), 0.0);
  const auto back = add_perturber_gravity(c.mass, 0.0, c.position.data(), p, a.data());
  double total[3] = {p.mass * back[0], p.mass * back[1], p.mass * back[2]};
  for (std::size_t i = 0; i < c.mass.size(); ++i)
    for (int k = 0; k < 3; ++k) total[k] += c.mass[i] * a[3 * i + k];
  const double scale = p.mass * std::hypot(back[0], back[1], back[2]);
  for (double t : total) EXPECT_LT(std::abs(t), 1e-15 * scale);
  // Particle 0 alone: the analytic inverse-square pull.
  double d[3], r2 = 0;
  for (int k = 0; k < 3; ++k) {
    d[k] = p.position[k] - c.position[k];
    r2 += d[k] * d[k];
  }
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], p.mass * d[k] / std::pow(r2, 1.5), 1e-15);
}

TEST(Gravity, InverseCubeIsAccurateOverManyScales) {
  // The AVX-512 path refines a 14-bit estimate by Newton steps: check a few ulp everywhere.
  for (double r : {1e-4, 3.7e-3, 0.01, 0.5, 1.0, 2.9, 77.0, 1e4}) {
    const Cloud c{{1.0, 1.0}, {0, 0, 0, r * 0.6, r * 0.0, r * 0.8}};
    const std::vector<double> a = direct(c, 0.0);
    const double expected = 1.0 / (r * r);  // |a| = m / r^2
    EXPECT_NEAR(std::hypot(a[0], a[1], a[2]), expected, 4e-16 * expected) << "r = " << r;
  }
}
