// The continuum-elasticity solvers that `validate` compares the network with, each against a
// published value or closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "base/errors.hpp"
#include "model/derived_quantities.hpp"
#include "physics/continuum_elasticity.hpp"

using namespace tidalcrust;

namespace {
constexpr double pi = std::numbers::pi;
constexpr double mean_density = 3 / (4 * pi);  // M = R = 1
}  // namespace

TEST(ContinuumElasticity, LambBreathingRootForPoissonRatioOneQuarterIsLovesValue) {
  // Love (1927) sec. 195: for nu = 1/4 the radial modes have h a / pi = 0.8160, 1.9285, ...
  EXPECT_NEAR(lamb_breathing_root(0.25) / pi, 0.8160, 5e-5);
  // The root satisfies tan x / x = 1 / (1 - 3 x^2 / 4) itself.
  const double x = lamb_breathing_root(0.25);
  EXPECT_NEAR(std::tan(x) / x, 1 / (1 - 0.75 * x * x), 1e-10);
}

TEST(ContinuumElasticity, LambBreathingRootTendsToPiInTheIncompressibleLimit) {
  // (lambda + 2 mu)/(4 mu) -> infinity: sin x = 0, x = pi (Love sec. 195).
  EXPECT_NEAR(lamb_breathing_root(0.4999999) / pi, 1.0, 1e-4);
}

TEST(ContinuumElasticity, BreathingPeriodFollowsFromRootAndPWaveSpeed) {
  const double E = 5.0;
  const double v_p = p_wave_speed(E, 0.25, mean_density);
  EXPECT_NEAR(v_p, std::sqrt(1.2 * E / mean_density), 1e-12);  // (1-nu)/((1+nu)(1-2nu)) = 6/5
  EXPECT_NEAR(lamb_breathing_period(E, 0.25, mean_density, 1.0), 2 * pi / (0.8160 * pi * v_p), 1e-4);
}

TEST(ContinuumElasticity, SelfGravityLowersTheBreathingFrequencyByAConstant) {
  // omega^2 = omega_Lamb^2 - (16 pi / 3) G rho: 4 t_grav^-2 at the mean density 3/(4 pi).
  for (const double E : {1.0, 5.0}) {
    const double lamb = lamb_breathing_period(E, 0.25, mean_density, 1.0);
    const double gravitating = self_gravitating_breathing_period(E, 0.25, mean_density, 1.0);
    EXPECT_NEAR(std::pow(2 * pi / gravitating, 2), std::pow(2 * pi / lamb, 2) - 4, 1e-9);
  }
  EXPECT_THROW(self_gravitating_breathing_period(0.01, 0.25, mean_density, 1.0), InputError);
}

TEST(ContinuumElasticity, LoveNumberTendsToTheIncompressibleClosedForm) {
  // Love (1911): h2 = (5/2) / (1 + 19 mu / (2 rho g R)); from a fluid-like to a rigid sphere.
  for (const double mu : {0.02, 0.3, 3.0}) {
    const double nu = 0.49999;
    const LoveNumbers love = homogeneous_sphere_love_numbers(2, 2 * mu * (1 + nu), nu, mean_density, 1.0);
    const double closed = incompressible_love_h2(mu, mean_density, 1.0);
    EXPECT_NEAR(love.h / closed, 1.0, 2e-3) << "mu = " << mu;
    EXPECT_NEAR(love.k / (0.6 * closed), 1.0, 2e-3) << "mu = " << mu;  // k2 = 3/5 h2 (homogeneous)
  }
}

