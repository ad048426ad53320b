#include <Eigen/Geometry>  // cross()
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>

#include "analysis/fracture_analysis.hpp"
#include "io/json.hpp"
#include "physics/orbital_frame.hpp"
#include "support/synthetic_encounter.hpp"

using namespace tidalcrust;
using tidalcrust::test_support::spring_between;
using tidalcrust::test_support::synthetic_encounter;

namespace {

Vec3 face_centroid(const Checkpoint& c, std::size_t f) {
  Vec3 sum = Vec3::Zero();
  for (auto i : c.body.faces[f]) sum += vec3_at(c.state.position, static_cast<std::size_t>(i));
  return sum / 3.0;
}

/// The edge (vertex pair) shared by two faces, or {-1, -1}.
std::array<std::int32_t, 2> shared_edge(const Body& body, std::size_t f, std::size_t g) {
  std::vector<std::int32_t> common;
  for (auto a : body.faces[f])
    for (auto b : body.faces[g])
      if (a == b) common.push_back(a);
  if (common.size() != 2) return {-1, -1};
  return {common[0], common[1]};
}

/// A strip of `length` faces walking from the face nearest +y toward -x (each consecutive pair
/// shares an edge), found by brute force without shell_topology.
std::vector<std::size_t> strip_toward_minus_x(const Checkpoint& c, int length) {
  std::size_t current = 0;
  for (std::size_t f = 1; f < c.body.faces.size(); ++f)
    if (face_centroid(c, f).y() > face_centroid(c, current).y()) current = f;
  std::vector<std::size_t> strip{current};
  while (static_cast<int>(strip.size()) < length) {
    std::size_t best = c.body.faces.size();
    for (std::size_t g = 0; g < c.body.faces.size(); ++g) {
      if (std::find(strip.begin(), strip.end(), g) != strip.end()) continue;
      if (shared_edge(c.body, current, g)[0] < 0) continue;
      if (best == c.body.faces.size() || face_centroid(c, g).x() < face_centroid(c, best).x()) best = g;
    }
    strip.push_back(current = best);
  }
  return strip;
}

}  // namespace

TEST(FractureAnalysis, NoFailures) {
  const FractureSummary s = analyze_fractures(synthetic_encounter(1).body, synthetic_encounter(1).state);
  EXPECT_EQ(s.count(), 0u);
  EXPECT_EQ(s.fraction_shell, 0.0);
  EXPECT_TRUE(std::isnan(s.hemisphere_fraction));
  EXPECT_TRUE(s.clusters.empty());
  EXPECT_EQ(s.longest_crack_length, 0.0);
}

