// Figure 7 (fig:orbit): the perturber's path relative to the body in the orbital plane.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "figures/figure_output.hpp"
#include "figures/figure_style.hpp"
#include "figures/figure_text.hpp"
#include "figures/figures.hpp"
#include "physics/orbital_frame.hpp"
#include "analysis/recorded_track.hpp"
#include "physics/two_body_orbit.hpp"

namespace tidalcrust {

namespace {
constexpr double figure_width_pt = 480, figure_height_pt = 540;
constexpr PageRect plot_area{64, 44, 396, 380};
constexpr double tick_interval = 0.1;  ///< t_grav between red diamonds (as in the paper)
/// At most this many diamonds: over a longer track (extreme or corrupt records) the interval
/// grows to a whole multiple of tick_interval, so the drawing time never depends on the values.
constexpr double max_ticks = 400;

constexpr Rgb analytic_track_color{0.55, 0.55, 0.55};  ///< thin grey dashed reference line
constexpr double analytic_dash[] = {4.0, 3.0};          ///< points on, off

/// Everything the orbit figure places in the orbital plane, R relative to the body's centre of
/// mass: the simulated track (the samples' perturber_offset) when the checkpoint has one,
/// otherwise the analytic two-body track; the analytic track as a reference.
struct OrbitPlotContent {
  bool simulated = false;                       ///< track from the timeseries, not analytic
  std::vector<Vec3> track;                      ///< drawn solid
  std::vector<Vec3> analytic_track;             ///< drawn thin grey dashed when simulated
  double max_deviation = 0;                     ///< max |simulated - analytic| over the samples
  std::vector<Vec3> tick_positions;             ///< every tick_every from the stage start
  double tick_every = tick_interval;            ///< t_grav between diamonds (>= tick_interval)
  std::vector<Vec3> snapshot_positions;
  Vec3 pericenter = Vec3::Zero();               ///< closest point of the track
  Vec3 direction = Vec3::UnitX();               ///< direction of motion there
  bool stored = false;                          ///< the checkpoint holds a perturber
  Vec3 stored_position = Vec3::Zero();
  double snapshot_radius = 0;                   ///< M2^(1/3) R
};

OrbitPlotContent orbit_plot_content(const Checkpoint& checkpoint, const EncounterRecord& record,
                                    const std::vector<double>& snapshot_times) {
  double t_start = checkpoint.stage.clock.start_time, t_end = checkpoint.state.time;
  if (!(t_end > t_start)) t_start = record.pericenter_time - 1.5, t_end = record.pericenter_time + 1.5;
  const double m2 = record.encounter.perturber_mass, tq = record.pericenter_time;
  const TwoBodyOrbit orbit = perturber_orbit(m2, record.encounter.pericenter, record.encounter.pericenter_speed);
  auto analytic = [&](double t) { return orbit.state_at_time(t - tq).position; };
  const RecordedTrack recorded(checkpoint.observables.timeseries);

  OrbitPlotContent content;
  content.simulated = !recorded.empty();
  content.snapshot_radius = std::cbrt(m2);
  constexpr int track_points = 600;
  for (int i = 0; i <= track_points; ++i)
    content.analytic_track.push_back(analytic(t_start + (t_end - t_start) * static_cast<double>(i) / track_points));
  // Where the figure puts the perturber at time t: on the simulated track where it was sampled.
  auto position = [&](double t) { return recorded.covers(t) ? recorded.position_at(t) : analytic(t); };
  const double span = t_end - t_start;
  const double interval =
      span / tick_interval > max_ticks ? tick_interval * std::ceil(span / (tick_interval * max_ticks)) : tick_interval;
  const double tick_count = std::isfinite(span / interval) ? std::floor(span / interval + 1e-9) : 0;
  const auto ticks = static_cast<long>(std::clamp(tick_count, 0.0, max_ticks));
  content.tick_every = interval;
  for (long k = 0; k <= ticks; ++k) {
    const double t = t_start + static_cast<double>(k) * interval;
    if (!content.simulated || recorded.covers(t)) content.tick_positions.push_back(position(t));
  }
  for (const double t : snapshot_times) content.snapshot_positions.push_back(position(t));

  if (content.simulated) {
    content.track = recorded.positions();
    const auto& times = recorded.times();
    std::size_t nearest = 0;
    for (std::size_t i = 0; i < times.size(); ++i) {
      content.max_deviation = std::max(content.max_deviation, (content.track[i] - analytic(times[i])).norm());
      if (content.track[i].norm() < content.track[nearest].norm()) nearest = i;
    }
    content.pericenter = content.track[nearest];
    const std::size_t before = nearest > 0 ? nearest - 1 : nearest;
    const std::size_t after = nearest + 1 < times.size() ? nearest + 1 : nearest;
    if (after > before) content.direction = (content.track[after] - content.track[before]).normalized();
  } else {
    content.track = content.analytic_track;
    content.pericenter = analytic(tq);
    content.direction = (analytic(tq + 0.02) - content.pericenter).normalized();
  }

  content.stored = checkpoint.state.perturber.present;
  const auto& p = checkpoint.state.perturber.position;
  content.stored_position = Vec3(p[0], p[1], p[2]) - body_center_of_mass(checkpoint.body, checkpoint.state);
  return content;
}

/// Equal scales on both axes; the body disc, both tracks, the snapshot discs and the direction
/// arrow in view.
PlotAxes orbit_axes(const OrbitPlotContent& content) {
  double x_lo = -1.2, x_hi = 1.2, y_lo = -1.2, y_hi = 1.2;
  auto include = [&](const Vec3& p, double margin) {
    x_lo = std::min(x_lo, p.x() - margin), x_hi = std::max(x_hi, p.x() + margin);
    y_lo = std::min(y_lo, p.y() - margin), y_hi = std::max(y_hi, p.y() + margin);
  };
  for (const Vec3& p : content.track) include(p, 0.15);
  for (const Vec3& p : content.analytic_track) include(p, 0.15);
  for (const Vec3& p : content.snapshot_positions) include(p, content.snapshot_radius + 0.1);
  include(content.pericenter, 0.5);
  if (content.stored) include(content.stored_position, 0.15);
  const double half = 0.52 * std::max((x_hi - x_lo) * plot_area.height / plot_area.width, y_hi - y_lo);
  const double xc = 0.5 * (x_lo + x_hi), yc = 0.5 * (y_lo + y_hi);
  const double half_x = half * plot_area.width / plot_area.height;
  return PlotAxes(plot_area, xc - half_x, xc + half_x, yc - half, yc + half);
}

void polyline(cairo_t* cr, const PlotAxes& axes, const std::vector<Vec3>& points) {
  std::vector<double> xs, ys;
  for (const Vec3& p : points) xs.push_back(p.x()), ys.push_back(p.y());
  axes.path(cr, xs, ys);
}

void cross(cairo_t* cr, double x, double y) {
  cairo_move_to(cr, x - 4, y - 4);
  cairo_line_to(cr, x + 4, y + 4);
  cairo_move_to(cr, x - 4, y + 4);
  cairo_line_to(cr, x + 4, y - 4);
}

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

PlotAxes orbit_plot_axes(const Checkpoint& checkpoint, const EncounterRecord& record,
                         const std::vector<double>& snapshot_times) {
  return orbit_axes(orbit_plot_content(checkpoint, record, snapshot_times));
}

FigureFiles write_orbit_plot(const Checkpoint& checkpoint, const EncounterRecord& record,
                             const std::vector<double>& snapshot_times, const std::filesystem::path& stem,
                             const std::string& title) {
  const OrbitPlotContent content = orbit_plot_content(checkpoint, record, snapshot_times);
  const PlotAxes axes = orbit_axes(content);
  const double scale = plot_area.height / (axes.y_max() - axes.y_min());  // points per R
  const double tq = record.pericenter_time;

  auto analytic_line_style = [](cairo_t* cr) {
    set_color(cr, analytic_track_color);
    cairo_set_line_width(cr, 0.8);
    cairo_set_dash(cr, analytic_dash, 2, 0);
  };
  auto track_line_style = [](cairo_t* cr) {
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.0);
    cairo_set_dash(cr, nullptr, 0, 0);
  };

