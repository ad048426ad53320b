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

HingeForces forces(const Corners& x, double rest, double k) {
  return HingeEvaluator(rest, k).force_and_energy(x[0], x[1], x[2], x[3]);
}

double energy(const Corners& x, double rest, double k) { return forces(x, rest, k).energy; }

/// C = L^2 / (|N1| + |N2|), the geometric prefactor of eq. 22.
double prefactor(const Corners& x) {
  const double n1 = (x[0] - x[2]).cross(x[0] - x[3]).norm(), n2 = (x[1] - x[3]).cross(x[1] - x[2]).norm();
  return (x[3] - x[2]).squaredNorm() / (n1 + n2);
}

/// Central finite-difference gradient of f(corners) with respect to vertex v.
template <typename F>
Vec3 gradient(F&& f, const Corners& x, int v) {
  const double h = 1e-6;
  Vec3 g;
  for (int c = 0; c < 3; ++c) {
    Corners plus = x, minus = x;
    plus[v][c] += h;
    minus[v][c] -= h;
    g[c] = (f(plus) - f(minus)) / (2 * h);
  }
  return g;
}

Vec3 angle_gradient(const Corners& x, int v) { return gradient(angle, x, v); }

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

TEST(HingeForce, EnergyIsZeroAtRestAndQuadraticNearIt) {
  const Corners x = hinge(0.2, -0.1);
  const double k = 0.01, theta = angle(x);
  EXPECT_LT(energy(x, theta, k), 1e-30);  // sin((theta - theta_rest)/2) ~ 1e-17 from rounding
  for (double offset : {1e-3, -1e-4, 1e-6}) {
    // E = 4 k C sin^2(offset/4) = k C offset^2/4 (1 - offset^2/48 + ...).
    const double expected = k * prefactor(x) * offset * offset / 4;
    EXPECT_NEAR(energy(x, theta - offset, k), expected, 1e-6 * expected) << offset;
  }
}

TEST(HingeForce, EnergyGradientIsMinusTheForcePlusTheFrozenPrefactorTerm) {
  // The force has no exact potential (hinge_force.hpp): E = 2 k C (1 - cos(delta/2)) has the
  // gradient -F_i + 2 k (1 - cos(delta/2)) dC/dx_i, delta = theta - theta_rest. Checked exactly
  // (to finite-difference accuracy), and the mismatch |grad E + F| / |F| measured: it shrinks in
  // proportion to delta, 0.35 delta to 0.5 delta on these hinges (so 5e-5 relative at
  // delta = 1e-4, 0.2 at delta = 0.4).
  const double k = 0.0075;
  for (const Corners& x : {hinge(0.1, 0.05), hinge(-0.3, 0.2), hinge(0.6, 0.7), hinge(1.5, -0.2)}) {
    for (double offset : {0.4, -0.1, 0.02}) {
      const double rest = angle(x) - offset;
      const HingeForces f = forces(x, rest, k);
      double force_norm = 0, mismatch = 0, residual = 0;
      for (int v = 0; v < 4; ++v) {
        const Vec3 g = gradient([&](const Corners& y) { return energy(y, rest, k); }, x, v);
        const Vec3 frozen_term =
            2 * k * (1 - std::cos(0.5 * offset)) * gradient([](const Corners& y) { return prefactor(y); }, x, v);
        force_norm += f.on[v].squaredNorm();
        mismatch += (g + f.on[v]).squaredNorm();
        residual += (g + f.on[v] - frozen_term).squaredNorm();
      }
      force_norm = std::sqrt(force_norm);
      EXPECT_LT(std::sqrt(residual), 1e-7 * force_norm) << "offset " << offset;
      EXPECT_LT(std::sqrt(mismatch), 0.6 * std::abs(offset) * force_norm) << "offset " << offset;
      EXPECT_GT(std::sqrt(mismatch), 0.2 * std::abs(offset) * force_norm) << "offset " << offset;
    }
  }
}

TEST(HingeForce, EnergyHasNoCancellationForTinyAngles) {
  // 1 - cos(delta/2) is evaluated as sin^2/(1 + cos): exact to rounding even at delta = 1e-9.
  const Corners x = hinge(0.3, 0.1);
  const double k = 1.0, delta = 1e-9;
  const double expected = k * prefactor(x) * delta * delta / 4;
  EXPECT_NEAR(energy(x, angle(x) - delta, k), expected, 1e-6 * expected);
}

TEST(HingeForce, EnergyOfAStronglyFoldedHingeTakesTheOtherBranch) {
  // cos((theta - theta_rest)/2) < 0 when the hinge is folded by more than pi from rest.
  const Corners x = hinge(3.0, 2.5);
  const double k = 1.0, theta = angle(x), rest = theta > 0 ? theta - 2.5 : theta + 2.5;
  EXPECT_NEAR(energy(x, rest, k), 2 * k * prefactor(x) * (1 - std::cos(0.5 * (theta - rest))), 1e-14);
}
