// The crack geometry of an encounter (docs/crack-geometry.md): the fracture map with the small
// circles fitted to the long cracks and their poles, and the rose of crack azimuths about the
// subsatellite point with the concentricity.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "figures/figure_output.hpp"
#include "figures/figure_style.hpp"
#include "figures/figure_text.hpp"
#include "figures/figures.hpp"
#include "physics/orbital_frame.hpp"

namespace tidalcrust {

namespace {
constexpr double figure_width_pt = 1080, figure_height_pt = 640;
constexpr PageRect map_area{62, 70, 640, 320};
constexpr double rose_center_x = 905, rose_center_y = 200, rose_radius_pt = 120;
constexpr double circle_step_deg = 2;  ///< sampling of a drawn circle along its azimuth
constexpr double degrees = 180.0 / std::numbers::pi;

/// Page angle (cairo: from +x toward +y, radians) of crack azimuth `a` (deg): 0 (toward the
/// subsatellite point) up, counter-clockwise on the page as on the sphere seen from outside.
double page_angle(double a) { return -(a + 90) / degrees; }

/// The fitted circle from `from` to `to` deg of azimuth (about its pole, from arc_start), drawn on
/// the map as chords of circle_step_deg (map_segment_pieces: seam and poles handled).
void draw_circle_part(cairo_t* cr, const PlotAxes& axes, const SmallCircleFit& fit, double from, double to) {
  const int steps = std::max(1, static_cast<int>(std::ceil((to - from) / circle_step_deg)));
  Vec3 previous = point_on_circle(fit, from);
  for (int i = 1; i <= steps; ++i) {
    const Vec3 next = point_on_circle(fit, from + (to - from) * i / steps);
    for (const MapPolyline& piece : map_segment_pieces(previous, next)) {
      axes.path(cr, piece.longitude_deg, piece.latitude_deg);
      cairo_stroke(cr);
    }
    previous = next;
  }
}

void draw_arcs(cairo_t* cr, const PlotAxes& axes, const CrackGeometry& geometry) {
  cairo_save(cr);
  axes.clip(cr);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  for (const CrackArc& arc : geometry.arcs) {
    // The whole circle thin and dashed, the arc the crack covers thick.
    const double dash[] = {4.0, 3.0};
    cairo_set_dash(cr, dash, 2, 0);
    cairo_set_line_width(cr, 0.8);
    set_color(cr, arc_color, 0.7);
    draw_circle_part(cr, axes, arc.fit, arc.fit.arc_deg, 360);
    cairo_set_dash(cr, nullptr, 0, 0);
    cairo_set_line_width(cr, 2.4);
    set_color(cr, arc_color, 0.85);
    draw_circle_part(cr, axes, arc.fit, 0, arc.fit.arc_deg);
  }
  for (std::size_t i = 0; i < geometry.arcs.size(); ++i) {
    const SmallCircleFit& fit = geometry.arcs[i].fit;
    const double x = axes.page_x(fit.pole_longitude_deg), y = axes.page_y(fit.pole_latitude_deg);
    cairo_new_sub_path(cr);
    cairo_arc(cr, x, y, 4, 0, 2 * std::numbers::pi);
    set_color(cr, arc_color);
    cairo_fill_preserve(cr);
    cairo_set_line_width(cr, 1);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_stroke(cr);
    set_color(cr, arc_color);
    draw_text(cr, std::to_string(i + 1), x + 6, y - 3, 0, 1, tick_font_size, true);
  }
  cairo_restore(cr);
}

void draw_rose(cairo_t* cr, const CrackOrientations& o) {
  const double cx = rose_center_x, cy = rose_center_y, radius = rose_radius_pt;
  cairo_save(cr);
  // Frame: the circle of the fullest bin, the axes toward the subsatellite point and concentric.
  cairo_set_line_width(cr, 0.6);
  set_color(cr, graticule_color);
  cairo_new_sub_path(cr);
  cairo_arc(cr, cx, cy, radius, 0, 2 * std::numbers::pi);
  cairo_stroke(cr);
  for (const double a : {0.0, 30.0, 60.0, 90.0, 120.0, 150.0}) {
    cairo_move_to(cr, cx + radius * std::cos(page_angle(a)), cy + radius * std::sin(page_angle(a)));
    cairo_line_to(cr, cx - radius * std::cos(page_angle(a)), cy - radius * std::sin(page_angle(a)));
  }
  cairo_stroke(cr);
  const std::int64_t fullest = *std::max_element(o.rose.begin(), o.rose.end());
  if (fullest > 0) {
    // Equal-area petals (radius ~ sqrt(count)), each bin drawn twice: the azimuth is an axis.
    const double half = 0.5 * CrackOrientations::bin_width_deg;
    for (std::size_t k = 0; k < CrackOrientations::bins; ++k) {
      if (o.rose[k] == 0) continue;
      const double r = radius * std::sqrt(static_cast<double>(o.rose[k]) / static_cast<double>(fullest));
      for (const double centre : {static_cast<double>(k) * CrackOrientations::bin_width_deg,
                                  static_cast<double>(k) * CrackOrientations::bin_width_deg + 180}) {
        cairo_move_to(cr, cx, cy);
        cairo_arc(cr, cx, cy, r, page_angle(centre + half), page_angle(centre - half));
        cairo_close_path(cr);
      }
    }
    set_color(cr, rose_color, 0.85);
    cairo_fill_preserve(cr);
    cairo_set_line_width(cr, 0.6);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_stroke(cr);
    // What azimuths uniform over [0, 180) would give in every bin.
    const double uniform = static_cast<double>(o.elements) / static_cast<double>(CrackOrientations::bins);
    const double dash[] = {3.0, 3.0};
    cairo_set_dash(cr, dash, 2, 0);
    cairo_set_line_width(cr, 1);
    cairo_new_sub_path(cr);
    cairo_arc(cr, cx, cy, radius * std::sqrt(uniform / static_cast<double>(fullest)), 0, 2 * std::numbers::pi);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
  }
  cairo_restore(cr);
  draw_text(cr, "toward the subsatellite point (radial)", cx, cy - radius - 6, 0.5, 1, tick_font_size);
  draw_text(cr, "concentric", cx - radius - 4, cy, 1, 0.5, tick_font_size);
  draw_text(cr, "concentric", cx + radius + 4, cy, 0, 0.5, tick_font_size);
  draw_title(cr, {cx - radius, cy - radius - 14, 2 * radius, 0}, "rose of crack azimuths");
}

std::string angle_text(double deg) { return std::isfinite(deg) ? fixed_text(deg, 0) + "\u00b0" : "n/a"; }

void draw_legend(cairo_t* cr, const FractureSummary& fractures) {
  const CrackGeometry& g = fractures.geometry;
  const CrackOrientations& o = g.orientations;
  // Below the rose: its numbers.
  double x = rose_center_x - rose_radius_pt, y = rose_center_y + rose_radius_pt + 34;
  auto line = [&](const std::string& text, bool bold = false) {
    draw_text(cr, text, x, y, 0, 1, tick_font_size + 1, bold);
    y += 14;
  };
  line(fmt::format("concentricity {}", std::isfinite(o.concentricity) ? fixed_text(o.concentricity, 3) : "n/a"), true);
  line(fmt::format("(uniform azimuths {}, all radial 0, rings 1)", fixed_text(random_concentricity, 3)));
  line(fmt::format("{} crack elements, rose peak at {}", o.elements, angle_text(o.rose_peak_deg)));
  line("petals equal-area; dashed: the uniform level");
  // Below the map: one line per fitted arc.
  x = map_area.left;
  y = map_area.bottom() + 96;
  line(fmt::format("{} fitted arcs (clusters of extent \u2265 {} R and \u2265 {} failed springs, longest first)",
                   g.arcs.size(), general_text(CrackGeometry::min_arc_extent), CrackGeometry::min_arc_springs),
       true);
  for (std::size_t i = 0; i < g.arcs.size(); ++i) {
    const SmallCircleFit& f = g.arcs[i].fit;
    line(fmt::format("{}: pole at ({}, {}), {} from the subsatellite axis; radius {}, arc {}, misfit {}; "
                     "crack {} R",
                     i + 1, angle_text(f.pole_longitude_deg), angle_text(f.pole_latitude_deg),
                     angle_text(f.pole_axis_from_subsatellite_deg), angle_text(f.radius_deg), angle_text(f.arc_deg),
                     std::isfinite(f.rms_misfit_deg) ? fixed_text(f.rms_misfit_deg, 1) + "\u00b0" : "n/a",
                     fixed_text(g.arcs[i].length, 2)));
  }
}
}  // namespace

PlotAxes crack_geometry_map_axes() { return PlotAxes(map_area, -180, 180, -90, 90); }

CrackRoseLayout crack_rose_layout() { return {rose_center_x, rose_center_y, rose_radius_pt}; }

FigureFiles write_crack_geometry(const FractureSummary& fractures, const std::filesystem::path& stem,
                                 const std::string& title) {
  const PlotAxes axes = crack_geometry_map_axes();
  return write_figure(stem, figure_width_pt, figure_height_pt, [&](cairo_t* cr) {
    draw_fracture_map(cr, axes, fractures);
    draw_arcs(cr, axes, fractures.geometry);
    draw_rose(cr, fractures.geometry.orientations);
    draw_legend(cr, fractures);
    draw_title(cr, {0, map_area.top - 18, figure_width_pt, 0}, title);
    draw_text(cr,
              "map: cracks (black), small circles fitted to the long cracks (blue: the arc they cover, dashed: the "
              "rest), their poles numbered; ring: subsatellite point",
              map_area.left, map_area.bottom() + 52, 0, 1, tick_font_size);
    draw_text(cr,
              "rose: azimuth of each failed spring's crack from the local direction toward the subsatellite point, "
              "counter-clockwise seen from outside",
              map_area.left, map_area.bottom() + 66, 0, 1, tick_font_size);
  });
}

}  // namespace tidalcrust
