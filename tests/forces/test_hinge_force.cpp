#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "forces/hinge_force.hpp"
#include "forces/hinge_geometry.hpp"

using namespace tidalcrust;

namespace {

using Corners = std::array<Vec3, 4>;

double angle(const Corners& x) { return hinge_angle(x[0], x[1], x[2], x[3]); }

/// A bent hinge: edge along x, wings on either side in y, lifted by z1, z2.
Corners hinge(double z1, double z2) {
  return {Vec3(0.45, 0.8, z1), Vec3(0.55, -0.85, z2), Vec3(0, 0, 0), Vec3(1.0, 0.02, 0.01)};
}

/// Finite-difference gradient of the hinge angle with respect to vertex v.
Vec3 angle_gradient(Corners x, int v) {
  const double h = 1e-6;
  Vec3 g;
  for (int c = 0; c < 3; ++c) {
    Corners plus = x, minus = x;
    plus[v][c] += h;
    minus[v][c] -= h;
    g[c] = (angle(plus) - angle(minus)) / (2 * h);
  }
  return g;
}

HingeForces forces(const Corners& x, double rest, double k) { return hinge_forces(x[0], x[1], x[2], x[3], rest, k); }

}  // namespace

TEST(HingeForce, ZeroAtTheRestAngle) {
  for (const Corners& x : {hinge(0.1, 0.05), hinge(-0.3, 0.2), hinge(0.0, 0.0)}) {
    const HingeForces f = forces(x, angle(x), 0.0075);
    for (const Vec3& fv : f.on) EXPECT_LT(fv.norm(), 1e-17);
  }
}

TEST(HingeForce, IsBridsonsMagnitudeAlongMinusTheAngleGradient) {
  // F_i = -k L^2/(|N1|+|N2|) sin((theta - theta_rest)/2) d theta/d x_i: restoring.
  const double k = 0.0075;
  for (const Corners& x : {hinge(0.1, 0.05), hinge(-0.3, 0.2), hinge(0.6, 0.7)}) {
    for (double offset : {0.05, -0.2, 1.0}) {
      const double theta = angle(x), rest = theta - offset;
      const HingeForces f = forces(x, rest, k);
      const Vec3 e = x[3] - x[2];
      const double n1 = (x[0] - x[2]).cross(x[0] - x[3]).norm(), n2 = (x[1] - x[3]).cross(x[1] - x[2]).norm();
      const double magnitude = k * e.squaredNorm() / (n1 + n2) * std::sin(0.5 * (theta - rest));
      for (int v = 0; v < 4; ++v) {
        const Vec3 expected = -magnitude * angle_gradient(x, v);
        EXPECT_LT((f.on[v] - expected).norm(), 1e-7 * std::abs(magnitude) + 1e-15) << "vertex " << v;
      }
      // Moving every vertex a little along its force brings theta closer to the rest angle.
      Corners moved = x;
      for (int v = 0; v < 4; ++v) moved[v] += 1e-3 / k * f.on[v];
      EXPECT_LT(std::abs(angle(moved) - rest), std::abs(theta - rest));
    }
  }
}

TEST(HingeForce, SumsToZeroAndExertsNoTorque) {
  const Corners x = hinge(0.3, -0.1);
  const HingeForces f = forces(x, 0.4, 0.01);
  Vec3 total = Vec3::Zero(), torque = Vec3::Zero();
  double scale = 0;
  for (int v = 0; v < 4; ++v) {
    total += f.on[v];
    // Torque about a point away from the hinge, so that no term vanishes by construction.
    const Vec3 r = x[v] - Vec3(0.3, -2.0, 1.5);
    torque += r.cross(f.on[v]);
    scale += r.norm() * f.on[v].norm();
  }
  EXPECT_GT(scale, 1e-4);
  EXPECT_LT(total.norm(), 1e-15 * scale);
  EXPECT_LT(torque.norm(), 1e-15 * scale);
}

TEST(HingeForce, HalfAngleFormulasMatchAtan2BeyondRightAngles) {
  // Strongly folded hinges take the cos(theta) < 0 branch of the half-angle formulas.
  const double k = 1.0;
  for (const Corners& x : {hinge(3.0, 2.5), hinge(-2.0, -3.0), hinge(1.5, -0.2)}) {
    const double theta = angle(x);
    const HingeForces f = forces(x, 0.0, k);
    const Vec3 e = x[3] - x[2];
    const double n1 = (x[0] - x[2]).cross(x[0] - x[3]).norm(), n2 = (x[1] - x[3]).cross(x[1] - x[2]).norm();
    const double magnitude = k * e.squaredNorm() / (n1 + n2) * std::sin(0.5 * theta);
    const Vec3 expected = magnitude * e.norm() * (x[0] - x[2]).cross(x[0] - x[3]) / (n1 * n1);
    EXPECT_LT((f.on[0] - expected).norm(), 1e-13 * expected.norm()) << "theta " << theta;
  }
}

TEST(HingeForce, FlagsACollapsedFace) {
  EXPECT_FALSE(forces(hinge(0.1, 0.1), 0.0, 1.0).collapsed);
  Corners flat = hinge(0.0, 0.0);
  flat[0] = 0.4 * flat[3] + Vec3(0.0, 1e-5, 0.0);  // wing 1 almost on the edge line
  EXPECT_TRUE(forces(flat, 0.0, 1.0).collapsed);
}
