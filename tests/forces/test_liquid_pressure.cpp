#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "forces/liquid_pressure.hpp"

using namespace tidalcrust;

namespace {

/// A cube of side 1: `side` particles a side on a cubic lattice jittered by 10% of the spacing s
/// (a disordered liquid), joined by liquid springs to every particle within 1.5 s, K = 3, V = s^3
/// each; `solid_layers` more layers of solid (interior) particles around it, joined to the liquid
/// by liquid springs too. Rest lengths: the built lengths (zero pressure).
struct LiquidBlock {
  Body body;
  std::vector<double> position;
  SpringState springs;
  double spacing = 0;
};

LiquidBlock liquid_block(int side, unsigned seed, int solid_layers = 0) {
  LiquidBlock b;
  b.spacing = 1.0 / side;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.1, 0.1);
  const int n = side + 2 * solid_layers;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const bool solid = i < solid_layers || j < solid_layers || k < solid_layers || i >= n - solid_layers ||
                           j >= n - solid_layers || k >= n - solid_layers;
        for (const int c : {i, j, k}) b.position.push_back((c - solid_layers + jitter(rng)) * b.spacing);
        b.body.mass.push_back(1.0 / (n * n * n));
        b.body.species.push_back(static_cast<std::uint8_t>(solid ? Species::interior : Species::liquid));
        b.body.liquid.node_volume.push_back(solid ? 0.0 : b.spacing * b.spacing * b.spacing);
      }
  const auto liquid = static_cast<std::uint8_t>(Species::liquid);
  for (std::size_t p = 0; p < b.body.mass.size(); ++p)
    for (std::size_t q = p + 1; q < b.body.mass.size(); ++q) {
      if (b.body.species[p] != liquid && b.body.species[q] != liquid) continue;
      double d2 = 0;
      for (int c = 0; c < 3; ++c) d2 += std::pow(b.position[3 * p + c] - b.position[3 * q + c], 2);
      if (d2 >= std::pow(1.5 * b.spacing, 2)) continue;
      b.body.springs.push_back({static_cast<std::int32_t>(p), static_cast<std::int32_t>(q)});
      b.body.spring_kind.push_back(static_cast<std::uint8_t>(SpringKind::liquid));
      b.springs.rest_length.push_back(std::sqrt(d2));
      b.springs.stiffness.push_back(0.0);
      b.springs.failed.push_back(0);
    }
  b.body.liquid.bulk_modulus = 3.0;
  return b;
}

/// The affine simple shear x += gamma (z - 1/2).
std::vector<double> sheared(std::vector<double> x, double gamma) {
  for (std::size_t p = 0; p < x.size() / 3; ++p) x[3 * p] += gamma * (x[3 * p + 2] - 0.5);
  return x;
}

/// Least-squares slope of the x displacement against z: the block's shear.
double shear_of(const std::vector<double>& x, const std::vector<double>& reference) {
  const std::size_t n = x.size() / 3;
  double mz = 0, mx = 0;
  for (std::size_t p = 0; p < n; ++p) {
    mz += reference[3 * p + 2] / static_cast<double>(n);
    mx += (x[3 * p] - reference[3 * p]) / static_cast<double>(n);
  }
  double szz = 0, sxz = 0;
  for (std::size_t p = 0; p < n; ++p) {
    const double z = reference[3 * p + 2] - mz, dx = x[3 * p] - reference[3 * p] - mx;
    szz += z * z;
    sxz += z * dx;
  }
  return sxz / szz;
}

}  // namespace

