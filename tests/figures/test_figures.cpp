#include <cairo.h>
#include <Eigen/Geometry>  // cross()
#include <gtest/gtest.h>


#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>
#include <string>

#include "figures/figure_output.hpp"
#include "figures/figures.hpp"
#include "figures/figure_body_shape.hpp"
#include "base/errors.hpp"
#include "model/center_of_mass.hpp"
#include "physics/orbital_frame.hpp"
#include "support/synthetic_encounter.hpp"
#include "physics/two_body_orbit.hpp"
#include "support/files.hpp"
#include "support/synthetic_encounter.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

void expect_png_and_svg(const FigureFiles& files) {
  ASSERT_EQ(files.size(), 2u);
  const std::string png = read_file(files[0]);
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  const std::string svg = read_file(files[1]);
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
}

struct Png {
  explicit Png(const fs::path& file) : surface(cairo_image_surface_create_from_png(file.c_str()), cairo_surface_destroy) {}
  /// Luminance 0 (black) .. 1 (white) at the pixel under page point (x, y), in points.
  double luminance(double x, double y) const {
    cairo_surface_flush(surface.get());
    const int px = static_cast<int>(x * png_pixels_per_point), py = static_cast<int>(y * png_pixels_per_point);
    const auto* row = cairo_image_surface_get_data(surface.get()) + py * cairo_image_surface_get_stride(surface.get());
    const std::uint32_t argb = reinterpret_cast<const std::uint32_t*>(row)[px];
    const double r = (argb >> 16 & 0xff) / 255.0, g = (argb >> 8 & 0xff) / 255.0, b = (argb & 0xff) / 255.0;
    return 0.299 * r + 0.587 * g + 0.114 * b;
  }
  std::unique_ptr<cairo_surface_t, void (*)(cairo_surface_t*)> surface;
};

/// Fails the shell spring whose midpoint is closest to direction `d`; returns its index.
std::int32_t fail_spring_near(Checkpoint& c, const Vec3& d) {
  std::int32_t best = -1;
  double best_dot = -2;
  for (std::size_t s = 0; s < c.body.spring_count(); ++s) {
    if (c.body.spring_kind[s] != static_cast<std::uint8_t>(SpringKind::shell)) continue;
    const Vec3 m = 0.5 * (vec3_at(c.state.position, c.body.springs[s][0]) + vec3_at(c.state.position, c.body.springs[s][1]));
    if (m.normalized().dot(d.normalized()) > best_dot) best_dot = m.normalized().dot(d.normalized()), best = static_cast<std::int32_t>(s);
  }
  c.state.springs.failed[static_cast<std::size_t>(best)] = 1;
  return best;
}

}  // namespace

TEST(Figures, FractureMapDrawsCrackBarsWhereTheyAre) {
  Checkpoint c = synthetic_encounter(3);
  fail_spring_near(c, {-0.6, 0.2, 0.5});
  fail_spring_near(c, {-1, -0.01, 0.1});  // faces close to the dateline (longitude 180)
  const FractureSummary fractures = analyze_fractures(c.body, c.state);
  const ScratchFolder scratch("figures_map");
  const fs::path& dir = scratch.path;
  const auto files = write_fracture_map(fractures, dir / "map", "test map");
  expect_png_and_svg(files);
  const Png png(files[0]);
  const PlotAxes axes = fracture_map_axes();
  for (const auto& bar : fractures.bars) {
    const Vec3 middle = 0.5 * (bar.centroid + bar.edge_midpoint);
    const double lon = longitude_deg(middle), lat = latitude_deg(middle);
    EXPECT_LT(png.luminance(axes.page_x(lon), axes.page_y(lat)), 0.35) << lon << " " << lat;
  }
  // Ice where nothing failed (between graticule lines), and the ring at the subsatellite point.
  EXPECT_GT(png.luminance(axes.page_x(-100), axes.page_y(-40)), 0.8);
  const double ring = png.luminance(axes.page_x(90) + 8, axes.page_y(0));
  EXPECT_LT(ring, 0.85);
}

