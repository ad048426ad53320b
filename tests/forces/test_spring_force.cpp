#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "forces/spring_force.hpp"

using namespace tidalcrust;

namespace {

double elastic_energy(const Vec3& d, double rest_length, double k) {
  const double stretch = d.norm() - rest_length;
  return 0.5 * k * stretch * stretch;
}

}  // namespace

TEST(SpringForce, ElasticForceIsMinusTheEnergyGradient) {
  const double k = 0.076, rest = 0.2;
  for (const Vec3& d : {Vec3(0.21, 0.03, -0.02), Vec3(-0.05, 0.1, 0.12), Vec3(0.3, -0.2, 0.1)}) {
    const Vec3 f = spring_force(d, Vec3::Zero(), rest, k, 0.0, 1.0);
    const double h = 1e-6;
    for (int c = 0; c < 3; ++c) {
      Vec3 plus = d, minus = d;
      plus[c] += h;
      minus[c] -= h;
      // d = x_i - x_j, so dE/dx_i = dE/dd.
      const double gradient = (elastic_energy(plus, rest, k) - elastic_energy(minus, rest, k)) / (2 * h);
      EXPECT_NEAR(f[c], -gradient, 1e-9 * k) << "component " << c;
    }
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
  const Vec3 f = spring_force(d, Vec3::Zero(), d.norm(), 0.5, 50.0, 0.01);
  EXPECT_LT(f.norm(), 1e-16);
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
  // The factor multiplies the elastic part only.
  const Vec3 d(0.2 * 1.015, 0, 0);
  const Vec3 dv(0.1, 0, 0);
  const Vec3 plain = spring_force(d, dv, 0.2, 1.0, 3.0, 0.01);
  const Vec3 softened = spring_force(d, dv, 0.2, 1.0, 3.0, 0.01, 0.5);
  const Vec3 damping = spring_force(d, dv, 0.2, 0.0, 3.0, 0.01);
  EXPECT_NEAR(softened.x() - damping.x(), 0.5 * (plain.x() - damping.x()), 1e-15);
}
