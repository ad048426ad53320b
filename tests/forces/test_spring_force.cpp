#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "forces/spring_force.hpp"

using namespace tidalcrust;

namespace {

/// Force on particle i of a spring with rest length L0, stiffness k, damping gamma * mu.
Vec3 spring_force(const Vec3& d, const Vec3& dv, double rest_length, double stiffness, double gamma, double mu,
                  const CrossSoftening* softening = nullptr) {
  return SpringEvaluator(rest_length, stiffness, gamma * mu, softening).force(d, dv);
}

double energy(const Vec3& d, double rest_length, double stiffness, const CrossSoftening* softening = nullptr) {
  return SpringEvaluator(rest_length, stiffness, 0.0, softening).force_and_energy(d.norm(), 0.0).energy;
}

/// Central finite-difference gradient of energy() with respect to d (= x_i - x_j, so it is the
/// gradient with respect to x_i).
Vec3 energy_gradient(const Vec3& d, double rest_length, double stiffness, const CrossSoftening* softening = nullptr) {
  const double h = 1e-6;
  Vec3 g;
  for (int c = 0; c < 3; ++c) {
    Vec3 plus = d, minus = d;
    plus[c] += h;
    minus[c] -= h;
    g[c] = (energy(plus, rest_length, stiffness, softening) - energy(minus, rest_length, stiffness, softening)) /
           (2 * h);
  }
  return g;
}

}  // namespace

TEST(SpringForce, ElasticForceIsMinusTheEnergyGradient) {
  const double k = 0.076, rest = 0.2;
  for (const Vec3& d : {Vec3(0.21, 0.03, -0.02), Vec3(-0.05, 0.1, 0.12), Vec3(0.3, -0.2, 0.1)}) {
    const Vec3 f = spring_force(d, Vec3::Zero(), rest, k, 0.0, 1.0);
    const double stretch = d.norm() - rest;
    EXPECT_DOUBLE_EQ(energy(d, rest, k), 0.5 * k * stretch * stretch);
    EXPECT_LT((f + energy_gradient(d, rest, k)).norm(), 1e-8 * f.norm());
  }
}

TEST(SpringForce, ElasticForcePullsWhenStretchedAndPushesWhenCompressed) {
  const Vec3 d(0.3, 0, 0);  // i to the right of j
  EXPECT_LT(spring_force(d, Vec3::Zero(), 0.25, 1.0, 0, 1.0).x(), 0);  // stretched: i pulled back
  EXPECT_GT(spring_force(d, Vec3::Zero(), 0.35, 1.0, 0, 1.0).x(), 0);  // compressed: i pushed out
  EXPECT_DOUBLE_EQ(spring_force(d, Vec3::Zero(), 0.25, 1.0, 0, 1.0).x(), -0.05);
}

TEST(SpringForce, ZeroAtRest) {
  const Vec3 d(0.1, 0.2, -0.05);
  const SpringForceEnergy r = SpringEvaluator(d.norm(), 0.5, 50.0 * 0.01).force_and_energy(d.norm(), 0.0);
  EXPECT_EQ(r.coefficient, 0.0);
  EXPECT_EQ(r.energy, 0.0);
  EXPECT_EQ(r.dissipated_power, 0.0);
}

TEST(SpringForce, DampingOpposesRelativeMotionAlongTheSpring) {
  const Vec3 d(0.2, 0.05, 0.0);
  const double gamma = 2.0, mu = 0.005;
  const Vec3 separating = 0.3 * d.normalized();
  const Vec3 f = spring_force(d, separating, d.norm(), 0.0, gamma, mu);
  EXPECT_LT(f.dot(separating), 0);
  // |F| = gamma mu dL/dt (eq. 14: gamma mu L0 eps_dot with eps_dot = Ldot/L0), along the spring.
  EXPECT_NEAR(f.norm(), gamma * mu * 0.3, 1e-15);
  EXPECT_NEAR(f.cross(d).norm(), 0.0, 1e-17);
  const Vec3 approaching = -separating;
  EXPECT_GT(spring_force(d, approaching, d.norm(), 0.0, gamma, mu).dot(separating), 0);
}

