// Principal axes of point masses: a lattice ellipsoid with known semi-axes, turned and moved.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "analysis/body_shape.hpp"
#include "base/errors.hpp"

using namespace tidalcrust;

namespace {

/// Equal masses on the points of a cubic lattice (spacing h) inside the unit ball, stretched to
/// semi-axes (a, b, c) along (x, y, z), turned by `turn` and moved by `shift`. By the lattice's
/// cubic symmetry the second moments along the three axes are a^2 s, b^2 s, c^2 s with one s, so
/// the axis ratios are exactly b/a and c/a.
void lattice_ellipsoid(double a, double b, double c, const Eigen::Matrix3d& turn, const Vec3& shift,
                       std::vector<double>& mass, std::vector<double>& position) {
  const double h = 0.1;
  for (int i = -10; i <= 10; ++i)
    for (int j = -10; j <= 10; ++j)
      for (int k = -10; k <= 10; ++k) {
        if (i * i + j * j + k * k > 100) continue;  // integers: the same points for every permutation
        const Vec3 unit(i * h, j * h, k * h);
        const Vec3 x = turn * Vec3(a * unit.x(), b * unit.y(), c * unit.z()) + shift;
        mass.push_back(1e-3);
        position.insert(position.end(), {x.x(), x.y(), x.z()});
      }
}

}  // namespace

TEST(BodyShape, LatticeEllipsoidGivesItsAxisRatiosExactly) {
  std::vector<double> mass, position;
  lattice_ellipsoid(1.3, 0.9, 0.7, Eigen::Matrix3d::Identity(), Vec3::Zero(), mass, position);
  const PrincipalAxes axes = principal_axes(mass, position);
  EXPECT_NEAR(axes.b_over_a(), 0.9 / 1.3, 1e-12);
  EXPECT_NEAR(axes.c_over_a(), 0.7 / 1.3, 1e-12);
  EXPECT_NEAR(std::abs(axes.direction[0].x()), 1.0, 1e-12);  // a along x
  EXPECT_NEAR(std::abs(axes.direction[2].z()), 1.0, 1e-12);  // c along z
}

TEST(BodyShape, TurnedAndMovedEllipsoidKeepsItsRatiosAndAxes) {
  const Eigen::Matrix3d turn =
      (Eigen::AngleAxisd(0.7, Vec3::UnitZ()) * Eigen::AngleAxisd(-0.4, Vec3(1, 1, 0).normalized())).toRotationMatrix();
  std::vector<double> mass, position;
  lattice_ellipsoid(1.2, 1.0, 0.8, turn, Vec3(0.3, -2.0, 5.0), mass, position);
  const PrincipalAxes axes = principal_axes(mass, position);
  EXPECT_NEAR(axes.b_over_a(), 1.0 / 1.2, 1e-12);
  EXPECT_NEAR(axes.c_over_a(), 0.8 / 1.2, 1e-12);
  EXPECT_NEAR(std::abs(axes.direction[0].dot(turn.col(0))), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(axes.direction[1].dot(turn.col(1))), 1.0, 1e-12);
}

TEST(BodyShape, SphereOfPointsHasRatiosOneAndBadInputIsRefused) {
  std::vector<double> mass, position;
  lattice_ellipsoid(1.0, 1.0, 1.0, Eigen::Matrix3d::Identity(), Vec3::Zero(), mass, position);
  const PrincipalAxes axes = principal_axes(mass, position);
  EXPECT_NEAR(axes.b_over_a(), 1.0, 1e-12);
  EXPECT_NEAR(axes.c_over_a(), 1.0, 1e-12);
  // A lattice sphere's semi-axis is sqrt(5 <x^2>): near 1 (the ball's radius) for a fine lattice.
  EXPECT_NEAR(axes.semi_axis[0], 1.0, 0.05);
  EXPECT_THROW(principal_axes({1.0}, {0.0, 0.0}), InputError);
  EXPECT_THROW(principal_axes({0.0}, {0.0, 0.0, 0.0}), InputError);
}
