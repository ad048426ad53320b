// Figure 8 (fig:lat): fractures in cylindrical projection.
#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "base/errors.hpp"

#include "figures/figure_output.hpp"
#include "figures/figure_style.hpp"
#include "figures/figures.hpp"
#include "physics/orbital_frame.hpp"

namespace tidalcrust {

namespace {
constexpr double map_width_pt = 720, map_height_pt = 420;
constexpr PageRect map_area{62, 40, 640, 320};
/// write_fracture_map_row: panels of half the size, room for the latitude labels between them,
/// for the figure's title and each panel's one-line title above, the axis labels and caption below.
constexpr PageRect map_row_panel{0, 80, 320, 160};
constexpr double map_row_side = 62, map_row_gap = 70, map_row_below = 58;
constexpr const char* map_caption =
    "cylindrical projection about the centre of mass, longitude stretched by 1/cos(lat); "
    "equator = orbital plane; ring: subsatellite point (90\u00b0)";

constexpr double max_map_step_deg = 3;  ///< largest longitude or latitude step between two drawn points
constexpr int max_subdivisions = 40;     ///< halvings of the segment before a step counts as a pole passage

/// Wraps a longitude difference into (-180, 180].
double wrap_deg(double d) {
  while (d > 180) d -= 360;
  while (d <= -180) d += 360;
  return d;
}

struct MapPoint {
  double lon, lat;
};

MapPoint map_point(const Vec3& p) { return {longitude_deg(p), latitude_deg(p)}; }

/// Appends the map points of from + s (to - from) for s in (s0, s1], halving the interval until
/// each step spans at most max_map_step_deg in longitude and latitude (or cannot be halved any
/// more: the segment passes over a pole there).
void sample_segment(const Vec3& from, const Vec3& to, double s0, MapPoint p0, double s1, MapPoint p1, int depth,
                    std::vector<MapPoint>& out) {
  if ((std::abs(wrap_deg(p1.lon - p0.lon)) <= max_map_step_deg && std::abs(p1.lat - p0.lat) <= max_map_step_deg) ||
      depth >= max_subdivisions) {
    out.push_back(p1);
    return;
  }
  const double s = 0.5 * (s0 + s1);
  const MapPoint middle = map_point(from + (to - from) * s);
  sample_segment(from, to, s0, p0, s, middle, depth + 1, out);
  sample_segment(from, to, s, middle, s1, p1, depth + 1, out);
}
}  // namespace

std::vector<MapPolyline> map_segment_pieces(const Vec3& from, const Vec3& to) {
  std::vector<MapPoint> points{map_point(from)};
  sample_segment(from, to, 0, points.front(), 1, map_point(to), 0, points);

  std::vector<MapPolyline> pieces(1);
  auto add = [&](double lon, double lat) {
    pieces.back().longitude_deg.push_back(lon);
    pieces.back().latitude_deg.push_back(lat);
  };
  add(points.front().lon, points.front().lat);
  for (std::size_t i = 1; i < points.size(); ++i) {
    const MapPoint& p = points[i - 1];
    const MapPoint& q = points[i];
    const double step = wrap_deg(q.lon - p.lon);
    if (std::abs(step) > max_map_step_deg) {
      // Over a pole the longitude jumps: the cylindrical map stretches that point into its whole
      // top or bottom edge, so the line is broken there rather than drawn along the edge.
      pieces.emplace_back();
    } else if (const double unwrapped = p.lon + step; unwrapped > 180 || unwrapped < -180) {
      // Across the seam: end on it and continue from the other side at the same latitude.
      const double seam = unwrapped > 180 ? 180 : -180;
      const double lat = p.lat + (seam - p.lon) / step * (q.lat - p.lat);
      add(seam, lat);
      pieces.emplace_back();
      add(-seam, lat);
    }
    add(q.lon, q.lat);
  }
  std::erase_if(pieces, [](const MapPolyline& piece) { return piece.longitude_deg.size() < 2; });
  return pieces;
}

namespace {
/// One half-bar centroid -> edge midpoint (map_segment_pieces).
void draw_bar(cairo_t* cr, const PlotAxes& axes, const Vec3& from, const Vec3& to) {
  for (const MapPolyline& piece : map_segment_pieces(from, to)) {
    axes.path(cr, piece.longitude_deg, piece.latitude_deg);
    cairo_stroke(cr);
  }
}
}  // namespace

PlotAxes fracture_map_axes() { return PlotAxes(map_area, -180, 180, -90, 90); }

void draw_fracture_map(cairo_t* cr, const PlotAxes& axes, const FractureSummary& fractures) {
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
}

FigureFiles write_fracture_map(const FractureSummary& fractures, const std::filesystem::path& stem,
                               const std::string& title) {
  const PlotAxes axes = fracture_map_axes();
  return write_figure(stem, map_width_pt, map_height_pt, [&](cairo_t* cr) {
    draw_fracture_map(cr, axes, fractures);
    draw_title(cr, map_area, title);
    draw_text(cr, map_caption, map_area.left, map_height_pt - 12, 0, 1, tick_font_size);
  });
}

PlotAxes fracture_map_row_axes(std::size_t index) {
  const double left = map_row_side + static_cast<double>(index) * (map_row_panel.width + map_row_gap);
  return PlotAxes({left, map_row_panel.top, map_row_panel.width, map_row_panel.height}, -180, 180, -90, 90);
}

FigureFiles write_fracture_map_row(const std::vector<const FractureSummary*>& panels,
                                   const std::vector<std::string>& panel_titles, const std::filesystem::path& stem,
                                   const std::string& title) {
  if (panels.empty() || panel_titles.size() != panels.size())
    throw InputError(fmt::format("{}: {} fracture maps with {} titles to draw", stem.string(), panels.size(),
                                 panel_titles.size()));
  const double n = static_cast<double>(panels.size());
  const double width = 2 * map_row_side + n * map_row_panel.width + (n - 1) * map_row_gap;
  const double height = map_row_panel.bottom() + map_row_below;
  return write_figure(stem, width, height, [&](cairo_t* cr) {
    for (std::size_t i = 0; i < panels.size(); ++i) {
      const PlotAxes axes = fracture_map_row_axes(i);
      draw_fracture_map(cr, axes, *panels[i]);
      draw_title(cr, axes.area(), panel_titles[i]);
    }
    draw_title(cr, {0, map_row_panel.top - title_font_size - 14, width, 0}, title);
    draw_text(cr, map_caption, map_row_side, height - 12, 0, 1, tick_font_size);
  });
}

}  // namespace tidalcrust