  return write_figure(stem, figure_width_pt, figure_height_pt, [&](cairo_t* cr) {
    cairo_save(cr);
    axes.clip(cr);
    // Body: black disc of radius R at its centre of mass.
    circle(cr, axes.page_x(0), axes.page_y(0), scale);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_fill(cr);
    if (content.simulated) {
      polyline(cr, axes, content.analytic_track);
      analytic_line_style(cr);
      cairo_stroke(cr);
    }
    polyline(cr, axes, content.track);
    track_line_style(cr);
    cairo_stroke(cr);
    set_color(cr, tick_marker_color);
    for (const Vec3& p : content.tick_positions) diamond(cr, axes.page_x(p.x()), axes.page_y(p.y()), 3.2);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 0.9);
    for (const Vec3& p : content.snapshot_positions) {
      circle(cr, axes.page_x(p.x()), axes.page_y(p.y()), content.snapshot_radius * scale);
      cairo_stroke(cr);
    }
    // Direction of motion, drawn just outside the pericenter.
    const Vec3 outward = content.pericenter.normalized() * 0.3;
    const Vec3 a0 = content.pericenter + outward - 0.35 * content.direction;
    const Vec3 a1 = content.pericenter + outward + 0.35 * content.direction;
    set_color(cr, tick_marker_color);
    cairo_set_line_width(cr, 1.6);
    arrow(cr, axes.page_x(a0.x()), axes.page_y(a0.y()), axes.page_x(a1.x()), axes.page_y(a1.y()));
    if (content.stored) {
      cairo_set_source_rgb(cr, 0.0, 0.3, 0.9);
      cairo_set_line_width(cr, 1.4);
      cross(cr, axes.page_x(content.stored_position.x()), axes.page_y(content.stored_position.y()));
      cairo_stroke(cr);
    }
    cairo_restore(cr);

    // Legend below the axes, two columns.
    const double row0 = plot_area.bottom() + 44, row1 = row0 + 16, row2 = row1 + 16;
    const double col0 = plot_area.left + 10, col1 = plot_area.left + 0.5 * plot_area.width + 10;
    auto legend_line = [&](double row) {
      cairo_move_to(cr, col0 - 7, row);
      cairo_line_to(cr, col0 + 7, row);
      cairo_stroke(cr);
    };
    track_line_style(cr);
    legend_line(row0);
    draw_text(cr,
              content.simulated ? fmt::format("simulated (max {} R from analytic)", fixed_text(content.max_deviation, 3))
                                : "two-body track (analytic; q, V_q, M\u2082)",
              col0 + 12, row0, 0, 0.5, tick_font_size);
    if (content.simulated) {
      analytic_line_style(cr);
      legend_line(row1);
      track_line_style(cr);
      draw_text(cr, "two-body track (analytic)", col0 + 12, row1, 0, 0.5, tick_font_size);
    }
    set_color(cr, tick_marker_color);
    diamond(cr, col1, row0, 3.2);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    draw_text(cr, fmt::format("every {} t_grav from the stage start", general_text(content.tick_every)), col1 + 12, row0, 0, 0.5,
              tick_font_size);
    const double snapshot_row = content.simulated ? row2 : row1;
    cairo_set_line_width(cr, 0.9);
    circle(cr, col0, snapshot_row, 5);
    cairo_stroke(cr);
    draw_text(cr, "snapshots (radius M\u2082^(1/3) R)", col0 + 12, snapshot_row, 0, 0.5, tick_font_size);
    cairo_set_source_rgb(cr, 0.0, 0.3, 0.9);
    cairo_set_line_width(cr, 1.4);
    cross(cr, col1, row1);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    draw_text(cr, "stored position, " + time_from_pericenter_text(checkpoint.state.time - tq), col1 + 12,
              row1, 0, 0.5, tick_font_size);

    axes.draw_frame(cr, "x [R]", "y [R]");
    draw_title(cr, plot_area, title);
    draw_text(cr, "relative to the body's centre of mass (black disc, radius R); pericenter on +y",
              plot_area.left, figure_height_pt - 10, 0, 1, tick_font_size);
  });
}

}  // namespace tidalcrust