TEST(FractureAnalysis, LineOfFailedSpringsIsOneCrack) {
  Checkpoint c = synthetic_encounter(2);
  // Move the whole body: analysis is relative to the centre of mass.
  for (std::size_t i = 0; i < c.body.particle_count(); ++i) set_vec3(c.state.position, i, vec3_at(c.state.position, i) + Vec3(5, -3, 2));
  const auto strip = strip_toward_minus_x(c, 7);
  double expected_length = 0;
  std::set<std::int32_t> failed;
  for (std::size_t i = 1; i < strip.size(); ++i) {
    const auto edge = shared_edge(c.body, strip[i - 1], strip[i]);
    const std::int32_t s = spring_between(c.body, edge[0], edge[1]);
    ASSERT_GE(s, 0);
    c.state.springs.failed[static_cast<std::size_t>(s)] = 1;
    failed.insert(s);
    const Vec3 m = 0.5 * (vec3_at(c.state.position, edge[0]) + vec3_at(c.state.position, edge[1]));
    expected_length += (face_centroid(c, strip[i - 1]) - m).norm() + (m - face_centroid(c, strip[i])).norm();
  }
  // A lone failed spring on the far side (-y) makes a second, shorter crack.
  std::int32_t far = -1;
  double lowest_y = 0;
  for (std::size_t s = 0; s < c.body.spring_count(); ++s) {
    if (c.body.spring_kind[s] != static_cast<std::uint8_t>(SpringKind::shell)) continue;
    const double y = vec3_at(c.state.position, c.body.springs[s][0]).y() + vec3_at(c.state.position, c.body.springs[s][1]).y();
    if (far < 0 || y < lowest_y) far = static_cast<std::int32_t>(s), lowest_y = y;
  }
  c.state.springs.failed[static_cast<std::size_t>(far)] = 1;
  // Failed flags on non-shell springs are ignored.
  c.state.springs.failed.back() = 1;

  const FractureSummary s = analyze_fractures(c.body, c.state);
  ASSERT_EQ(s.count(), 7u);
  EXPECT_EQ(s.shell_springs, 480u);
  EXPECT_DOUBLE_EQ(s.fraction_shell, 7.0 / 480.0);
  EXPECT_DOUBLE_EQ(s.hemisphere_fraction, 6.0 / 7.0);
  ASSERT_EQ(s.clusters.size(), 2u);
  EXPECT_EQ(std::set<std::int32_t>(s.clusters[0].springs.begin(), s.clusters[0].springs.end()), failed);
  EXPECT_EQ(s.clusters[1].springs, std::vector<std::int32_t>{far});
  EXPECT_NEAR(s.longest_crack_length, expected_length, 1e-12);
  EXPECT_NEAR(s.clusters[0].length, expected_length, 1e-12);
  // The total is every cluster's length: the strip's and the lone far spring's two bars.
  EXPECT_NEAR(s.total_crack_length, s.clusters[0].length + s.clusters[1].length, 1e-15);
  EXPECT_GT(s.clusters[1].length, 0.0);
  // End to end: from the first to the last face of the strip, on the unit sphere.
  const Vec3 offset(5, -3, 2);
  const double ends = std::acos((face_centroid(c, strip.front()) - offset).normalized().dot(
      (face_centroid(c, strip.back()) - offset).normalized()));
  EXPECT_NEAR(s.longest_crack_extent, ends, 1e-6);
  EXPECT_EQ(s.bars.size(), 2u * 7u);  // two half-bars per failed edge on a closed shell
  // The strip starts at +y and walks along the equator toward -x: longitudes from ~90 upward.
  double mean_angle = 0;
  std::vector<double> angles;
  std::int64_t histogram_total = 0;
  for (const auto& f : s.failed) {
    const Vec3 m = 0.5 * (vec3_at(c.state.position, c.body.springs[f.spring][0]) +
                          vec3_at(c.state.position, c.body.springs[f.spring][1])) - offset;
    EXPECT_NEAR(f.longitude_deg, std::atan2(m.y(), m.x()) * 180 / std::numbers::pi, 1e-9);
    mean_angle += std::acos(m.normalized().y()) * 180 / std::numbers::pi / 7;
    angles.push_back(std::acos(m.normalized().y()) * 180 / std::numbers::pi);
  }
  std::sort(angles.begin(), angles.end());
  EXPECT_NEAR(s.median_angle_from_subsatellite_deg, angles[3], 1e-9);  // 7 failures: the 4th
  for (auto n : s.angle_histogram) histogram_total += n;
  EXPECT_EQ(histogram_total, 7);
  EXPECT_NEAR(s.mean_angle_from_subsatellite_deg, mean_angle, 1e-9);
  EXPECT_GT(s.angle_histogram.back() + s.angle_histogram[s.angle_bins - 2], 0);  // the far spring
}

TEST(FractureAnalysis, EdgesShareAClusterOnlyThroughACommonFace) {
  Checkpoint c = synthetic_encounter(1);
  const auto& face = c.body.faces[0];
  const std::int32_t ab = spring_between(c.body, face[0], face[1]);
  const std::int32_t bc = spring_between(c.body, face[1], face[2]);
  c.state.springs.failed[static_cast<std::size_t>(ab)] = 1;
  c.state.springs.failed[static_cast<std::size_t>(bc)] = 1;
  EXPECT_EQ(analyze_fractures(c.body, c.state).clusters.size(), 1u);

  // An edge at vertex a that shares no face with edge ab: touches ab only at a node.
  c.state.springs.failed[static_cast<std::size_t>(bc)] = 0;
  std::int32_t other = -1;
  for (std::size_t s = 0; s < c.body.spring_count() && other < 0; ++s) {
    if (c.body.spring_kind[s] != static_cast<std::uint8_t>(SpringKind::shell)) continue;
    const auto e = c.body.springs[s];
    if (static_cast<std::int32_t>(s) == ab || (e[0] != face[0] && e[1] != face[0])) continue;
    const std::int32_t x = e[0] == face[0] ? e[1] : e[0];
    bool common_face = false;
    for (const auto& g : c.body.faces) {
      const auto has = [&](std::int32_t v) { return std::find(g.begin(), g.end(), v) != g.end(); };
      common_face |= has(face[0]) && has(face[1]) && has(x);
    }
    if (!common_face) other = static_cast<std::int32_t>(s);
  }
  ASSERT_GE(other, 0);
  c.state.springs.failed[static_cast<std::size_t>(other)] = 1;
  const FractureSummary s = analyze_fractures(c.body, c.state);
  EXPECT_EQ(s.clusters.size(), 2u);
}