TEST(ContinuumElasticity, CompressibleSphereIsSofterThanIncompressibleAtEqualShearModulus) {
  // At nu = 1/4 the volume change adds radial compliance: h2 is larger than at nu = 1/2.
  const double mu = 2.0;
  const LoveNumbers quarter = homogeneous_sphere_love_numbers(2, 2 * mu * 1.25, 0.25, mean_density, 1.0);
  EXPECT_GT(quarter.h, incompressible_love_h2(mu, mean_density, 1.0) * 1.02);
  EXPECT_LT(quarter.h, incompressible_love_h2(mu, mean_density, 1.0) * 2.0);
  // and the result has converged in the step count
  const LoveNumbers coarse = homogeneous_sphere_love_numbers(2, 2 * mu * 1.25, 0.25, mean_density, 1.0, 4000);
  EXPECT_NEAR(coarse.h / quarter.h, 1.0, 1e-6);
}

TEST(ContinuumElasticity, PlateDeflectionAndHingeLatticeRigidity) {
  // D w'''' = q with w = w0 sin(k x): w0 = q0 / (D k^4).
  EXPECT_DOUBLE_EQ(plate_sinusoidal_deflection(2.0, 0.5, 4.0), 2.0 / (4.0 * 0.0625));
  EXPECT_DOUBLE_EQ(hinge_lattice_flexural_rigidity(0.0075), 0.0075 / 4);
}

TEST(ContinuumElasticity, BadMaterialIsAnInputError) {
  EXPECT_THROW(lamb_breathing_root(0.5), InputError);
  EXPECT_THROW(p_wave_speed(-1, 0.25, 1), InputError);
  EXPECT_THROW(homogeneous_sphere_love_numbers(1, 1, 0.25, 1, 1), InputError);
  EXPECT_THROW(plate_sinusoidal_deflection(1, 0, 1), InputError);
}

TEST(ContinuumElasticity, LayeredSphereOfEqualLayersIsTheHomogeneousSphere) {
  const double E = 3.9;
  const LoveNumbers one = homogeneous_sphere_love_numbers(2, E, 0.25, mean_density, 1.0);
  const LoveNumbers four = layered_sphere_love_numbers(
      2, {{0.3, E, 0.25, mean_density}, {0.55, E, 0.25, mean_density}, {0.9, E, 0.25, mean_density},
          {1.0, E, 0.25, mean_density}});
  EXPECT_NEAR(four.h / one.h, 1.0, 1e-6);
  EXPECT_NEAR(four.k / one.k, 1.0, 1e-6);
  EXPECT_NEAR(four.l / one.l, 1.0, 1e-6);
}

TEST(ContinuumElasticity, LayeredSphereLiesBetweenItsLayersAndFeelsTheOuterOneMost) {
  // A 10x stiffer core of half the radius: h2 between the homogeneous spheres of either modulus,
  // and nearer the mantle's (a degree-2 tide strains the outside most); the same modulus
  // outside a softer core changes h2 less than a softer mantle over the same core.
  const double E = 3.0, rho = mean_density;
  const double mantle = homogeneous_sphere_love_numbers(2, E, 0.25, rho, 1.0).h;
  const double core = homogeneous_sphere_love_numbers(2, 10 * E, 0.25, rho, 1.0).h;
  const double layered = layered_sphere_love_numbers(2, {{0.5, 10 * E, 0.25, rho}, {1.0, E, 0.25, rho}}).h;
  EXPECT_LT(layered, mantle);
  EXPECT_GT(layered, core);
  EXPECT_LT(mantle - layered, layered - core);
  const double soft_core = layered_sphere_love_numbers(2, {{0.5, 0.5 * E, 0.25, rho}, {1.0, E, 0.25, rho}}).h;
  const double soft_mantle = layered_sphere_love_numbers(2, {{0.5, E, 0.25, rho}, {1.0, 0.5 * E, 0.25, rho}}).h;
  EXPECT_GT(soft_core, mantle);
  EXPECT_GT(soft_mantle - mantle, 2 * (soft_core - mantle));
  EXPECT_THROW(layered_sphere_love_numbers(2, {}), InputError);
  EXPECT_THROW(layered_sphere_love_numbers(2, {{0.5, E, 0.25, rho}, {0.4, E, 0.25, rho}}), InputError);
}