TEST(SpringForce, DissipatedPowerIsTheWorkRateOfTheDampingForce) {
  // Power of the damping force on both ends: F_i.v_i + F_j.v_j = F_i.(v_i - v_j) = -P.
  const double gamma = 3.0, mu = 0.02;
  for (const Vec3& dv : {Vec3(0.3, -0.1, 0.2), Vec3(-0.05, 0.4, 0.0), Vec3(0.0, 0.0, 0.0)}) {
    const Vec3 d(0.2, 0.05, -0.1);
    const SpringEvaluator damper(d.norm(), 0.0, gamma * mu);  // at rest length: damping only
    const double power = damper.force_and_energy(d.norm(), d.dot(dv)).dissipated_power;
    EXPECT_GE(power, 0.0);
    EXPECT_NEAR(power, -damper.force(d, dv).dot(dv), 1e-15);
  }
}

TEST(SpringForce, DampingIgnoresMotionPerpendicularToTheSpring) {
  const Vec3 d(0.2, 0.0, 0.0);
  const Vec3 sliding(0.0, 0.4, -0.1);
  EXPECT_EQ(spring_force(d, sliding, d.norm(), 0.0, 50.0, 0.01).norm(), 0.0);
}

TEST(SpringForce, FailedSpringIsTheSameLawWithReducedStiffness) {
  const Vec3 d(0.26, 0.0, 0.0);
  const double k = 0.06, factor = 0.005;
  EXPECT_DOUBLE_EQ(spring_force(d, Vec3::Zero(), 0.25, factor * k, 0, 1).x(),
                   factor * spring_force(d, Vec3::Zero(), 0.25, k, 0, 1).x());
}

TEST(SpringForce, CrossSpringFactorFollowsEq26) {
  EXPECT_EQ(cross_spring_factor(-0.01, 0.03, 0.1), 1.0);  // compression: linear
  EXPECT_EQ(cross_spring_factor(0.0, 0.03, 0.1), 1.0);
  EXPECT_DOUBLE_EQ(cross_spring_factor(0.015, 0.03, 0.1), 0.5);
  EXPECT_EQ(cross_spring_factor(0.05, 0.03, 0.1), 0.1);  // floor F_Ck
  // The factor multiplies the elastic part only: at strain 0.015 it is 0.5.
  const CrossSoftening cross{0.03, 0.1};
  const Vec3 d(0.2 * 1.015, 0, 0);
  const Vec3 dv(0.1, 0, 0);
  const Vec3 plain = spring_force(d, dv, 0.2, 1.0, 3.0, 0.01);
  const Vec3 softened = spring_force(d, dv, 0.2, 1.0, 3.0, 0.01, &cross);
  const Vec3 damping = spring_force(d, dv, 0.2, 0.0, 3.0, 0.01);
  EXPECT_NEAR(softened.x() - damping.x(), 0.5 * (plain.x() - damping.x()), 1e-15);
}

TEST(SpringForce, SoftenedEnergyIsTheIntegralOfTheEq26Force) {
  // Compression, the softened range, just past the floor's kink u_c = L0 eps_C (1 - F_Ck) and
  // far on the floor: minus the energy gradient is the force everywhere.
  const CrossSoftening cross{0.03, 0.1};
  const double rest = 0.2, k = 0.5;
  const double kink = rest * 0.03 * 0.9;
  for (double stretch : {-0.01, 0.2 * kink, 0.7 * kink, 1.1 * kink, 3.0 * kink}) {
    const Vec3 d = (rest + stretch) * Vec3(0.6, -0.48, 0.64);
    const Vec3 f = spring_force(d, Vec3::Zero(), rest, k, 0.0, 1.0, &cross);
    EXPECT_LT((f + energy_gradient(d, rest, k, &cross)).norm(), 1e-7 * f.norm()) << "stretch " << stretch;
  }
  // Continuous at the kink, and matching the closed forms on either side.
  const Vec3 n(0.0, 0.0, 1.0);
  const double at_kink = energy((rest + kink) * n, rest, k, &cross);
  EXPECT_NEAR(at_kink, k * kink * kink * (0.5 - kink / (3 * rest * 0.03)), 1e-18);
  EXPECT_NEAR(energy((rest + kink * (1 + 1e-9)) * n, rest, k, &cross), at_kink, 1e-9 * at_kink);
  const double far = 2 * kink;
  EXPECT_NEAR(energy((rest + far) * n, rest, k, &cross), at_kink + 0.5 * k * 0.1 * (far * far - kink * kink),
              1e-12 * at_kink);
  // Softening only ever lowers the energy in tension, and leaves compression alone.
  EXPECT_LT(energy((rest + far) * n, rest, k, &cross), energy((rest + far) * n, rest, k));
  EXPECT_EQ(energy((rest - 0.01) * n, rest, k, &cross), energy((rest - 0.01) * n, rest, k));
}