// compare --resolution's figure: one map panel per level, side by side, each drawn by the same
// draw_fracture_map as write_fracture_map (cracks where they are, ice elsewhere, the ring).
TEST(Figures, FractureMapRowHasOnePanelPerLevelWithItsCracks) {
  std::vector<Checkpoint> levels{synthetic_encounter(1), synthetic_encounter(2), synthetic_encounter(3)};
  std::vector<FractureSummary> summaries;
  for (auto& c : levels) {
    fail_spring_near(c, {-0.6, 0.2, 0.5});
    summaries.push_back(analyze_fractures(c.body, c.state));
  }
  const std::int32_t second = fail_spring_near(levels[2], {0.3, -1, -0.2});  // on the finest level only
  summaries[2] = analyze_fractures(levels[2].body, levels[2].state);
  const ScratchFolder scratch("figures_map_row");
  const auto files = write_fracture_map_row({&summaries[0], &summaries[1], &summaries[2]},
                                            {"level 1", "level 2", "level 3"}, scratch.path / "row", "test\nrow");
  expect_png_and_svg(files);
  const Png png(files[0]);
  EXPECT_EQ(cairo_image_surface_get_width(png.surface.get()), static_cast<int>(2 * (2 * 62 + 3 * 320 + 2 * 70)));
  EXPECT_EQ(cairo_image_surface_get_height(png.surface.get()), static_cast<int>(2 * (80 + 160 + 58)));
  for (std::size_t panel = 0; panel < 3; ++panel) {
    const PlotAxes axes = fracture_map_row_axes(panel);
    EXPECT_EQ(axes.area().width, 320);
    if (panel > 0) {
      EXPECT_GT(axes.area().left, fracture_map_row_axes(panel - 1).area().right() + 40);
    }
    for (const auto& bar : summaries[panel].bars) {
      const Vec3 middle = 0.5 * (bar.centroid + bar.edge_midpoint);
      EXPECT_LT(png.luminance(axes.page_x(longitude_deg(middle)), axes.page_y(latitude_deg(middle))), 0.35) << panel;
    }
    EXPECT_GT(png.luminance(axes.page_x(-100), axes.page_y(-40)), 0.8) << panel;
    EXPECT_LT(png.luminance(axes.page_x(90) + 8, axes.page_y(0)), 0.85) << panel;  // the ring
  }
  // The second crack (toward -y: longitude about -90) is drawn on the level-3 panel only.
  Vec3 far = Vec3::Zero();
  for (const auto& bar : summaries[2].bars)
    if (bar.spring == second) far = 0.5 * (bar.centroid + bar.edge_midpoint);
  const double lon = longitude_deg(far), lat = latitude_deg(far);
  ASSERT_LT(lon, 0);
  EXPECT_LT(png.luminance(fracture_map_row_axes(2).page_x(lon), fracture_map_row_axes(2).page_y(lat)), 0.5);
  EXPECT_GT(png.luminance(fracture_map_row_axes(0).page_x(lon), fracture_map_row_axes(0).page_y(lat)), 0.6);
  EXPECT_THROW(write_fracture_map_row({}, {}, scratch.path / "none", "x"), InputError);
}

TEST(Figures, HemisphereViewShowsCracksFacingTheViewer) {
  Checkpoint c = synthetic_encounter(3);
  fail_spring_near(c, {0.3, 1, 0.4});
  Checkpoint later = c;
  later.state.time = 2.5;
  later.state.perturber.position = {-1.9, 1.5, 0};  // off to the right on screen, partly in view
  const ScratchFolder scratch("figures_hemisphere");
  const fs::path& dir = scratch.path;
  const auto files = write_hemisphere_views({&c, &later}, 1.2, dir / "hemisphere", "test views");
  expect_png_and_svg(files);
  const Png png(files[0]);
  const FractureSummary fractures = analyze_fractures(c.body, c.state);
  for (std::size_t panel = 0; panel < 2; ++panel) {
    const PlotAxes axes = hemisphere_panel_axes(panel, 2);
    for (const auto& bar : fractures.bars) {
      const Vec3 middle = 0.5 * (bar.centroid + bar.edge_midpoint);
      EXPECT_LT(png.luminance(axes.page_x(-middle.x()), axes.page_y(middle.z())), 0.3);
    }
    // Lit ice on the upper left of the disc, away from the crack; space outside it.
    EXPECT_GT(png.luminance(axes.page_x(-0.5), axes.page_y(-0.3)), 0.5);
    EXPECT_LT(png.luminance(axes.page_x(-1.4), axes.page_y(-1.4)), 0.1);
  }
  // The perturber (radius 0.5^(1/3) = 0.79 at screen x = 1.9) tints space magenta at x = 1.3,
  // in the second panel only.
  auto magenta = [&](std::size_t panel) {
    const PlotAxes axes = hemisphere_panel_axes(panel, 2);
    cairo_surface_flush(png.surface.get());
    const int px = static_cast<int>(axes.page_x(1.3) * png_pixels_per_point);
    const int py = static_cast<int>(axes.page_y(0.2) * png_pixels_per_point);
    const auto* row = cairo_image_surface_get_data(png.surface.get()) + py * cairo_image_surface_get_stride(png.surface.get());
    const std::uint32_t argb = reinterpret_cast<const std::uint32_t*>(row)[px];
    return static_cast<int>(argb >> 16 & 0xff) - static_cast<int>(argb >> 8 & 0xff);  // red minus green
  };
  EXPECT_GT(magenta(1), 30);
  EXPECT_LT(magenta(0), 5);
}

