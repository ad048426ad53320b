// The static moduli measurement of a spring network (physics/network_moduli.hpp): exact on a
// perfect FCC lattice, where the affine deformation is the equilibrium, and below the affine
// (eq. 15) value on a random network, where the nodes relax off the affine positions.
#include <gtest/gtest.h>

#include <cmath>

#include "base/errors.hpp"
#include "base/invariant.hpp"
#include "base/random.hpp"
#include "physics/network_moduli.hpp"

using namespace tidalcrust;

namespace {

struct Network {
  std::vector<Vec3> positions;
  std::vector<NetworkSpring> springs;
};

/// Springs k between all node pairs closer than `reach`, rest length = `rest_factor` times the
/// distance (1: no pre-stress).
void connect(Network& net, double reach, double k, double rest_factor = 1.0) {
  for (std::size_t a = 0; a < net.positions.size(); ++a)
    for (std::size_t b = a + 1; b < net.positions.size(); ++b) {
      const double d = (net.positions[a] - net.positions[b]).norm();
      if (d < reach)
        net.springs.push_back({static_cast<std::int32_t>(a), static_cast<std::int32_t>(b), rest_factor * d, k});
    }
}

/// FCC nodes (cubic cell 1, nearest-neighbour distance 1/sqrt 2) within `radius` of the origin,
/// nearest neighbours joined by springs k.
Network fcc_ball(double radius, double k) {
  Network net;
  const Vec3 basis[4] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  const int n = static_cast<int>(std::ceil(radius)) + 1;
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      for (int l = -n; l <= n; ++l)
        for (const auto& b : basis) {
          const Vec3 x = Vec3(i, j, l) + b;
          if (x.norm() <= radius) net.positions.push_back(x);
        }
  connect(net, 0.75, k);  // nearest neighbours only (the next are 1 apart)
  return net;
}

/// Random nodes in a ball (no two closer than `separation`), joined within `reach`.
Network random_ball(int count, double radius, double separation, double reach, double k) {
  Network net;
  Random random(11);
  while (static_cast<int>(net.positions.size()) < count) {
    const Vec3 x(radius * (2 * random.uniform() - 1), radius * (2 * random.uniform() - 1),
                 radius * (2 * random.uniform() - 1));
    if (x.norm() > radius) continue;
    bool close = false;
    for (const auto& y : net.positions) close = close || (x - y).norm() < separation;
    if (!close) net.positions.push_back(x);
  }
  connect(net, reach, k);
  return net;
}

}  // namespace

TEST(NetworkModuli, PerfectFccLatticeDeformsAffinelyWithItsCubicConstants) {
  // Nearest-neighbour central springs on FCC: C11 = sqrt(2) k / L, C12 = C44 = k / (sqrt(2) L)
  // (Cauchy relation), L = 1/sqrt(2): 2k and k. Every node is a centre of inversion, so the
  // relaxed and the affine response are the same.
  const double k = 0.7;
  const Network net = fcc_ball(6.2, k);
  const NetworkModuli m = measure_network_moduli(net.positions, net.springs, Vec3(0.013, 0.021, 0.017), 4.6, 3.6);
  EXPECT_GT(m.free_nodes, 1000);
  EXPECT_GT(m.held_nodes, 1000);
  // No relaxation: relaxed == affine to rounding.
  EXPECT_LT((m.relaxed - m.affine).norm(), 1e-7 * m.affine.norm());
  // The cubic constants within 0.5% (the measured sphere cuts the lattice; found within 0.1%).
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(m.relaxed(a, a), 2 * k, 0.005 * 2 * k);
    EXPECT_NEAR(m.relaxed(a + 3, a + 3), k, 0.005 * k);
    for (int b = 0; b < 3; ++b)
      if (a != b) {
        EXPECT_NEAR(m.relaxed(a, b), k, 0.005 * k);
      }
    for (int b = 3; b < 6; ++b) EXPECT_NEAR(m.relaxed(a, b), 0.0, 1e-3 * k);  // no normal-shear coupling
  }
  // The Voigt average of the affine tensor is eq. 15 with nu = 1/4, on any network, exactly.
  EXPECT_NEAR(m.affine_moduli.youngs / m.eq15_youngs, 1.0, 1e-9);
  EXPECT_NEAR(m.affine_moduli.poisson, 0.25, 1e-9);
  EXPECT_NEAR(m.reference_pressure, 0.0, 1e-12);  // rest lengths = lengths: no pre-stress
}