TEST(FractureAnalysis, AllSpringsFailedShowTheDualLattice) {
  Checkpoint c = synthetic_encounter(2);
  double expected = 0, y_positive = 0;
  for (std::size_t s = 0; s < c.body.spring_count(); ++s) {
    if (c.body.spring_kind[s] != static_cast<std::uint8_t>(SpringKind::shell)) continue;
    c.state.springs.failed[s] = 1;
    const Vec3 m = 0.5 * (vec3_at(c.state.position, c.body.springs[s][0]) + vec3_at(c.state.position, c.body.springs[s][1]));
    y_positive += m.y() - body_center_of_mass(c.body, c.state).y() > 0;
  }
  for (std::size_t f = 0; f < c.body.faces.size(); ++f)
    for (int k = 0; k < 3; ++k)  // a three-pronged fork on every face
      expected += (face_centroid(c, f) - 0.5 * (vec3_at(c.state.position, c.body.faces[f][k]) +
                                                  vec3_at(c.state.position, c.body.faces[f][(k + 1) % 3]))).norm();
  const FractureSummary s = analyze_fractures(c.body, c.state);
  EXPECT_EQ(s.count(), 480u);
  EXPECT_EQ(s.fraction_shell, 1.0);
  EXPECT_EQ(s.clusters.size(), 1u);
  EXPECT_EQ(s.bars.size(), 3u * c.body.faces.size());
  EXPECT_NEAR(s.longest_crack_length, expected, 1e-10);
  EXPECT_NEAR(s.total_crack_length, expected, 1e-10);  // one cluster: the total is its length
  EXPECT_NEAR(s.failed_area_fraction, 1.0, 1e-14);    // every spring's third of each face
  EXPECT_DOUBLE_EQ(s.hemisphere_fraction, y_positive / 480.0);
  EXPECT_GT(s.longest_crack_extent, 0.95 * std::numbers::pi);  // spans the globe
  EXPECT_NEAR(s.mean_angle_from_subsatellite_deg, 90.0, 1e-9);  // symmetric about the xz-plane
}

TEST(FractureAnalysis, FailureSummaryJson) {
  Checkpoint c = synthetic_encounter(1);
  c.state.springs.failed[0] = 1;
  const FractureSummary s = analyze_fractures(c.body, c.state);
  // Ordered JSON compares key order too; as text, since NaN (null in the file) equals nothing.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(failure_summary_json(s).dump(), Json({{"count", 1},
                                           {"fraction_shell", 1.0 / 120},
                                           {"hemisphere_fraction", s.hemisphere_fraction},
                                           {"mean_angle_from_subsatellite_deg", s.mean_angle_from_subsatellite_deg},
                                           {"median_angle_from_subsatellite_deg", s.median_angle_from_subsatellite_deg},
                                           {"largest_network_length", s.longest_crack_length},
                                           {"largest_network_extent", s.longest_crack_extent},
                                           {"clusters", 1},
                                           {"total_crack_length", s.total_crack_length},
                                           {"failed_area_fraction", s.failed_area_fraction},
                                           {"concentricity", s.geometry.orientations.concentricity},
                                           {"crack_rose_peak_deg", s.geometry.orientations.rose_peak_deg},
                                           {"fitted_arcs", 0},
                                           {"median_arc_radius_deg", nan},
                                           {"median_arc_pole_axis_from_subsatellite_deg", nan},
                                           {"longest_arc_radius_deg", nan},
                                           {"longest_arc_pole_axis_from_subsatellite_deg", nan},
                                           {"longest_arc_span_deg", nan},
                                           {"longest_arc_misfit_deg", nan}}).dump());
  EXPECT_GT(s.longest_crack_length, 0.0);
  // One failed spring: one crack element (its azimuth defined), too short for a circle.
  EXPECT_TRUE(std::isfinite(s.geometry.orientations.concentricity));
  EXPECT_TRUE(s.geometry.arcs.empty());
}