TEST(Figures, OrbitFailureAndConservationPlotsAreWritten) {
  Checkpoint c = synthetic_encounter(1);
  for (int i = 0; i < 20; ++i) {
    TimeseriesSample s;
    s.time = 0.1 * i;
    s.failed = i / 4;
    s.kinetic_energy = 0.1 + 1e-4 * i;
    s.momentum = {1e-15 * i, 0, 0};
    s.angular_momentum = {0, 0, 2.0 + 1e-13 * i};
    c.observables.timeseries.push_back(s);
  }
  for (int i = 0; i < 5; ++i) c.observables.failures.push_back({1.0 + 0.1 * i, 500 + 50 * i, i, 0.004, {0, 1, 0}});
  const EncounterRecord encounter = stage_record<EncounterRecord>(c, "synthetic.h5");
  const ScratchFolder scratch("figures_series");
  const fs::path& dir = scratch.path;
  expect_png_and_svg(write_orbit_plot(c, encounter, {0.8, 1.2, 1.6}, dir / "orbit", "orbit"));
  expect_png_and_svg(write_failure_history(c, encounter.pericenter_time, dir / "failures", "failures"));
  expect_png_and_svg(write_conservation_plot(c, encounter.pericenter_time, dir / "conservation", "conservation"));
}

// Extreme values in a record (M2 = 1e300 at its parabolic speed, a stage spanning 1e9 t_grav:
// 1e10 diamonds at 0.1 t_grav) must not make the orbit figure hang: it returns, with no more
// drawn than for an ordinary record (the drawing is bounded in elements, not timed).
TEST(Figures, OrbitPlotOfAnExtremeRecordReturns) {
  Checkpoint c = synthetic_encounter(1);
  c.state.time = c.stage.clock.start_time + 1e9;
  EncounterRecord& record = c.stage.as<EncounterRecord>();
  record.encounter.perturber_mass = 1e300;
  record.encounter.pericenter_speed = std::sqrt(2.0 * (1 + 1e300) / record.encounter.pericenter);
  const ScratchFolder scratch("figures_extreme_orbit");
  const Checkpoint ordinary = synthetic_encounter(1);
  const auto ordinary_files =
      write_orbit_plot(ordinary, ordinary.stage.as<EncounterRecord>(), {1.0, 2.0}, scratch.path / "ordinary", "ordinary");
  expect_png_and_svg(ordinary_files);
  const std::size_t ordinary_svg = read_file(ordinary_files[1]).size();
  for (const bool sampled : {false, true}) {
    if (sampled)
      for (int i = 0; i < 20; ++i) {
        TimeseriesSample s;
        s.time = 1e8 * i;
        s.perturber_offset = {1e100 * i, 1.0, 0.0};
        c.observables.timeseries.push_back(s);
      }
    const std::string name = sampled ? "sampled" : "analytic";
    const auto files = write_orbit_plot(c, record, {1.0, 1e8}, scratch.path / name, name);
    expect_png_and_svg(files);
    // At most 400 diamonds and 600 track points: the SVG stays the size of an ordinary one.
    EXPECT_LT(read_file(files[1]).size(), 3 * ordinary_svg) << name;
  }
}

