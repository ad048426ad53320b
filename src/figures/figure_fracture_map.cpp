// Figure 8 (fig:lat): fractures in cylindrical projection.
#include <cmath>
#include <numbers>

#include "figures/figure_output.hpp"
#include "figures/figure_style.hpp"
#include "figures/figures.hpp"
#include "physics/orbital_frame.hpp"

namespace tidalcrust {

namespace {
constexpr double map_width_pt = 720, map_height_pt = 420;
constexpr PageRect map_area{62, 40, 640, 320};

/// Wraps a longitude difference into (-180, 180].
double wrap_deg(double d) {
  while (d > 180) d -= 360;
  while (d <= -180) d += 360;
  return d;
}

/// One half-bar centroid -> edge midpoint, sampled along the chord so that it bends as the
/// projection does; longitudes are unwrapped along the bar, and a bar that leaves [-180, 180]
/// is drawn again shifted by 360 degrees (the map is clipped to its frame).
void draw_bar(cairo_t* cr, const PlotAxes& axes, const Vec3& from, const Vec3& to) {
  constexpr int pieces = 8;
  std::vector<double> lon(pieces + 1), lat(pieces + 1);
  for (int i = 0; i <= pieces; ++i) {
    const Vec3 p = from + (to - from) * (static_cast<double>(i) / pieces);
    lat[i] = latitude_deg(p);
    lon[i] = i == 0 ? longitude_deg(p) : lon[i - 1] + wrap_deg(longitude_deg(p) - lon[i - 1]);
  }
  double lo = lon[0], hi = lon[0];
  for (const double l : lon) lo = std::min(lo, l), hi = std::max(hi, l);
  for (const double shift : {0.0, -360.0, 360.0}) {
    if ((shift < 0 && hi <= 180) || (shift > 0 && lo >= -180)) continue;
    std::vector<double> shifted(lon);
    for (double& l : shifted) l += shift;
    axes.path(cr, shifted, lat);
    cairo_stroke(cr);
  }
}
}  // namespace

PlotAxes fracture_map_axes() { return PlotAxes(map_area, -180, 180, -90, 90); }

FigureFiles write_fracture_map(const FractureSummary& fractures, const std::filesystem::path& stem,
                               const std::string& title) {
  const PlotAxes axes = fracture_map_axes();
  return write_figure(stem, map_width_pt, map_height_pt, [&](cairo_t* cr) {
    cairo_save(cr);
    axes.clip(cr);
    set_color(cr, surface_color);
    cairo_paint(cr);
    // Graticule every 30 degrees; the equator (orbital plane) slightly darker.
    cairo_set_line_width(cr, 0.5);
    for (int lon = -150; lon <= 150; lon += 30) {
      axes.path(cr, {double(lon), double(lon)}, {-90.0, 90.0});
    }
    for (int lat = -60; lat <= 60; lat += 30) axes.path(cr, {-180.0, 180.0}, {double(lat), double(lat)});
    set_color(cr, graticule_color);
    cairo_stroke(cr);
    cairo_set_line_width(cr, 0.9);
    axes.path(cr, {-180.0, 180.0}, {0.0, 0.0});
    cairo_stroke(cr);

    set_color(cr, crack_color);
    cairo_set_line_width(cr, map_crack_width);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    for (const auto& bar : fractures.bars) draw_bar(cr, axes, bar.centroid, bar.edge_midpoint);

    draw_subsatellite_ring(cr, axes.page_x(90), axes.page_y(0), 8);
    cairo_restore(cr);

    std::vector<double> lon_ticks, lat_ticks;
    for (int l = -180; l <= 180; l += 60) lon_ticks.push_back(l);
    for (int l = -90; l <= 90; l += 30) lat_ticks.push_back(l);
    axes.draw_frame(cr, "longitude [deg]", "latitude [deg]", lon_ticks, lat_ticks);
    draw_title(cr, map_area, title);
    draw_text(cr,
              "cylindrical projection about the body's centre of mass; equator = orbital plane; "
              "ring: subsatellite point (lon 90\u00b0)",
              map_area.left, map_height_pt - 12, 0, 1, tick_font_size);
  });
}

}  // namespace tidalcrust
