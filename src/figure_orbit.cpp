// Figure 7 (fig:orbit): the perturber's path relative to the body in the orbital plane.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "figure_output.hpp"
#include "figure_style.hpp"
#include "figures.hpp"
#include "orbital_frame.hpp"
#include "two_body_orbit.hpp"

namespace tidalcrust {

namespace {
constexpr double figure_width_pt = 480, figure_height_pt = 520;
constexpr PageRect plot_area{64, 44, 396, 380};
constexpr double tick_interval = 0.1;  ///< t_grav between red diamonds (as in the paper)

void circle(cairo_t* cr, double x, double y, double radius) {
  cairo_new_sub_path(cr);
  cairo_arc(cr, x, y, radius, 0, 2 * std::numbers::pi);
}

void diamond(cairo_t* cr, double x, double y, double half) {
  cairo_move_to(cr, x, y - half);
  cairo_line_to(cr, x + half, y);
  cairo_line_to(cr, x, y + half);
  cairo_line_to(cr, x - half, y);
  cairo_close_path(cr);
}

void arrow(cairo_t* cr, double x0, double y0, double x1, double y1) {
  const double angle = std::atan2(y1 - y0, x1 - x0), head = 7;
  cairo_move_to(cr, x0, y0);
  cairo_line_to(cr, x1, y1);
  cairo_stroke(cr);
  cairo_move_to(cr, x1, y1);
  cairo_line_to(cr, x1 - head * std::cos(angle - 0.4), y1 - head * std::sin(angle - 0.4));
  cairo_line_to(cr, x1 - head * std::cos(angle + 0.4), y1 - head * std::sin(angle + 0.4));
  cairo_close_path(cr);
  cairo_fill(cr);
}
}  // namespace

double stage_start_time(const Checkpoint& checkpoint) {
  const State& s = checkpoint.state;
  return s.time - static_cast<double>(s.step - checkpoint.stage.start_step) * s.dt;
}

FigureFiles write_orbit_plot(const Checkpoint& checkpoint, const RecordedEncounter& encounter,
                             const std::vector<double>& snapshot_times, const std::filesystem::path& stem,
                             const std::string& title) {
  double t_start = stage_start_time(checkpoint), t_end = checkpoint.state.time;
  if (!(t_end > t_start)) t_start = encounter.pericenter_time - 1.5, t_end = encounter.pericenter_time + 1.5;

  constexpr int track_points = 600;
  std::vector<double> track_times(track_points + 1);
  for (int i = 0; i <= track_points; ++i)
    track_times[i] = t_start + (t_end - t_start) * static_cast<double>(i) / track_points;
  std::vector<double> tick_times;
  const auto ticks = static_cast<long>(std::floor((t_end - t_start) / tick_interval + 1e-9));
  for (long k = 0; k <= ticks; ++k) tick_times.push_back(t_start + static_cast<double>(k) * tick_interval);
  const double m2 = encounter.perturber_mass, tq = encounter.pericenter_time;
  const TwoBodyOrbit orbit = perturber_orbit(m2, encounter.pericenter, encounter.pericenter_speed);
  auto positions = [&](const std::vector<double>& times) {
    std::vector<Vec3> out;
    for (const double t : times) out.push_back(orbit.state_at_time(t - tq).position);
    return out;
  };
  const auto track = positions(track_times);
  const auto tick_positions = positions(tick_times);
  const auto snapshot_positions = positions(snapshot_times);
  const auto near_pericenter = positions({tq, tq + 0.02});

  const bool stored = checkpoint.state.perturber.present;
  const Vec3 stored_position =
      Vec3(checkpoint.state.perturber.position[0], checkpoint.state.perturber.position[1],
           checkpoint.state.perturber.position[2]) -
      body_center_of_mass(checkpoint.body, checkpoint.state);

  // Equal scales on both axes; the body disc, the whole track, the snapshot discs and the
  // direction arrow in view.
  const double snapshot_radius = std::cbrt(m2);
  double x_lo = -1.2, x_hi = 1.2, y_lo = -1.2, y_hi = 1.2;
  auto include = [&](const Vec3& p, double margin) {
    x_lo = std::min(x_lo, p.x() - margin), x_hi = std::max(x_hi, p.x() + margin);
    y_lo = std::min(y_lo, p.y() - margin), y_hi = std::max(y_hi, p.y() + margin);
  };
  for (const Vec3& p : track) include(p, 0.15);
  for (const Vec3& p : snapshot_positions) include(p, snapshot_radius + 0.1);
  include(near_pericenter[0], 0.5);
  if (checkpoint.state.perturber.present) include(stored_position, 0.15);
  const double half = 0.52 * std::max((x_hi - x_lo) * plot_area.height / plot_area.width, y_hi - y_lo);
  const double xc = 0.5 * (x_lo + x_hi), yc = 0.5 * (y_lo + y_hi);
  const double half_x = half * plot_area.width / plot_area.height;
  const PlotAxes axes(plot_area, xc - half_x, xc + half_x, yc - half, yc + half);
  const double scale = plot_area.height / (2 * half);  // points per R

  return write_figure(stem, figure_width_pt, figure_height_pt, [&](cairo_t* cr) {
    cairo_save(cr);
    axes.clip(cr);
    // Body: black disc of radius R at its centre of mass.
    circle(cr, axes.page_x(0), axes.page_y(0), scale);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_fill(cr);
    std::vector<double> xs, ys;
    for (const Vec3& p : track) xs.push_back(p.x()), ys.push_back(p.y());
    axes.path(cr, xs, ys);
    cairo_set_line_width(cr, 1.0);
    cairo_stroke(cr);
    set_color(cr, tick_marker_color);
    for (const Vec3& p : tick_positions) diamond(cr, axes.page_x(p.x()), axes.page_y(p.y()), 3.2);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 0.9);
    for (const Vec3& p : snapshot_positions) {
      circle(cr, axes.page_x(p.x()), axes.page_y(p.y()), snapshot_radius * scale);
      cairo_stroke(cr);
    }
    // Direction of motion, drawn just outside the pericenter.
    const Vec3 along = (near_pericenter[1] - near_pericenter[0]).normalized();
    const Vec3 outward = near_pericenter[0].normalized() * 0.3;
    const Vec3 a0 = near_pericenter[0] + outward - 0.35 * along, a1 = near_pericenter[0] + outward + 0.35 * along;
    set_color(cr, tick_marker_color);
    cairo_set_line_width(cr, 1.6);
    arrow(cr, axes.page_x(a0.x()), axes.page_y(a0.y()), axes.page_x(a1.x()), axes.page_y(a1.y()));
    if (stored) {
      const double px = axes.page_x(stored_position.x()), py = axes.page_y(stored_position.y());
      cairo_set_source_rgb(cr, 0.0, 0.3, 0.9);
      cairo_set_line_width(cr, 1.4);
      cairo_move_to(cr, px - 4, py - 4);
      cairo_line_to(cr, px + 4, py + 4);
      cairo_move_to(cr, px - 4, py + 4);
      cairo_line_to(cr, px + 4, py - 4);
      cairo_stroke(cr);
    }
    cairo_restore(cr);

    // Legend below the axes, two columns.
    const double row0 = plot_area.bottom() + 44, row1 = row0 + 16;
    const double col0 = plot_area.left + 10, col1 = plot_area.left + 0.5 * plot_area.width + 10;
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.0);
    cairo_move_to(cr, col0 - 7, row0);
    cairo_line_to(cr, col0 + 7, row0);
    cairo_stroke(cr);
    draw_text(cr, "two-body track (q, V_q, M\u2082)", col0 + 12, row0, 0, 0.5, tick_font_size);
    set_color(cr, tick_marker_color);
    diamond(cr, col1, row0, 3.2);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    draw_text(cr, fmt::format("every {} t_grav from the stage start", tick_interval), col1 + 12, row0, 0, 0.5,
              tick_font_size);
    circle(cr, col0, row1, 5);
    cairo_stroke(cr);
    draw_text(cr, "snapshots (radius M\u2082^(1/3) R)", col0 + 12, row1, 0, 0.5, tick_font_size);
    cairo_set_source_rgb(cr, 0.0, 0.3, 0.9);
    cairo_set_line_width(cr, 1.4);
    cairo_move_to(cr, col1 - 4, row1 - 4);
    cairo_line_to(cr, col1 + 4, row1 + 4);
    cairo_move_to(cr, col1 - 4, row1 + 4);
    cairo_line_to(cr, col1 + 4, row1 - 4);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    draw_text(cr, fmt::format("stored position, t \u2212 t_peri = {:+.2f}", checkpoint.state.time - tq), col1 + 12,
              row1, 0, 0.5, tick_font_size);

    axes.draw_frame(cr, "x [R]", "y [R]");
    draw_title(cr, plot_area, title);
    draw_text(cr, "relative to the body's centre of mass (black disc, radius R); pericenter on +y",
              plot_area.left, figure_height_pt - 10, 0, 1, tick_font_size);
  });
}

}  // namespace tidalcrust