TEST(Figures, OrbitPlotDrawsTheSimulatedTrackWhereItWasSampled) {
  // A simulated track 0.8 R outside the analytic one (stage from t = 0 to 2, pericenter at 1.2),
  // sampled every 0.02 t_grav.
  Checkpoint c = synthetic_encounter(1);
  const EncounterRecord encounter = stage_record<EncounterRecord>(c, "synthetic.h5");
  const TwoBodyOrbit orbit = perturber_orbit(encounter.encounter.perturber_mass, encounter.encounter.pericenter, encounter.encounter.pericenter_speed);
  auto simulated = [&](double t) {
    const Vec3 p = orbit.state_at_time(t - encounter.pericenter_time).position;
    return Vec3(p + 0.8 * p.normalized());
  };
  for (int i = 0; i <= 100; ++i) {
    TimeseriesSample s;
    s.time = 0.02 * i;
    const Vec3 p = simulated(s.time);
    s.perturber_offset = {p.x(), p.y(), p.z()};
    c.observables.timeseries.push_back(s);
  }
  // Halfway between the samples at t = 0.64 and 0.66, away from the diamonds (every 0.1) and
  // from the analytic track.
  const Vec3 between = 0.5 * (simulated(0.64) + simulated(0.66));
  ASSERT_GT((between - orbit.state_at_time(0.65 - encounter.pericenter_time).position).norm(), 0.7);
  const ScratchFolder scratch("figures_simulated_orbit");
  const fs::path& dir = scratch.path;
  {
    const auto files = write_orbit_plot(c, encounter, {}, dir / "simulated", "simulated");
    expect_png_and_svg(files);
    const PlotAxes axes = orbit_plot_axes(c, encounter, {});
    EXPECT_LT(Png(files[0]).luminance(axes.page_x(between.x()), axes.page_y(between.y())), 0.5);
  }
  // Without perturber offsets (an older kind of sample) the same point is empty paper: only the
  // analytic track is drawn.
  for (auto& s : c.observables.timeseries) s.perturber_offset = {};
  {
    const auto files = write_orbit_plot(c, encounter, {}, dir / "analytic", "analytic");
    const PlotAxes axes = orbit_plot_axes(c, encounter, {});
    EXPECT_GT(Png(files[0]).luminance(axes.page_x(between.x()), axes.page_y(between.y())), 0.9);
    const Vec3 on_analytic = orbit.state_at_time(0.65 - encounter.pericenter_time).position;
    EXPECT_LT(Png(files[0]).luminance(axes.page_x(on_analytic.x()), axes.page_y(on_analytic.y())), 0.5);
  }
}

namespace {
/// Angle between two map points on the unit sphere, degrees.
double map_angle_deg(double lon1, double lat1, double lon2, double lat2) {
  constexpr double rad = std::numbers::pi / 180;
  auto unit = [](double lon, double lat) {
    return Vec3(std::cos(lat * rad) * std::cos(lon * rad), std::cos(lat * rad) * std::sin(lon * rad), std::sin(lat * rad));
  };
  const Vec3 a = unit(lon1, lat1), b = unit(lon2, lat2);
  return std::atan2(a.cross(b).norm(), a.dot(b)) / rad;
}

/// The unit vector at map longitude and latitude (degrees): orbital_frame.hpp, longitude from +x
/// in the xy-plane, latitude toward +z.
Vec3 on_map(double lon, double lat) {
  constexpr double rad = std::numbers::pi / 180;
  return {std::cos(lat * rad) * std::cos(lon * rad), std::cos(lat * rad) * std::sin(lon * rad), std::sin(lat * rad)};
}

/// Checks what every drawn piece must satisfy: longitudes inside the map, no step longer than
/// 3 degrees in longitude or latitude, so no piece is drawn across the map.
void expect_drawable(const std::vector<MapPolyline>& pieces) {
  for (const auto& piece : pieces) {
    ASSERT_EQ(piece.longitude_deg.size(), piece.latitude_deg.size());
    ASSERT_GE(piece.longitude_deg.size(), 2u);
    for (std::size_t i = 0; i < piece.longitude_deg.size(); ++i) {
      EXPECT_GE(piece.longitude_deg[i], -180.0);
      EXPECT_LE(piece.longitude_deg[i], 180.0);
      if (i == 0) continue;
      EXPECT_LE(std::abs(piece.longitude_deg[i] - piece.longitude_deg[i - 1]), 3.0 + 1e-9);
      EXPECT_LE(std::abs(piece.latitude_deg[i] - piece.latitude_deg[i - 1]), 3.0 + 1e-9);
    }
  }
}

/// Sum over the drawn steps of the angle between their end points, degrees.
double drawn_angle_deg(const std::vector<MapPolyline>& pieces) {
  double sum = 0;
  for (const auto& p : pieces)
    for (std::size_t i = 1; i < p.longitude_deg.size(); ++i)
      sum += map_angle_deg(p.longitude_deg[i - 1], p.latitude_deg[i - 1], p.longitude_deg[i], p.latitude_deg[i]);
  return sum;
}

double angle_deg(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180 / std::numbers::pi;
}
}  // namespace

