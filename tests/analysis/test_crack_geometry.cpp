// Crack geometry (analysis/crack_geometry.hpp): the small-circle fit recovers synthetic arcs, the
// crack azimuths, rose and concentricity of synthetic crack sets, and the geometry that
// analyze_fractures gives a ring of failed springs about the subsatellite point.
#include <Eigen/Geometry>  // cross()
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "analysis/crack_geometry.hpp"
#include "analysis/fracture_analysis.hpp"
#include "base/random.hpp"
#include "physics/orbital_frame.hpp"
#include "support/synthetic_encounter.hpp"

using namespace tidalcrust;
using tidalcrust::test_support::synthetic_encounter;

namespace {

constexpr double degrees = 180.0 / std::numbers::pi;

double angle_deg(const Vec3& a, const Vec3& b) {
  return std::atan2(a.normalized().cross(b.normalized()).norm(), a.normalized().dot(b.normalized())) * degrees;
}

/// An orthonormal pair perpendicular to the unit vector p.
std::pair<Vec3, Vec3> perpendicular_pair(const Vec3& p) {
  const Vec3 e1 = p.cross(std::abs(p.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).normalized();
  return {e1, p.cross(e1)};
}

/// `count` points on the circle of angular radius `radius_deg` about `pole`, at azimuths evenly
/// spread over [start, start + span] deg; with `noise_deg` > 0 each is moved by up to that many
/// degrees in each of two tangent directions (uniform, deterministic seed).
std::vector<Vec3> circle_points(const Vec3& pole, double radius_deg, double start, double span, int count,
                                double noise_deg = 0, std::uint64_t seed = 11) {
  const auto [e1, e2] = perpendicular_pair(pole);
  Random random(seed);
  std::vector<Vec3> points;
  const double r = radius_deg / degrees;
  for (int i = 0; i < count; ++i) {
    const double a = (start + span * i / (count - 1)) / degrees;
    Vec3 x = std::cos(r) * pole + std::sin(r) * (std::cos(a) * e1 + std::sin(a) * e2);
    if (noise_deg > 0) {
      const auto [t1, t2] = perpendicular_pair(x);
      x = (x + random.uniform(-1, 1) * noise_deg / degrees * t1 + random.uniform(-1, 1) * noise_deg / degrees * t2)
              .normalized();
    }
    points.push_back(2.5 * x);  // any length: used by direction
  }
  return points;
}

const Vec3 tilted_pole = Vec3(0.3, 0.8, -0.52).normalized();

}  // namespace

TEST(SmallCircleFit, RecoversAFortyDegreeArcSpanning270Degrees) {
  const SmallCircleFit fit = fit_small_circle(circle_points(tilted_pole, 40, 15, 270, 61));
  ASSERT_TRUE(fit.finite());
  EXPECT_LT(angle_deg(fit.pole, tilted_pole), 1e-8);
  EXPECT_NEAR(fit.radius_deg, 40, 1e-8);
  EXPECT_NEAR(fit.arc_deg, 270, 1e-8);
  EXPECT_NEAR(fit.arc_length, 270 / degrees * std::sin(40 / degrees), 1e-10);
  EXPECT_LT(fit.rms_misfit_deg, 1e-8);
  EXPECT_EQ(fit.points, 61u);
  EXPECT_NEAR(fit.pole.norm(), 1, 1e-15);
  EXPECT_NEAR(fit.pole_longitude_deg, longitude_deg(tilted_pole), 1e-8);
  EXPECT_NEAR(fit.pole_latitude_deg, latitude_deg(tilted_pole), 1e-8);
  EXPECT_NEAR(fit.pole_from_subsatellite_deg, angle_deg(tilted_pole, subsatellite_direction), 1e-8);
  EXPECT_NEAR(fit.pole_axis_from_subsatellite_deg, fit.pole_from_subsatellite_deg, 1e-12);  // < 90 here
}

TEST(SmallCircleFit, RecoversANoisyArcWithinHalfADegree) {
  for (const std::uint64_t seed : {1, 2, 3, 4, 5}) {
    const SmallCircleFit fit = fit_small_circle(circle_points(tilted_pole, 40, -60, 270, 80, 1.0, seed));
    ASSERT_TRUE(fit.finite()) << seed;
    EXPECT_LT(angle_deg(fit.pole, tilted_pole), 0.5) << seed;
    EXPECT_NEAR(fit.radius_deg, 40, 0.5) << seed;
    EXPECT_NEAR(fit.arc_deg, 270, 5) << seed;  // each end moves by up to 1 deg / sin 40 deg
    // Uniform noise of +-1 deg in two directions: the radial part alone has rms 1/sqrt(3) deg.
    EXPECT_GT(fit.rms_misfit_deg, 0.4) << seed;
    EXPECT_LT(fit.rms_misfit_deg, 0.75) << seed;
  }
}

TEST(SmallCircleFit, AGreatCircleHasRadiusNinety) {
  // A whole great circle (72 points every 5 deg), exact and noisy.
  for (const double noise : {0.0, 0.5}) {
    const SmallCircleFit fit = fit_small_circle(circle_points(tilted_pole, 90, 0, 355, 72, noise));
    ASSERT_TRUE(fit.finite());
    EXPECT_NEAR(fit.radius_deg, 90, noise > 0 ? 0.5 : 1e-8);
    EXPECT_LT(std::min(angle_deg(fit.pole, tilted_pole), angle_deg(-fit.pole, tilted_pole)), noise > 0 ? 0.5 : 1e-8);
    EXPECT_NEAR(fit.arc_deg, 355, noise > 0 ? 2 : 1e-8);
    EXPECT_NEAR(fit.arc_length, 355 / degrees, noise > 0 ? 0.05 : 1e-8);
  }
}

TEST(SmallCircleFit, ACircleWiderThanAHemisphereIsReportedAboutItsAntipode) {
  // Radius 130 deg about the tilted pole is radius 50 deg about its antipode.
  const SmallCircleFit fit = fit_small_circle(circle_points(tilted_pole, 130, 0, 200, 41));
  EXPECT_LT(angle_deg(fit.pole, -tilted_pole), 1e-8);
  EXPECT_NEAR(fit.radius_deg, 50, 1e-8);
  EXPECT_NEAR(fit.arc_deg, 200, 1e-8);
  EXPECT_NEAR(fit.pole_axis_from_subsatellite_deg, std::min(fit.pole_from_subsatellite_deg,
                                                            180 - fit.pole_from_subsatellite_deg), 1e-12);
}

TEST(SmallCircleFit, TheArcRunsFromArcStartCounterClockwiseAboutThePole) {
  const std::vector<Vec3> points = circle_points(tilted_pole, 40, 100, 120, 25);
  const SmallCircleFit fit = fit_small_circle(points);
  // Counter-clockwise about the pole: from the first point generated (the azimuth basis of
  // circle_points is right-handed about the pole) to the last.
  EXPECT_LT(angle_deg(point_on_circle(fit, 0), points.front()), 1e-8);
  EXPECT_LT(angle_deg(point_on_circle(fit, fit.arc_deg), points.back()), 1e-8);
  EXPECT_LT(angle_deg(point_on_circle(fit, 0.5 * fit.arc_deg), points[12]), 1e-8);
  EXPECT_NEAR(angle_deg(point_on_circle(fit, 200), fit.pole), 40, 1e-8);  // every point lies on the circle
}

TEST(SmallCircleFit, TheSameInputGivesTheSameBitsAndTheOrderOnlyRoundOff) {
  std::vector<Vec3> points = circle_points(tilted_pole, 40, 0, 270, 50, 1.0);
  const SmallCircleFit a = fit_small_circle(points), b = fit_small_circle(points);
  EXPECT_EQ(a.pole, b.pole);
  EXPECT_EQ(a.radius_deg, b.radius_deg);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_LE(a.iterations, max_fit_iterations);
  std::reverse(points.begin(), points.end());
  const SmallCircleFit c = fit_small_circle(points);
  EXPECT_LT(angle_deg(a.pole, c.pole), 1e-9);
  EXPECT_NEAR(a.radius_deg, c.radius_deg, 1e-9);
}

namespace {
/// Crack elements on rings about the subsatellite point (angles 15..165 deg from it, 24 per ring),
/// each with a spring along `spring_direction(position, toward, around)` (all tangent unit vectors:
/// toward the subsatellite point and around it, counter-clockwise seen from outside).
template <class Direction>
std::vector<double> ring_azimuths(Direction spring_direction) {
  std::vector<double> azimuths;
  for (int ring = 1; ring <= 11; ++ring)
    for (int k = 0; k < 24; ++k) {
      const double theta = (15.0 * ring) / degrees, phi = (15.0 * k + 3) / degrees;
      const Vec3 u(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      const Vec3 toward = (subsatellite_direction - subsatellite_direction.dot(u) * u).normalized();
      const Vec3 around = u.cross(toward);
      azimuths.push_back(crack_azimuth_deg(0.97 * u, spring_direction(u, toward, around)));
    }
  return azimuths;
}
}  // namespace

TEST(CrackOrientations, ConcentricRingsHaveConcentricityOneAndPeakAtNinety) {
  // A spring pointing at the subsatellite point fails as a crack around it (plus a radial part
  // of the spring, which is dropped).
  const std::vector<double> azimuths =
      ring_azimuths([](const Vec3& u, const Vec3& toward, const Vec3&) { return Vec3(0.02 * toward + 0.01 * u); });
  for (const double a : azimuths) EXPECT_NEAR(a, 90, 1e-12);
  const CrackOrientations o = crack_orientations(azimuths);
  EXPECT_EQ(o.elements, azimuths.size());
  EXPECT_NEAR(o.concentricity, 1, 1e-12);
  EXPECT_EQ(o.rose_peak_deg, 90);
  EXPECT_EQ(o.rose[9], static_cast<std::int64_t>(azimuths.size()));  // bin centred on 90
}

TEST(CrackOrientations, RadialCracksHaveConcentricityZeroAndPeakAtZero) {
  const std::vector<double> azimuths =
      ring_azimuths([](const Vec3&, const Vec3&, const Vec3& around) { return Vec3(-0.03 * around); });
  for (const double a : azimuths) EXPECT_LT(std::min(a, 180 - a), 1e-12) << a;
  const CrackOrientations o = crack_orientations(azimuths);
  EXPECT_NEAR(o.concentricity, 0, 1e-12);
  EXPECT_EQ(o.rose_peak_deg, 0);
  EXPECT_EQ(o.rose[0], static_cast<std::int64_t>(azimuths.size()));  // [175, 180) and [0, 5)
}

TEST(CrackOrientations, ObliqueCracksAreMeasuredCounterClockwiseFromOutside) {
  // A spring 30 deg counter-clockwise from the direction toward the subsatellite point: its crack
  // (perpendicular, counter-clockwise) lies at 120 deg.
  const std::vector<double> azimuths = ring_azimuths([](const Vec3&, const Vec3& toward, const Vec3& around) {
    return Vec3(std::cos(30 / degrees) * toward + std::sin(30 / degrees) * around);
  });
  for (const double a : azimuths) EXPECT_NEAR(a, 120, 1e-10);
  const CrackOrientations o = crack_orientations(azimuths);
  EXPECT_NEAR(o.concentricity, std::sin(120 / degrees), 1e-12);
  EXPECT_EQ(o.rose_peak_deg, 120);
}

TEST(CrackOrientations, UniformAzimuthsGiveTwoOverPi) {
  std::vector<double> azimuths;
  for (int i = 0; i < 18000; ++i) azimuths.push_back((i + 0.5) * 0.01);
  const CrackOrientations o = crack_orientations(azimuths);
  EXPECT_NEAR(o.concentricity, random_concentricity, 1e-8);
  EXPECT_NEAR(random_concentricity, 2 / std::numbers::pi, 1e-16);
  for (const auto n : o.rose) EXPECT_EQ(n, 1000);
}

TEST(CrackOrientations, TheRosesSectorsOf45DegreesHoldTheirShares) {
  // Uniform azimuths: a quarter in each sector. Sector edges at 22.5 + 45 k deg; [157.5, 180) is radial.
  std::vector<double> uniform;
  for (int i = 0; i < 18000; ++i) uniform.push_back((i + 0.5) * 0.01);
  for (const double share : crack_orientations(uniform).sector_share) EXPECT_DOUBLE_EQ(share, 0.25);
  const CrackOrientations o = crack_orientations({0, 22.4, 22.6, 67.6, 90, 112.4, 112.6, 157.4, 157.6, 179.9, std::nan("")});
  EXPECT_EQ(o.elements, 10u);
  EXPECT_EQ(o.sector_share, (std::array<double, 4>{0.4, 0.1, 0.3, 0.2}));  // radial 0, 22.4, 157.6, 179.9
  const CrackOrientations none = crack_orientations({});
  for (const double share : none.sector_share) EXPECT_TRUE(std::isnan(share));
}

TEST(CrackOrientations, UndefinedAzimuthsAreSkipped) {
  EXPECT_TRUE(std::isnan(crack_azimuth_deg(subsatellite_direction, Vec3(1, 0, 0))));    // at the subsatellite point
  EXPECT_TRUE(std::isnan(crack_azimuth_deg(-2 * subsatellite_direction, Vec3(0, 0, 1))));  // at its antipode
  EXPECT_TRUE(std::isnan(crack_azimuth_deg(Vec3(1, 0, 0), Vec3(2, 0, 0))));              // a radial spring
  const CrackOrientations none = crack_orientations({std::nan(""), std::nan("")});
  EXPECT_EQ(none.elements, 0u);
  EXPECT_TRUE(std::isnan(none.concentricity));
  EXPECT_TRUE(std::isnan(none.rose_peak_deg));
}

// On a level-4 icosphere, every shell spring that crosses the circle 60 deg from the subsatellite
// point fails: one ring-shaped crack, concentric about the subsatellite point.
TEST(CrackGeometry, ARingOfFailedSpringsAboutTheSubsatellitePointIsFittedAsOne) {
  Checkpoint c = synthetic_encounter(4);
  const double cos60 = 0.5;
  for (std::size_t s = 0; s < c.body.spring_count(); ++s) {
    if (c.body.spring_kind[s] != static_cast<std::uint8_t>(SpringKind::shell)) continue;
    const double a = vec3_at(c.state.position, c.body.springs[s][0]).normalized().y() - cos60;
    const double b = vec3_at(c.state.position, c.body.springs[s][1]).normalized().y() - cos60;
    if (a * b < 0) c.state.springs.failed[s] = 1;
  }
  const FractureSummary f = analyze_fractures(c.body, c.state);
  ASSERT_GT(f.count(), 50u);
  ASSERT_EQ(f.clusters.size(), 1u);
  const CrackGeometry& g = f.geometry;
  ASSERT_EQ(g.arcs.size(), 1u);
  const SmallCircleFit& fit = g.arcs[0].fit;
  EXPECT_EQ(fit.points, f.count());
  EXPECT_LT(fit.pole_from_subsatellite_deg, 0.5);
  EXPECT_NEAR(fit.radius_deg, 60, 0.5);
  EXPECT_GT(fit.arc_deg, 350);
  EXPECT_LT(fit.rms_misfit_deg, 1.5);  // the midpoints zigzag about the circle by a lattice spacing
  EXPECT_EQ(g.pole_axis_histogram[0], 1);
  EXPECT_NEAR(g.median_pole_axis_from_subsatellite_deg, fit.pole_axis_from_subsatellite_deg, 0);
  // Springs crossing a ring about the subsatellite point point across it, within 60 deg (the
  // triangular lattice): their cracks run along it, well above the random 0.64.
  EXPECT_GT(g.orientations.concentricity, 0.75);
  EXPECT_EQ(g.orientations.rose_peak_deg, 90);
  EXPECT_EQ(g.orientations.elements, f.count());
  for (const auto& spring : f.failed) EXPECT_GE(spring.crack_azimuth_deg, 0);
}

TEST(CrackGeometry, ShortClustersGetNoCircle) {
  Checkpoint c = synthetic_encounter(2);
  c.state.springs.failed[0] = c.state.springs.failed[5] = 1;
  const FractureSummary f = analyze_fractures(c.body, c.state);
  EXPECT_TRUE(f.geometry.arcs.empty());
  EXPECT_TRUE(std::isnan(f.geometry.median_arc_radius_deg));
  EXPECT_EQ(f.geometry.orientations.elements, 2u);
  const Json json = crack_geometry_json(f.geometry);
  EXPECT_TRUE(json["arcs"].empty());
  EXPECT_EQ(json["arc_selection"]["min_extent"], CrackGeometry::min_arc_extent);
  EXPECT_EQ(json["concentricity_random"], random_concentricity);
  EXPECT_EQ(json["rose"]["histogram"].size(), CrackOrientations::bins);
}

// The lattice itself: with every shell spring failed, the crack directions are those of the
// icosphere's edges, which over the sphere take every orientation to the subsatellite direction
// alike: the concentricity is the random 2/pi, to within the lattice's own anisotropy.
TEST(CrackGeometry, EveryEdgeOfTheLatticeIsNearlyRandom) {
  for (const int level : {3, 4}) {
    Checkpoint c = synthetic_encounter(level);
    for (std::size_t s = 0; s < c.body.spring_count(); ++s)
      if (c.body.spring_kind[s] == static_cast<std::uint8_t>(SpringKind::shell)) c.state.springs.failed[s] = 1;
    const FractureSummary f = analyze_fractures(c.body, c.state);
    std::printf("[ info ] level %d: every edge failed, concentricity %.4f (2/pi = %.4f)\n", level,
                f.geometry.orientations.concentricity, random_concentricity);
    EXPECT_NEAR(f.geometry.orientations.concentricity, random_concentricity, 0.005) << level;
  }
}
