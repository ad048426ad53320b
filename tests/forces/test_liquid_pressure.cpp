#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "forces/liquid_pressure.hpp"

using namespace tidalcrust;

namespace {

/// A cube of side 1: `side` + 1 particles a side on a cubic lattice of spacing s = 1/side, jittered
/// by 10% of s (disordered), each cell cut into six tetrahedra around its main diagonal (Kuhn);
/// the particles on the cube's faces solid when `solid_faces`, the rest liquid; K = 3; rest
/// volumes the volumes as built (zero pressure).
struct LiquidBlock {
  Body body;
  std::vector<double> position;
  std::vector<double> rest_volume;
  double spacing = 0;
};

LiquidBlock liquid_block(int side, unsigned seed, bool solid_faces = false) {
  LiquidBlock b;
  b.spacing = 1.0 / side;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.1, 0.1);
  const int m = side + 1;
  auto index = [m](int i, int j, int k) { return static_cast<std::int32_t>((i * m + j) * m + k); };
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k) {
        const bool face = i == 0 || j == 0 || k == 0 || i == side || j == side || k == side;
        for (const int c : {i, j, k}) b.position.push_back((c + jitter(rng)) * b.spacing);
        b.body.mass.push_back(1.0 / (m * m * m));
        b.body.species.push_back(static_cast<std::uint8_t>(solid_faces && face ? Species::interior : Species::liquid));
      }
  // The six tetrahedra of a cube along the diagonal 0-7 (corners c = 4 dx + 2 dy + dz).
  const int paths[6][4] = {{0, 4, 6, 7}, {0, 4, 5, 7}, {0, 2, 6, 7}, {0, 2, 3, 7}, {0, 1, 5, 7}, {0, 1, 3, 7}};
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (int k = 0; k < side; ++k)
        for (const auto& path : paths) {
          std::array<std::int32_t, 4> t{};
          for (int v = 0; v < 4; ++v) t[static_cast<std::size_t>(v)] = index(i + (path[v] >> 2), j + ((path[v] >> 1) & 1), k + (path[v] & 1));
          const double* p = b.position.data();
          if (tetrahedron_volume(p + 3 * t[0], p + 3 * t[1], p + 3 * t[2], p + 3 * t[3]) < 0) std::swap(t[2], t[3]);
          bool wet = false;
          for (const std::int32_t c : t) wet = wet || b.body.species[static_cast<std::size_t>(c)] == static_cast<std::uint8_t>(Species::liquid);
          if (wet) b.body.liquid.tetrahedra.push_back(t);
        }
  b.body.liquid.bulk_modulus = 3.0;
  b.rest_volume = LiquidPressure(b.body).volumes(b.position.data());
  return b;
}

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

TEST(LiquidPressure, TetrahedronVolumeIsASixthOfTheDeterminant) {
  const double o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, y[3] = {0, 2, 0}, z[3] = {0, 0, 3};
  EXPECT_DOUBLE_EQ(tetrahedron_volume(o, x, y, z), 1.0);
  EXPECT_DOUBLE_EQ(tetrahedron_volume(o, y, x, z), -1.0);
}

// The forces are minus the gradient of the energy (finite differences on liquid and solid
// corners, under pressure), and they sum to zero force and zero torque.
TEST(LiquidPressure, ForcesAreMinusTheEnergyGradientAndConserveMomentum) {
  LiquidBlock b = liquid_block(4, 3, true);
  for (double& v : b.rest_volume) v *= 1.01;  // compressed
  LiquidPressure liquid(b.body);
  liquid.compute(b.position.data(), b.rest_volume, {}, false);
  const std::vector<double> f = liquid.forces();
  double fmax = 0;
  for (const double c : f) fmax = std::max(fmax, std::abs(c));
  ASSERT_GT(fmax, 0.0);
  for (const std::size_t p : {std::size_t{0}, std::size_t{31}, std::size_t{62}, std::size_t{93}}) {
    for (int k = 0; k < 3; ++k) {
      const double h = 1e-6;
      std::vector<double> plus = b.position, minus = b.position;
      plus[3 * p + k] += h;
      minus[3 * p + k] -= h;
      const double gradient = (liquid.energy(plus.data(), b.rest_volume, {}) - liquid.energy(minus.data(), b.rest_volume, {})) / (2 * h);
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
    EXPECT_NEAR(sum[k], 0.0, 1e-14);
    EXPECT_NEAR(torque[k], 0.0, 1e-14);
  }
}

// A uniform compression by c in length changes every volume by c^3: pressure K (1 - c^3) exactly.
TEST(LiquidPressure, AUniformCompressionGivesTheBulkModulus) {
  LiquidBlock b = liquid_block(5, 5);
  LiquidPressure liquid(b.body);
  std::vector<double> x = b.position;
  const double c = 0.999;
  for (double& v : x) v *= c;
  for (const double p : liquid.pressure(x.data(), b.rest_volume)) EXPECT_NEAR(p, 3.0 * (1 - c * c * c), 1e-12);
}

// The measurement of "no static shear": a liquid block at zero pressure sheared affinely by 1%
// (which keeps every volume: energy 0 at once), then pushed off its affine shape by noise and left
// to lower its energy, keeps its shear: nothing pulls it back. A compressed one does not keep its
// compression: its energy stays.
TEST(LiquidPressure, ALiquidBlockCarriesNoStaticShear) {
  LiquidBlock b = liquid_block(6, 11);
  LiquidPressure liquid(b.body);
  const double gamma = 0.01;
  std::vector<double> x = sheared(b.position, gamma);
  EXPECT_LT(liquid.energy(x.data(), b.rest_volume, {}), 1e-20);  // a simple shear keeps every volume
  std::mt19937_64 rng(4);
  std::normal_distribution<double> noise(0.0, 1e-3 * b.spacing);
  for (double& c : x) c += noise(rng);
  const double noisy = liquid.energy(x.data(), b.rest_volume, {});
  ASSERT_GT(noisy, 0.0);
  const double alpha = 0.05 / (b.body.liquid.bulk_modulus * b.spacing);
  for (int it = 0; it < 2000; ++it) {
    liquid.compute(x.data(), b.rest_volume, {}, false);
    for (std::size_t i = 0; i < x.size(); ++i) x[i] += alpha * liquid.forces()[i];
  }
  EXPECT_LT(liquid.energy(x.data(), b.rest_volume, {}), 0.05 * noisy);
  EXPECT_NEAR(shear_of(x, b.position), gamma, 0.05 * gamma);
}

// The same bits on one thread and on several.
TEST(LiquidPressure, ForcesAreBitwiseTheSameForAnyThreadCount) {
  LiquidBlock b = liquid_block(6, 17, true);
  for (double& v : b.rest_volume) v *= 1.02;
  std::mt19937_64 rng(1);
  std::normal_distribution<double> g(0.0, 0.01);
  for (double& c : b.position) c += g(rng);
  LiquidPressure liquid(b.body);
  liquid.compute(b.position.data(), b.rest_volume, {}, false);
  const std::vector<double> serial = liquid.forces();
  liquid.compute(b.position.data(), b.rest_volume, {}, true);
  EXPECT_EQ(serial, liquid.forces());
}