TEST(Figures, MapSegmentAcrossTheSeamIsTwoPiecesMeetingOnIt) {
  const Vec3 from = on_map(178, 10), to = on_map(-176, 12);
  const auto pieces = map_segment_pieces(from, to);
  ASSERT_EQ(pieces.size(), 2u);
  expect_drawable(pieces);
  EXPECT_EQ(pieces[0].longitude_deg.front(), longitude_deg(from));
  EXPECT_EQ(pieces[0].longitude_deg.back(), 180.0);
  EXPECT_EQ(pieces[1].longitude_deg.front(), -180.0);
  EXPECT_EQ(pieces[1].longitude_deg.back(), longitude_deg(to));
  EXPECT_EQ(pieces[0].latitude_deg.back(), pieces[1].latitude_deg.front());
  EXPECT_GT(pieces[1].latitude_deg.front(), 10.0);
  EXPECT_LT(pieces[1].latitude_deg.front(), 12.0);
  // Together no longer than the segment itself (6 degrees of longitude near the equator).
  EXPECT_NEAR(drawn_angle_deg(pieces), angle_deg(from, to), 0.01 * angle_deg(from, to));
}

TEST(Figures, MapSegmentNearAPoleFollowsItAndBreaksOverIt) {
  // The crack bar of the quick run at latitude -85: 2.3 degrees long, 27 degrees of longitude.
  const Vec3 from = on_map(115.5, -84.8), to = on_map(142.1, -85.5);
  const auto near = map_segment_pieces(from, to);
  ASSERT_EQ(near.size(), 1u);
  expect_drawable(near);
  EXPECT_GE(near[0].longitude_deg.size(), 10u);  // bent as the projection bends it
  EXPECT_NEAR(drawn_angle_deg(near), angle_deg(from, to), 0.01 * angle_deg(from, to));
  // A bar over the south pole: two pieces, one on each side, none along the map's edge (where
  // the projection puts the pole).
  const Vec3 a = on_map(10, -87.5), b = on_map(-170, -88);
  const auto over = map_segment_pieces(a, b);
  ASSERT_EQ(over.size(), 2u);
  expect_drawable(over);
  for (const double lon : over[0].longitude_deg) EXPECT_NEAR(lon, 10, 3.0);
  for (const double lon : over[1].longitude_deg) EXPECT_NEAR(lon, -170, 3.0);
  EXPECT_LE(drawn_angle_deg(over), angle_deg(a, b) * 1.001);
  EXPECT_GE(drawn_angle_deg(over), angle_deg(a, b) * 0.95);
}