// The forces are minus the gradient of the energy (finite differences on every coordinate of
// liquid and solid particles under pressure), and they sum to zero force and zero torque.
TEST(LiquidPressure, ForcesAreMinusTheEnergyGradientAndConserveMomentum) {
  LiquidBlock b = liquid_block(4, 3, 1);
  for (double& l : b.springs.rest_length) l *= 1.01;  // compressed: a pressure of about 3 K 0.01
  LiquidPressure liquid(b.body);
  liquid.compute(b.position.data(), b.springs, false);
  const std::vector<double> f = liquid.forces();
  double fmax = 0;
  for (const double c : f) fmax = std::max(fmax, std::abs(c));
  ASSERT_GT(fmax, 0.0);
  for (const std::size_t p : {std::size_t{0}, std::size_t{43}, std::size_t{86}, std::size_t{129}}) {
    for (int k = 0; k < 3; ++k) {
      const double h = 1e-6;
      std::vector<double> plus = b.position, minus = b.position;
      plus[3 * p + k] += h;
      minus[3 * p + k] -= h;
      const double gradient = (liquid.energy(plus.data(), b.springs) - liquid.energy(minus.data(), b.springs)) / (2 * h);
      EXPECT_NEAR(f[3 * p + k], -gradient, 1e-6 * fmax) << "particle " << p << " axis " << k;
    }
  }
  double sum[3] = {0, 0, 0}, torque[3] = {0, 0, 0};
  for (std::size_t p = 0; p < b.body.mass.size(); ++p) {
    const double* x = &b.position[3 * p];
    const double* fp = &f[3 * p];
    for (int k = 0; k < 3; ++k) sum[k] += fp[k];
    torque[0] += x[1] * fp[2] - x[2] * fp[1];
    torque[1] += x[2] * fp[0] - x[0] * fp[2];
    torque[2] += x[0] * fp[1] - x[1] * fp[0];
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(sum[k], 0.0, 1e-13);
    EXPECT_NEAR(torque[k], 0.0, 1e-13);
  }
}

// A uniform compression by a factor c in length gives every liquid particle theta = 3 (c - 1),
// the pressure K times the relative change of volume to first order; a pure shear gives a theta
// of second order only on average.
TEST(LiquidPressure, AUniformCompressionGivesTheBulkModulusAndAShearNoVolume) {
  LiquidBlock b = liquid_block(6, 5);
  LiquidPressure liquid(b.body);
  std::vector<double> x = b.position;
  const double c = 0.999;
  for (double& v : x) v *= c;
  for (const double p : liquid.pressure(x.data(), b.springs)) EXPECT_NEAR(p, -3.0 * 3 * (c - 1), 1e-12);
  const std::vector<double> theta = liquid.volumetric_strain(sheared(b.position, 1e-3).data(), b.springs);
  double mean = 0;
  for (const double t : theta) mean += t / static_cast<double>(theta.size());
  EXPECT_LT(std::abs(mean), 1e-5);  // |theta| of single particles is of order 1e-4 (disorder)
}

// The measurement of "no static shear": a liquid block at zero pressure is sheared affinely by
// 1%; letting its particles move to lower the energy takes out nearly all of it while the block
// keeps its shear (nothing pulls it back). A solid would keep the energy of the shear.
TEST(LiquidPressure, ALiquidBlockCarriesNoStaticShear) {
  LiquidBlock b = liquid_block(6, 11);
  LiquidPressure liquid(b.body);
  const double gamma = 0.01;
  std::vector<double> x = sheared(b.position, gamma);
  const double affine = liquid.energy(x.data(), b.springs);
  ASSERT_GT(affine, 0.0);
  // Steepest descent, x += alpha F, alpha below the inverse curvature of the stiffest mode (~ K s).
  const double alpha = 0.1 / (b.body.liquid.bulk_modulus * b.spacing);
  for (int it = 0; it < 3000; ++it) {
    liquid.compute(x.data(), b.springs, false);
    for (std::size_t i = 0; i < x.size(); ++i) x[i] += alpha * liquid.forces()[i];
  }
  const double relaxed = liquid.energy(x.data(), b.springs);
  EXPECT_LT(relaxed, 0.02 * affine) << "affine " << affine << " relaxed " << relaxed;
  EXPECT_GT(shear_of(x, b.position), 0.9 * gamma);
}

// The same bits on one thread and on several.
TEST(LiquidPressure, ForcesAreBitwiseTheSameForAnyThreadCount) {
  LiquidBlock b = liquid_block(6, 17, 1);
  for (double& l : b.springs.rest_length) l *= 1.02;
  std::mt19937_64 rng(1);
  std::normal_distribution<double> g(0.0, 0.01);
  for (double& c : b.position) c += g(rng);
  LiquidPressure liquid(b.body);
  liquid.compute(b.position.data(), b.springs, false);
  const std::vector<double> serial = liquid.forces();
  liquid.compute(b.position.data(), b.springs, true);
  EXPECT_EQ(serial, liquid.forces());
}
