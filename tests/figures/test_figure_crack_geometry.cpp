// The crack-geometry figure (write_crack_geometry): the fitted circle over the cracks on the map,
// its pole, and the rose petals in the directions of the crack azimuths; read back from the PNG.
#include <cairo.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>

#include "analysis/fracture_analysis.hpp"
#include "figures/figure_output.hpp"
#include "figures/figure_style.hpp"
#include "figures/figures.hpp"
#include "physics/orbital_frame.hpp"
#include "support/files.hpp"
#include "support/synthetic_encounter.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

struct PngColors {
  explicit PngColors(const fs::path& file)
      : surface(cairo_image_surface_create_from_png(file.c_str()), cairo_surface_destroy) {}
  /// Red, green, blue 0..1 at page point (x, y), points.
  std::array<double, 3> rgb(double x, double y) const {
    cairo_surface_flush(surface.get());
    const int px = static_cast<int>(x * png_pixels_per_point), py = static_cast<int>(y * png_pixels_per_point);
    const auto* row = cairo_image_surface_get_data(surface.get()) + py * cairo_image_surface_get_stride(surface.get());
    const std::uint32_t argb = reinterpret_cast<const std::uint32_t*>(row)[px];
    return {(argb >> 16 & 0xff) / 255.0, (argb >> 8 & 0xff) / 255.0, (argb & 0xff) / 255.0};
  }
  bool bluish(double x, double y) const {
    const auto c = rgb(x, y);
    return c[2] > c[0] + 0.2 && c[2] > 0.5;
  }
  bool white(double x, double y) const {
    const auto c = rgb(x, y);
    return c[0] > 0.97 && c[1] > 0.97 && c[2] > 0.97;
  }
  std::unique_ptr<cairo_surface_t, void (*)(cairo_surface_t*)> surface;
};

/// The failed springs of a level-4 icosphere that cross the circle 50 deg from the subsatellite
/// point: one ring crack concentric about it.
FractureSummary ring_about_the_subsatellite_point() {
  Checkpoint c = synthetic_encounter(4);
  const double cos50 = std::cos(50 * std::numbers::pi / 180);
  for (std::size_t s = 0; s < c.body.spring_count(); ++s) {
    if (c.body.spring_kind[s] != static_cast<std::uint8_t>(SpringKind::shell)) continue;
    const double a = vec3_at(c.state.position, c.body.springs[s][0]).normalized().y() - cos50;
    const double b = vec3_at(c.state.position, c.body.springs[s][1]).normalized().y() - cos50;
    if (a * b < 0) c.state.springs.failed[s] = 1;
  }
  return analyze_fractures(c.body, c.state);
}

}  // namespace

TEST(CrackGeometryFigure, DrawsTheFittedCircleItsPoleAndTheRose) {
  const FractureSummary fractures = ring_about_the_subsatellite_point();
  ASSERT_EQ(fractures.geometry.arcs.size(), 1u);
  const SmallCircleFit& fit = fractures.geometry.arcs[0].fit;
  const ScratchFolder scratch("figure_crack_geometry");
  const FigureFiles files = write_crack_geometry(fractures, scratch.path / "crack_geometry", "test\nsecond line");
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0].extension(), ".png");
  EXPECT_NE(read_file(files[1]).find("</svg>"), std::string::npos);
  const PngColors png(files[0]);

  // The circle is drawn where the fit puts it, over the cracks; its pole is the numbered dot.
  const PlotAxes map = crack_geometry_map_axes();
  int on_circle = 0;
  for (const double a : {30.0, 100.0, 200.0, 300.0}) {
    const Vec3 p = point_on_circle(fit, a);
    on_circle += png.bluish(map.page_x(longitude_deg(p)), map.page_y(latitude_deg(p)));
  }
  EXPECT_EQ(on_circle, 4);
  EXPECT_TRUE(png.bluish(map.page_x(fit.pole_longitude_deg), map.page_y(fit.pole_latitude_deg)));
  // Ice far from the ring (the antipodal hemisphere) is not blue.
  EXPECT_FALSE(png.bluish(map.page_x(-100), map.page_y(-35)));

  // Rose: the petal of the fullest bin is filled in its direction and the opposite one (an axis:
  // azimuth 0 up, counter-clockwise), an empty bin's direction is white.
  const CrackRoseLayout rose = crack_rose_layout();
  const CrackOrientations& o = fractures.geometry.orientations;
  auto rose_point = [&](double azimuth_deg, double fraction) {
    const double angle = -(azimuth_deg + 90) * std::numbers::pi / 180;
    return std::array<double, 2>{rose.center_x + fraction * rose.radius * std::cos(angle),
                                 rose.center_y + fraction * rose.radius * std::sin(angle)};
  };
  for (const double a : {o.rose_peak_deg, o.rose_peak_deg + 180}) {
    const auto p = rose_point(a, 0.6);
    EXPECT_TRUE(png.bluish(p[0], p[1])) << a;
  }
  std::size_t empty = 0;
  while (empty < o.bins && o.rose[empty] != 0) ++empty;
  ASSERT_LT(empty, o.bins) << "a ring has cracks in a few directions only";
  // 3 deg off the bin centre: the frame's axes run through 0, 30, ... deg.
  for (const double a : {o.bin_width_deg * static_cast<double>(empty) + 3, o.bin_width_deg * static_cast<double>(empty) + 183}) {
    const auto p = rose_point(a, 0.6);
    EXPECT_TRUE(png.white(p[0], p[1])) << a;
  }
}

TEST(CrackGeometryFigure, AFractureSetWithoutArcsStillDraws) {
  const Checkpoint c = synthetic_encounter(2);
  const FractureSummary none = analyze_fractures(c.body, c.state);
  const ScratchFolder scratch("figure_crack_geometry_empty");
  const FigureFiles files = write_crack_geometry(none, scratch.path / "empty", "no cracks");
  ASSERT_EQ(files.size(), 2u);
  const PngColors png(files[0]);
  const CrackRoseLayout rose = crack_rose_layout();
  EXPECT_TRUE(png.white(rose.center_x + 0.6 * rose.radius, rose.center_y + 1));
}