TEST(Figures, HemispherePerturberInFrontIsDrawnUnderTheCracks) {
  using enum HemisphereLayer;
  EXPECT_EQ(hemisphere_panel_layers(false, true), (std::vector<HemisphereLayer>{faces, cracks}));
  EXPECT_EQ(hemisphere_panel_layers(true, false),
            (std::vector<HemisphereLayer>{perturber_fill, perturber_outline, faces, cracks}));
  EXPECT_EQ(hemisphere_panel_layers(true, true),
            (std::vector<HemisphereLayer>{faces, perturber_fill, cracks, perturber_outline}));

  // Drawn: a crack facing the viewer under the disc of a perturber in front of it stays black,
  // not tinted magenta.
  Checkpoint c = synthetic_encounter(3);
  fail_spring_near(c, {0.05, 1, 0.05});
  c.state.perturber.position = {0, 2.5, 0};
  const ScratchFolder scratch("figures_perturber_in_front");
  const auto files = write_hemisphere_views({&c}, 0.0, scratch.path / "hemisphere", "in front");
  const Png png(files[0]);
  const PlotAxes axes = hemisphere_panel_axes(0, 1);
  cairo_surface_flush(png.surface.get());
  for (const auto& bar : analyze_fractures(c.body, c.state).bars) {
    const Vec3 middle = 0.5 * (bar.centroid + bar.edge_midpoint);
    const int px = static_cast<int>(axes.page_x(-middle.x()) * png_pixels_per_point);
    const int py = static_cast<int>(axes.page_y(middle.z()) * png_pixels_per_point);
    const auto* row = cairo_image_surface_get_data(png.surface.get()) + py * cairo_image_surface_get_stride(png.surface.get());
    const std::uint32_t argb = reinterpret_cast<const std::uint32_t*>(row)[px];
    EXPECT_LT(static_cast<int>(argb >> 16 & 0xff) - static_cast<int>(argb >> 8 & 0xff), 12);  // red minus green
    EXPECT_LT(png.luminance(axes.page_x(-middle.x()), axes.page_y(middle.z())), 0.2);
  }
}

TEST(Figures, BodySlicesDrawSpringsAndParticlesOfTheOrbitalPlane) {
  Checkpoint c = synthetic_encounter(3);
  Checkpoint stretched = c;
  for (std::size_t i = 0; i < stretched.body.particle_count(); ++i) stretched.state.position[3 * i] *= 1.3;
  stretched.state.time = 1.0;
  const ScratchFolder scratch("figures_body_shape");
  const auto files = write_body_slices({&c, &stretched}, 0.5, scratch.path / "body_shape", "test slices");
  expect_png_and_svg(files);
  const Png png(files[0]);
  // The centre particle (on the orbital plane, at the centre of mass to within the shell's
  // asymmetry) is a dark dot; the corner of a panel, outside the body, stays white.
  for (std::size_t panel = 0; panel < 2; ++panel) {
    const PlotAxes axes = body_slice_panel_axes(panel, 2);
    const Vec3 com = body_center_of_mass((panel ? stretched : c).body, (panel ? stretched : c).state);
    EXPECT_LT(png.luminance(axes.page_x(-com.x()), axes.page_y(-com.y())), 0.5);
    EXPECT_GT(png.luminance(axes.page_x(-1.4), axes.page_y(1.4)), 0.95);
  }
  // The stretched body's outline reaches x = 1.25 R, the round one's does not (grey fill there).
  const PlotAxes round = body_slice_panel_axes(0, 2), long_body = body_slice_panel_axes(1, 2);
  EXPECT_GT(png.luminance(round.page_x(1.2), round.page_y(0.0)), 0.95);
  EXPECT_LT(png.luminance(long_body.page_x(1.2), long_body.page_y(0.0)), 0.95);
}

TEST(Figures, AxisRatiosArePlottedWhereTheyAre) {
  std::vector<double> times = {-1.0, 0.0, 1.0, 2.0};
  std::vector<PrincipalAxes> shapes(4);
  const double b[] = {1.0, 0.9, 0.8, 0.85}, cc[] = {1.0, 0.95, 0.9, 0.92};
  for (std::size_t k = 0; k < 4; ++k) shapes[k].semi_axis = {1.0, b[k], cc[k] * b[k]};
  const ScratchFolder scratch("figures_axis_ratios");
  const auto files = write_axis_ratios(times, shapes, scratch.path / "axis_ratios", "test ratios");
  expect_png_and_svg(files);
  const Png png(files[0]);
  const PlotAxes axes = axis_ratio_axes(times, shapes);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_LT(png.luminance(axes.page_x(times[k]), axes.page_y(shapes[k].b_over_a())), 0.3);  // a marker
    EXPECT_LT(png.luminance(axes.page_x(times[k]), axes.page_y(shapes[k].c_over_a())), 0.3);
  }
  EXPECT_GT(png.luminance(axes.page_x(1.5), axes.page_y(0.99)), 0.9);  // nothing drawn up there
  EXPECT_THROW(write_axis_ratios({0.0}, {}, scratch.path / "bad", "bad"), InputError);
}
