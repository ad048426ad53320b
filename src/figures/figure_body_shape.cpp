// Figure 5 (fig:mush): slices of the body in the orbital plane, and its principal axis ratios.
#include "figures/figure_body_shape.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "base/errors.hpp"
#include "figures/figure_output.hpp"
#include "figures/figure_style.hpp"
#include "figures/figure_text.hpp"
#include "model/center_of_mass.hpp"

namespace tidalcrust {

namespace {
constexpr PanelRow panel_row{200, 12, 16, 70, 460, 30};
constexpr double view_half_width = 1.5;  ///< R from the centre of mass to the panel edge
constexpr Rgb spring_color{0.93, 0.45, 0.62};   ///< pink, as the paper's Figure 5
constexpr Rgb outline_color{0.55, 0.55, 0.55};
constexpr Rgb particle_color{0.10, 0.10, 0.18};

using Point = std::array<double, 2>;

double cross(const Point& o, const Point& a, const Point& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/// Convex hull of points in the plane, counter-clockwise (Andrew's monotone chain).
std::vector<Point> convex_hull(std::vector<Point> points) {
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  std::vector<Point> hull(2 * points.size());
  std::size_t k = 0;
  for (const Point& p : points) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

void draw_slice_panel(cairo_t* cr, const PlotAxes& axes, const Checkpoint& checkpoint, double pericenter_time) {
  const Body& body = checkpoint.body;
  const State& state = checkpoint.state;
  const Vec3 center = body_center_of_mass(body, state);
  const std::size_t n = body.particle_count();
  std::vector<Vec3> r(n);
  std::vector<Point> projected(n);
  for (std::size_t i = 0; i < n; ++i) {
    r[i] = vec3_at(state.position, i) - center;
    projected[i] = {r[i].x(), r[i].y()};
  }
  auto in_slice = [&](std::size_t i) { return std::abs(r[i].z()) < body_slice_half_width; };

  cairo_save(cr);
  axes.clip(cr);
  const std::vector<Point> hull = convex_hull(projected);
  for (std::size_t k = 0; k < hull.size(); ++k)
    (k == 0 ? cairo_move_to : cairo_line_to)(cr, axes.page_x(hull[k][0]), axes.page_y(hull[k][1]));
  cairo_close_path(cr);
  set_color(cr, outline_color, 0.15);
  cairo_fill_preserve(cr);
  set_color(cr, outline_color);
  cairo_set_line_width(cr, 1.2);
  cairo_stroke(cr);

  for (const auto& [a, b] : body.springs) {
    const auto i = static_cast<std::size_t>(a), j = static_cast<std::size_t>(b);
    if (!in_slice(i) || !in_slice(j)) continue;
    cairo_move_to(cr, axes.page_x(r[i].x()), axes.page_y(r[i].y()));
    cairo_line_to(cr, axes.page_x(r[j].x()), axes.page_y(r[j].y()));
  }
  set_color(cr, spring_color);
  cairo_set_line_width(cr, 0.7);
  cairo_stroke(cr);

  set_color(cr, particle_color);
  for (std::size_t i = 0; i < n; ++i) {
    if (!in_slice(i)) continue;
    cairo_new_sub_path(cr);
    cairo_arc(cr, axes.page_x(r[i].x()), axes.page_y(r[i].y()), 1.6, 0, 2 * std::numbers::pi);
  }
  cairo_fill(cr);

  if (state.perturber.present) {
    const Vec3 toward = (Vec3(state.perturber.position[0], state.perturber.position[1], state.perturber.position[2]) -
                         center);
    const double length = std::hypot(toward.x(), toward.y());
    if (length > 0) {
      const double ux = toward.x() / length, uy = toward.y() / length;
      const double from = 1.15, to = 1.45;
      set_color(cr, perturber_color);
      cairo_set_line_width(cr, 2.0);
      cairo_move_to(cr, axes.page_x(from * ux), axes.page_y(from * uy));
      cairo_line_to(cr, axes.page_x(to * ux), axes.page_y(to * uy));
      cairo_stroke(cr);
    }
  }
  cairo_restore(cr);

  const PageRect& area = axes.area();
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 0.8);
  cairo_rectangle(cr, area.left, area.top, area.width, area.height);
  cairo_stroke(cr);
  draw_text(cr, time_from_pericenter_text(state.time - pericenter_time), area.left + 0.5 * area.width, area.top - 5,
            0.5, 1, label_font_size);
  const PrincipalAxes shape = principal_axes(body.mass, state.position);
  draw_text(cr, fmt::format("b/a = {:.3f}, c/a = {:.3f}", shape.b_over_a(), shape.c_over_a()), area.left + 6,
            area.bottom() - 6, 0, 1, tick_font_size);
}
}  // namespace

PlotAxes body_slice_panel_axes(std::size_t index, std::size_t panel_count) {
  return panel_row.axes(index, panel_count, view_half_width);
}

std::vector<std::filesystem::path> write_body_slices(const std::vector<const Checkpoint*>& snapshots,
                                                     double pericenter_time, const std::filesystem::path& stem,
                                                     const std::string& title) {
  return panel_row.write(
      stem, snapshots.size(), view_half_width, title,
      [&](cairo_t* cr, const PlotAxes& axes, std::size_t i) { draw_slice_panel(cr, axes, *snapshots[i], pericenter_time); },
      [](cairo_t* cr, double width, double height) {
        draw_text(cr,
                  fmt::format("orbital plane seen from +z (+x right, subsatellite +y up); particles and springs with "
                              "|z| < {} R; grey: outline of the whole body; magenta: toward the perturber",
                              body_slice_half_width),
                  0.5 * width, height - 8, 0.5, 1, tick_font_size);
      });
}

PlotAxes axis_ratio_axes(const std::vector<double>& time_from_pericenter, const std::vector<PrincipalAxes>& axes) {
  double t_lo = 0, t_hi = 1, lowest = 1;
  if (!time_from_pericenter.empty()) {
    const auto [lo, hi] = std::minmax_element(time_from_pericenter.begin(), time_from_pericenter.end());
    t_lo = *lo, t_hi = *hi;
  }
  for (const auto& a : axes) lowest = std::min({lowest, a.b_over_a(), a.c_over_a()});
  const double margin = 0.05 * std::max(t_hi - t_lo, 1e-6);
  return PlotAxes({72, 40, 520, 260}, t_lo - margin, t_hi + margin, std::max(0.0, lowest - 0.1 * (1 - lowest) - 0.01),
                  1.005);
}

std::vector<std::filesystem::path> write_axis_ratios(const std::vector<double>& time_from_pericenter,
                                                     const std::vector<PrincipalAxes>& axes,
                                                     const std::filesystem::path& stem, const std::string& title) {
  if (axes.size() != time_from_pericenter.size() || axes.empty())
    throw InputError(fmt::format("{}: {} times but {} shapes to draw", stem.string(), time_from_pericenter.size(),
                                 axes.size()));
  std::vector<double> ba, ca;
  for (const auto& a : axes) ba.push_back(a.b_over_a()), ca.push_back(a.c_over_a());
  const PlotAxes plot = axis_ratio_axes(time_from_pericenter, axes);
  return write_figure(stem, 620, 350, [&](cairo_t* cr) {
    cairo_save(cr);
    plot.clip(cr);
    for (const auto* ratio : {&ba, &ca}) {
      cairo_save(cr);
      if (ratio == &ca) {
        const double dashes[] = {5, 3};
        cairo_set_dash(cr, dashes, 2, 0);
      }
      plot.path(cr, time_from_pericenter, *ratio);
      cairo_set_source_rgb(cr, 0, 0, 0);
      cairo_set_line_width(cr, 1.4);
      cairo_stroke(cr);
      cairo_restore(cr);
      for (std::size_t k = 0; k < ratio->size(); ++k) {
        cairo_new_sub_path(cr);
        cairo_arc(cr, plot.page_x(time_from_pericenter[k]), plot.page_y((*ratio)[k]), 2.5, 0, 2 * std::numbers::pi);
      }
      cairo_fill(cr);
    }
    cairo_restore(cr);
    plot.draw_frame(cr, "t \u2212 t_peri [t_grav]", "principal axis ratio");
    draw_title(cr, plot.area(), title);
    draw_text(cr, "solid: b/a, dashed: c/a (axes of the ellipsoid with the body's second moments)", plot.area().left,
              350 - 10, 0, 1, tick_font_size);
  });
}

}  // namespace tidalcrust
