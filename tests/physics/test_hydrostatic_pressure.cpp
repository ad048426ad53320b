// The layered hydrostatic pressure (physics/hydrostatic_pressure.hpp) against an independent
// numerical integration of dP/dr = -rho(r) G m(r)/r^2 and the limits it must reduce to.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "physics/hydrostatic_pressure.hpp"

using namespace tidalcrust;

namespace {

/// P(r) by the midpoint rule from the surface inward, layer by layer (so that no step straddles
/// the density jump), with m(r) from the densities (G = 1).
double integrated_pressure(const LayeredSphere& s, double r, int steps = 100000) {
  auto enclosed = [&](double x) {
    const double pi = std::numbers::pi, rc = std::min(x, s.core_radius);
    return 4.0 / 3.0 * pi * (s.core_density() * rc * rc * rc + s.mantle_density() * (x * x * x - rc * rc * rc));
  };
  auto segment = [&](double from, double to, double density) {  // integral over [from, to], from < to
    double p = 0;
    const double h = (to - from) / steps;
    for (int i = 0; i < steps; ++i) {
      const double x = from + (i + 0.5) * h;
      p += density * enclosed(x) / (x * x) * h;
    }
    return p;
  };
  const double rc = s.core_radius;
  double p = segment(std::max(r, rc), 1.0, s.mantle_density());
  if (r < rc) p += segment(r, rc, s.core_density());
  return p;
}

}  // namespace

TEST(HydrostaticPressure, TwoLayerBodyMatchesTheIntegratedEquation) {
  const LayeredSphere s{0.5, 3.0};
  // Total mass 1.
  const double pi = std::numbers::pi;
  EXPECT_NEAR(4.0 / 3.0 * pi * (s.core_density() * 0.125 + s.mantle_density() * (1 - 0.125)), 1.0, 1e-14);
  for (double r : {0.0, 0.2, 0.49, 0.5, 0.51, 0.8, 0.99})
    EXPECT_NEAR(s.pressure(r), integrated_pressure(s, std::max(r, 1e-9)), 1e-6 * s.pressure(0)) << "r = " << r;
  EXPECT_NEAR(s.pressure(1.0), 0.0, 1e-15);
  // A denser core raises the central pressure above the uniform body's 3/(8 pi).
  EXPECT_GT(s.pressure(0), hydrostatic_pressure(0));
}

TEST(HydrostaticPressure, UniformLimitIsThePapersFormula) {
  for (const LayeredSphere s : {LayeredSphere{0.5, 1.0}, LayeredSphere{0.0, 3.0}})
    for (double r : {0.0, 0.3, 0.7, 1.0}) EXPECT_NEAR(s.pressure(r), hydrostatic_pressure(r), 1e-15);
}

TEST(ParticleHydrostaticPressure, ACrustOnAPointMassCarriesItsWeightDownToTheCentre) {
  // A point mass M0 at the centre and one particle m at r = 1: everything below r = 1 carries
  // m G M0 / (4 pi R^4), nothing beyond it.
  const ParticleHydrostaticPressure p({1.0, 0.0}, {0.25, 0.75});
  const double expected = 0.25 * 0.75 / (4 * std::numbers::pi);
  EXPECT_DOUBLE_EQ(p(0.0), expected);
  EXPECT_DOUBLE_EQ(p(0.5), expected);
  EXPECT_DOUBLE_EQ(p(1.0), 0.0);
  EXPECT_DOUBLE_EQ(p(2.0), 0.0);
}

TEST(ParticleHydrostaticPressure, AUniformCloudFollowsTheContinuumProfileWithin1Percent) {
  // Equal masses on a cubic lattice of spacing h inside the unit sphere, total mass 1: the
  // profile is (2/3) pi rho^2 (1 - r^2) (hydrostatic_pressure) up to the lattice's granularity.
  const double h = 0.03;
  std::vector<double> radius;
  for (double x = -1; x <= 1; x += h)
    for (double y = -1; y <= 1; y += h)
      for (double z = -1; z <= 1; z += h)
        if (const double r = std::sqrt(x * x + y * y + z * z); r < 1) radius.push_back(r);
  const std::vector<double> mass(radius.size(), 1.0 / static_cast<double>(radius.size()));
  const ParticleHydrostaticPressure p(radius, mass);
  for (double r : {0.05, 0.3, 0.6, 0.9})
    EXPECT_NEAR(p(r), hydrostatic_pressure(r), 0.01 * hydrostatic_pressure(0)) << "r = " << r;
}
