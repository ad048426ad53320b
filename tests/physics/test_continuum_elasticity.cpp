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

TEST(ContinuumElasticity, ShidaNumberTendsToTheIncompressibleClosedForm) {
  // Love (1911): l2 = (3/4) / (1 + 19 mu / (2 rho g R)), 3/10 of h2, from fluid-like to rigid.
  for (const double mu : {0.02, 0.3, 3.0}) {
    const double nu = 0.49999;
    const LoveNumbers love = homogeneous_sphere_love_numbers(2, 2 * mu * (1 + nu), nu, mean_density, 1.0);
    const double closed = incompressible_love_l2(mu, mean_density, 1.0);
    EXPECT_NEAR(closed, 0.75 / (1 + 19 * mu / (2 * mean_density * (4 * pi / 3 * mean_density))), 1e-14);
    EXPECT_NEAR(love.l / closed, 1.0, 2e-3) << "mu = " << mu;
  }
}

TEST(ContinuumElasticity, CompressibleSphereWithoutSelfGravityMatchesItsClosedForm) {
  // h2 = (rho g a/mu)(5 lambda + 4 mu)/(19 lambda + 14 mu), l2 = (rho g a/mu)(3 lambda + 2 mu)/(2(19 lambda + 14 mu))
  // (docs/validation.md): the solver's mechanical part, compressibility and l2, without gravity.
  for (const double nu : {0.1, 0.25, 0.4}) {
    for (const double E : {3.07, 30.0}) {
      const LoveNumbers closed = nongravitating_sphere_love_numbers(E, nu, mean_density, 1.0);
      const LoveNumbers solved = layered_sphere_love_numbers(2, {{1.0, E, nu, mean_density}}, 20000, false);
      EXPECT_NEAR(solved.h / closed.h, 1.0, 1e-6) << "nu = " << nu << ", E = " << E;
      EXPECT_NEAR(solved.l / closed.l, 1.0, 1e-6) << "nu = " << nu << ", E = " << E;
      EXPECT_EQ(solved.k, 0.0);
    }
  }
  // nu = 1/4: l2/h2 = 5/18; the incompressible limit is Love's stiff-sphere 5/19, 3/38 (rho g a / mu).
  const LoveNumbers quarter = nongravitating_sphere_love_numbers(3.07, 0.25, mean_density, 1.0);
  EXPECT_NEAR(quarter.l / quarter.h, 5.0 / 18, 1e-14);
  const double mu = 1.0, nu = 0.4999999, rho_g_a_over_mu = mean_density * (4 * pi / 3 * mean_density) / mu;
  const LoveNumbers stiff = nongravitating_sphere_love_numbers(2 * mu * (1 + nu), nu, mean_density, 1.0);
  EXPECT_NEAR(stiff.h / rho_g_a_over_mu, 5.0 / 19, 1e-6);
  EXPECT_NEAR(stiff.l / rho_g_a_over_mu, 3.0 / 38, 1e-6);
}

TEST(ContinuumElasticity, SelfGravityStiffensTheMaterialBodiesAgainstTheTide) {
  // E = 3.07, nu = 1/4 (the material workflows): the surface's own gravity pulls a bulge back, so
  // the self-gravitating sphere deforms less than the same sphere without it (as Love's
  // (5/2)/(1 + 19 mu/(2 rho g a)) lies below its stiff limit 5 rho g a/(19 mu)); l2/h2 stays near 5/18.
  const LoveNumbers with = homogeneous_sphere_love_numbers(2, 3.07, 0.25, mean_density, 1.0);
  const LoveNumbers without = nongravitating_sphere_love_numbers(3.07, 0.25, mean_density, 1.0);
  EXPECT_LT(with.h, without.h);
  EXPECT_GT(with.h, 0.9 * without.h);
  EXPECT_NEAR(with.l / with.h, 5.0 / 18, 0.01);
}