TEST(NetworkModuli, RandomNetworkIsSofterThanAffine) {
  // A random network relaxes off the affine positions: every modulus below the affine (Voigt)
  // bound; shear more than bulk. This network (13 springs per node, 685 of its 1500 nodes free)
  // keeps 0.81 of its affine bulk and 0.74 of its shear modulus (measured; nu 0.268).
  const Network net = random_ball(1500, 1.0, 0.09, 0.22, 1.0);
  const NetworkModuli m = measure_network_moduli(net.positions, net.springs, Vec3::Zero(), 0.78, 0.67);
  EXPECT_LT(m.relaxed_moduli.shear, m.affine_moduli.shear);
  EXPECT_LT(m.relaxed_moduli.bulk, m.affine_moduli.bulk * (1 + 1e-12));
  EXPECT_LT(m.relaxed_moduli.shear / m.affine_moduli.shear, m.relaxed_moduli.bulk / m.affine_moduli.bulk);
  EXPECT_NEAR(m.relaxed_moduli.bulk / m.affine_moduli.bulk, 0.81, 0.02);
  EXPECT_NEAR(m.relaxed_moduli.shear / m.affine_moduli.shear, 0.74, 0.02);
  EXPECT_NEAR(m.affine_moduli.youngs / m.eq15_youngs, 1.0, 1e-9);
  // Without pre-stress the unstressed measurement is the same network: identical result.
  const NetworkModuli same = measure_network_moduli(net.positions, net.springs, Vec3::Zero(), 0.78, 0.67, 1e-6, false);
  EXPECT_LT((same.relaxed - m.relaxed).norm(), 1e-9 * m.relaxed.norm());
}

TEST(NetworkModuli, StrainAmplitudeDoesNotMatter) {
  const Network net = random_ball(400, 1.0, 0.14, 0.35, 1.0);
  const NetworkModuli a = measure_network_moduli(net.positions, net.springs, Vec3::Zero(), 0.65, 0.5, 1e-6);
  const NetworkModuli b = measure_network_moduli(net.positions, net.springs, Vec3::Zero(), 0.65, 0.5, 1e-4);
  EXPECT_NEAR(a.relaxed_moduli.youngs / b.relaxed_moduli.youngs, 1.0, 1e-6);
  EXPECT_NEAR(a.relaxed_moduli.poisson, b.relaxed_moduli.poisson, 1e-6);
}

TEST(NetworkModuli, BadGeometryIsInputErrorAndBadArgumentsAnInternalError) {
  const Network net = random_ball(200, 1.0, 0.18, 0.4, 1.0);
  // The caller's arguments: measure radius beyond the hold radius, a spring to no node.
  EXPECT_THROW(measure_network_moduli(net.positions, net.springs, Vec3::Zero(), 0.5, 0.6), InternalError);
  std::vector<NetworkSpring> bad = net.springs;
  bad.push_back({0, 999, 0.1, 1.0});
  EXPECT_THROW(measure_network_moduli(net.positions, bad, Vec3::Zero(), 0.6, 0.5), InternalError);
  // The body's: too small a network to hold any node (validate reports it and goes on).
  EXPECT_THROW(measure_network_moduli(net.positions, net.springs, Vec3::Zero(), 5.0, 0.6), InputError);  // none held
  EXPECT_THROW(isotropic_moduli_from_bulk_shear(1.0, 0.0), InputError);
}

TEST(NetworkModuli, IsotropicModuliOfBulkAndShear) {
  // lambda = mu = 1: K = 5/3, E = 5/2, nu = 1/4.
  const IsotropicModuli m = isotropic_moduli_from_bulk_shear(5.0 / 3, 1.0);
  EXPECT_NEAR(m.youngs, 2.5, 1e-14);
  EXPECT_NEAR(m.poisson, 0.25, 1e-14);
}
