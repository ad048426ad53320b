// The pieces of `validate --measure tide` (analysis/tidal_response.hpp) on synthetic fields where
// the answer is known exactly: the h2/l2 fit, the continuum surface strain, the spring-by-spring
// ratio statistics.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "analysis/tidal_response.hpp"
#include "base/errors.hpp"
#include "bodies/icosphere.hpp"

using namespace tidalcrust;

namespace {

/// A level-2 icosphere of shell nodes (inversion-symmetric, so an even field keeps the centre of
/// mass) around one interior node at the centre.
struct SyntheticBody {
  Body body;
  State rest;
  SyntheticBody() {
    const Icosphere ico = make_icosphere(2);
    body.mass.push_back(0.5);
    body.species.push_back(static_cast<std::uint8_t>(Species::interior));
    rest.position = {0, 0, 0};
    for (const Vec3& n : ico.nodes) {
      body.mass.push_back(0.5 / static_cast<double>(ico.nodes.size()));
      body.species.push_back(static_cast<std::uint8_t>(Species::shell));
      for (int k = 0; k < 3; ++k) rest.position.push_back(0.98 * n[k]);
    }
  }
  /// rest + eps (h r^4 P2 r_hat + l r^3 dP2/dtheta theta_hat) + a0 r_hat on the shell nodes,
  /// written in spherical coordinates.
  State displaced(double eps, double h, double l, double a0) const {
    State s = rest;
    for (std::size_t i = 0; i < body.particle_count(); ++i) {
      if (body.species[i] != static_cast<std::uint8_t>(Species::shell)) continue;
      const Vec3 x = vec3_at(rest.position, i);
      const double r = x.norm(), theta = std::acos(x.z() / r), phi = std::atan2(x.y(), x.x());
      const Vec3 r_hat(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      const Vec3 theta_hat(std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi), -std::sin(theta));
      const double p2 = 0.5 * (3 * std::cos(theta) * std::cos(theta) - 1);
      const double dp2 = -3 * std::cos(theta) * std::sin(theta);
      set_vec3(s.position, i, x + (a0 + eps * h * std::pow(r, 4) * p2) * r_hat + eps * l * std::pow(r, 3) * dp2 * theta_hat);
    }
    return s;
  }
};

}  // namespace

TEST(TidalResponse, DegreeTwoFitRecoversASyntheticFieldExactly) {
  const SyntheticBody b;
  const double eps = 0.03, h = 0.0319, l = 0.00883, a0 = 2e-4;
  // Against the rest state: the uniform shift is a0.
  const State plus = b.displaced(eps, h, l, a0);
  const DegreeTwoFit one = fit_degree_two_displacement(b.body, b.rest, plus, nullptr, eps);
  EXPECT_NEAR(one.h2, h, 1e-12);
  EXPECT_NEAR(one.l2, l, 1e-12);
  EXPECT_NEAR(one.uniform, a0, 1e-14);
  EXPECT_NEAR(one.mean_radius, 0.98, 1e-12);
  EXPECT_LT(one.rms_azimuthal, 1e-12);  // axisymmetric
  // (plus - minus)/2: the common shift cancels, h2 and l2 stay.
  const State minus = b.displaced(-eps, h, l, a0);
  const DegreeTwoFit two = fit_degree_two_displacement(b.body, b.rest, plus, &minus, eps);
  EXPECT_NEAR(two.h2, h, 1e-12);
  EXPECT_NEAR(two.l2, l, 1e-12);
  EXPECT_NEAR(two.uniform, 0.0, 1e-14);
  Body no_shell;
  no_shell.mass = {1.0};
  no_shell.species = {static_cast<std::uint8_t>(Species::interior)};
  State one_node;
  one_node.position = {0, 0, 0};
  EXPECT_THROW(fit_degree_two_displacement(no_shell, one_node, one_node, nullptr, eps), InputError);
}

TEST(TidalResponse, ContinuumSurfaceStrainIsIsotropicAtThePoleAndHasItsClosedFormAtTheEquator) {
  const double h = 0.0319, l = 0.00883;
  const SurfaceStrain pole = continuum_surface_strain(h, l, 0.0);
  EXPECT_NEAR(pole.meridional, h - 3 * l, 1e-15);  // no preferred direction on the axis
  EXPECT_NEAR(pole.azimuthal, h - 3 * l, 1e-15);
  const SurfaceStrain equator = continuum_surface_strain(h, l, M_PI / 2);
  EXPECT_NEAR(equator.meridional, -0.5 * h + 3 * l, 1e-15);
  EXPECT_NEAR(equator.azimuthal, -0.5 * h, 1e-15);
}

TEST(TidalResponse, StrainRatioSpreadIsTheMedianAndHalfThe16To84RangeOfTheClearSprings) {
  // Every clear spring at 1.2x, a near-zero prediction wildly off: left out (rms 4.15, cut 2.07).
  const std::vector<double> theory = {3.0, -4.0, 5.0, -6.0, 1e-3};
  const std::vector<double> measured = {3.6, -4.8, 6.0, -7.2, 5.0};
  const StrainRatioSpread same = strain_ratio_spread(measured, theory);
  EXPECT_NEAR(same.median, 1.2, 1e-15);
  EXPECT_NEAR(same.scatter, 0.0, 1e-15);
  EXPECT_EQ(same.springs, 4);
  // Ratios 0, 0.01, ..., 1: median 0.5, 16th and 84th percentiles 0.16 and 0.84.
  std::vector<double> ones(101, 1.0), spread(101);
  for (int i = 0; i <= 100; ++i) spread[i] = 0.01 * i;
  const StrainRatioSpread s = strain_ratio_spread(spread, ones);
  EXPECT_NEAR(s.median, 0.5, 1e-12);
  EXPECT_NEAR(s.scatter, 0.34, 1e-12);
  EXPECT_EQ(s.springs, 101);
  EXPECT_THROW(strain_ratio_spread({1.0}, {1.0, 2.0}), InputError);
  EXPECT_THROW(strain_ratio_spread({1.0}, {0.0}), InputError);
}