TEST(ContinuumElasticity, FundamentalSpheroidalModeOfAPoissonSphereIsLambs) {
  // Lamb (1882): the n = 2 fundamental (0S2) of a free homogeneous sphere, nu = 1/4, no gravity:
  // omega a / V_S = 2.640 (e.g. Lapwood & Usami 1981, "Free Oscillations of the Earth", table 5.1).
  const double E = 3.07, nu = 0.25, mu = E / (2 * (1 + nu));
  const double shear_speed = std::sqrt(mu / mean_density);
  const double omega = spheroidal_fundamental_frequency(2, {{1.0, E, nu, mean_density}}, false);
  EXPECT_NEAR(omega / shear_speed, 2.640, 5e-4);
  EXPECT_NEAR(spheroidal_fundamental_frequency(2, {{1.0, E, nu, mean_density}}, false, 4000), omega, 1e-6 * omega);
  // Without gravity the ratio does not depend on the modulus or the density.
  EXPECT_NEAR(spheroidal_fundamental_frequency(2, {{1.0, 10 * E, nu, 2 * mean_density}}, false) /
                  std::sqrt(10 * mu / (2 * mean_density)),
              omega / shear_speed, 1e-6);
  // Equal layers are the homogeneous sphere.
  EXPECT_NEAR(spheroidal_fundamental_frequency(2, {{0.5, E, nu, mean_density}, {1.0, E, nu, mean_density}}, false),
              omega, 1e-6 * omega);
}

TEST(ContinuumElasticity, SelfGravityRaisesTheFootballModeByAnAmountFixedByTheDensity) {
  // To first order in G rho (Rayleigh's principle on Lamb's eigenfunction, whose shape does not
  // depend on the modulus) self-gravity adds a constant c g / a to omega^2: the same c for a stiff
  // and a stiffer sphere of the same density: c = 0.643 at nu = 1/4 (docs/validation.md; Kelvin's
  // (1863) fluid sphere has 4/5 with its own, irrotational eigenfunction).
  const double g = 4 * pi / 3 * mean_density;
  const auto shift = [&](double E) {
    const double with = spheroidal_fundamental_frequency(2, {{1.0, E, 0.25, mean_density}}, true);
    const double without = spheroidal_fundamental_frequency(2, {{1.0, E, 0.25, mean_density}}, false);
    return (with * with - without * without) / g;
  };
  const double stiff = shift(30.0), stiffer = shift(300.0);
  EXPECT_GT(stiff, 0.0);
  EXPECT_NEAR(stiff / stiffer, 1.0, 0.02);
  EXPECT_NEAR(stiffer, 0.643, 0.002);
  // The material bodies (E = 3.07): gravity raises omega by a few per cent.
  const double lamb = spheroidal_fundamental_frequency(2, {{1.0, 3.07, 0.25, mean_density}}, false);
  const double gravitating = spheroidal_fundamental_frequency(2, {{1.0, 3.07, 0.25, mean_density}}, true);
  EXPECT_GT(gravitating, lamb);
  EXPECT_LT(gravitating, 1.05 * lamb);
}

// Degree-0 compression of a layered sphere: one layer is 1/(3K); a core in a mantle is Hashin's
// composite sphere (Hashin 1962, J. Appl. Mech. 29, 143: the coated sphere under uniform pressure),
// K = K_m + f (K_c - K_m) / (1 + (1 - f)(K_c - K_m) / (K_m + 4 mu_m / 3)), f = (r_c / a)^3; splitting a
// layer in two changes nothing.
TEST(ContinuumElasticity, ALayeredSphereUnderPressureCompressesAsHashinsCompositeSphere) {
  const auto bulk = [](double e, double nu) { return e / (3 * (1 - 2 * nu)); };
  EXPECT_NEAR(layered_sphere_compression({{1.0, 3.0, 0.25, 0}}), 1 / (3 * bulk(3.0, 0.25)), 1e-15);
  const double rc = 0.5, ec = 30, nuc = 0.3, em = 3, num = 0.25;
  const double kc = bulk(ec, nuc), km = bulk(em, num), mum = em / (2 * (1 + num)), f = rc * rc * rc;
  const double hashin = km + f * (kc - km) / (1 + (1 - f) * (kc - km) / (km + 4 * mum / 3));
  EXPECT_NEAR(layered_sphere_compression({{rc, ec, nuc, 0}, {1.0, em, num, 0}}) * 3 * hashin, 1.0, 1e-13);
  EXPECT_NEAR(layered_sphere_compression({{0.3, ec, nuc, 0}, {rc, ec, nuc, 0}, {0.8, em, num, 0}, {1.0, em, num, 0}}) *
                  3 * hashin, 1.0, 1e-13);
  EXPECT_THROW(layered_sphere_compression({}), InputError);
  EXPECT_THROW(layered_sphere_compression({{0.5, 3, 0.25, 0}, {0.4, 3, 0.25, 0}}), InputError);
  EXPECT_THROW(layered_sphere_compression({{1.0, 3, 0.5, 0}}), InputError);
}