// On the regular icosahedron (level 0, vertices on the unit sphere) every face has the same area,
// so one failed edge is 2/3 of a face of 20: 1/30 of the area, its share of the 30 springs. Its
// two bars run from the two face centroids to the edge midpoint, each the inradius a/(2 sqrt 3) of
// a face of edge a = 4 / sqrt(10 + 2 sqrt 5).
TEST(FractureAnalysis, OneFailedEdgeOfTheIcosahedronHasExactAreaAndLength) {
  Checkpoint c = synthetic_encounter(0);
  ASSERT_EQ(c.body.faces.size(), 20u);
  c.state.springs.failed[0] = 1;
  const FractureSummary s = analyze_fractures(c.body, c.state);
  ASSERT_EQ(s.count(), 1u);
  EXPECT_EQ(s.fraction_shell, 1.0 / 30);
  EXPECT_NEAR(s.failed_area_fraction, 1.0 / 30, 1e-15);
  const double edge = 4 / std::sqrt(10 + 2 * std::sqrt(5.0));
  EXPECT_NEAR(s.total_crack_length, 2 * edge / (2 * std::sqrt(3.0)), 1e-14);
  EXPECT_EQ(s.total_crack_length, s.longest_crack_length);
}

// On a level-1 icosphere the faces differ in area: a failed spring counts a third of each of its
// two faces (brute force here, without shell_topology), not 1/120 of the shell.
TEST(FractureAnalysis, FailedAreaFractionCountsAThirdOfEachFaceOfAFailedSpring) {
  Checkpoint c = synthetic_encounter(1);
  auto area = [&](const std::array<std::int32_t, 3>& f) {
    const Vec3 a = vec3_at(c.state.position, static_cast<std::size_t>(f[0]));
    const Vec3 b = vec3_at(c.state.position, static_cast<std::size_t>(f[1]));
    const Vec3 d = vec3_at(c.state.position, static_cast<std::size_t>(f[2]));
    return 0.5 * (b - a).cross(d - a).norm();
  };
  double total = 0, smallest = 1e9, largest = 0;
  for (const auto& f : c.body.faces) total += area(f), smallest = std::min(smallest, area(f)), largest = std::max(largest, area(f));
  ASSERT_GT(largest / smallest, 1.05) << "the level-1 faces differ in area";
  double expected = 0;
  for (const std::size_t spring : {0, 7, 33}) {
    c.state.springs.failed[spring] = 1;
    const auto e = c.body.springs[spring];
    for (const auto& f : c.body.faces) {
      const auto has = [&](std::int32_t v) { return std::find(f.begin(), f.end(), v) != f.end(); };
      if (has(e[0]) && has(e[1])) expected += area(f) / 3;
    }
  }
  const FractureSummary s = analyze_fractures(c.body, c.state);
  ASSERT_EQ(s.count(), 3u);
  EXPECT_NEAR(s.failed_area_fraction, expected / total, 1e-15);
  EXPECT_NE(s.failed_area_fraction, s.fraction_shell);
  double bars = 0;
  for (const auto& bar : s.bars) bars += (bar.edge_midpoint - bar.centroid).norm();
  EXPECT_NEAR(s.total_crack_length, bars, 1e-15);
  EXPECT_EQ(s.bars.size(), 6u);
}

TEST(FractureAnalysis, NoFailuresHaveNoAreaAndNoLength) {
  const Checkpoint c = synthetic_encounter(1);
  const FractureSummary s = analyze_fractures(c.body, c.state);
  EXPECT_EQ(s.failed_area_fraction, 0.0);
  EXPECT_EQ(s.total_crack_length, 0.0);
}
