// Phase diagram of a sweep (`tidalcrust report`): failed fraction over (q, V_q) for one M2 and
// eps_S, with the eq. 5 strain = eps_S line and the crack/no-crack boundary of the grid.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "base/errors.hpp"
#include "figures/figure_output.hpp"
#include "figures/figure_style.hpp"
#include "figures/figure_text.hpp"
#include "figures/figures.hpp"

namespace tidalcrust {

namespace {

constexpr double pi = 3.14159265358979323846;
constexpr double page_width = 560, page_height = 430;
constexpr double marker_radius = 6;

/// Viridis at five stops, linearly interpolated: dark for little, yellow for much.
Rgb viridis(double t) {
  static constexpr Rgb stops[] = {
      {0.267, 0.005, 0.329}, {0.229, 0.322, 0.546}, {0.128, 0.567, 0.551}, {0.369, 0.789, 0.383}, {0.993, 0.906, 0.144}};
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 4;
  const int i = std::min(3, static_cast<int>(t));
  const double f = t - i;
  Rgb c{};
  for (int k = 0; k < 3; ++k) c[k] = stops[i][k] + f * (stops[i + 1][k] - stops[i][k]);
  return c;
}

/// Top of the colour scale: the largest failed fraction, rounded up to a tick, at least 0.01.
double colour_scale_top(const std::vector<const SweepRow*>& rows) {
  double top = 0;
  for (const SweepRow* r : rows)
    if (r->status == SweepStatus::finished && std::isfinite(r->failed_fraction)) top = std::max(top, r->failed_fraction);
  const auto ticks = nice_ticks(0, std::max(top, 0.01), 5);
  return std::max(ticks.back() < top ? top : ticks.back(), 0.01);
}

/// Edges of the cells around sorted grid values: midpoints between neighbours, half a spacing
/// beyond the ends (a single value gets +-`lone` around it).
std::vector<double> cell_edges(const std::vector<double>& values, double lone) {
  std::vector<double> edges;
  if (values.size() == 1) return {values[0] - lone, values[0] + lone};
  edges.push_back(values[0] - 0.5 * (values[1] - values[0]));
  for (std::size_t i = 0; i + 1 < values.size(); ++i) edges.push_back(0.5 * (values[i] + values[i + 1]));
  edges.push_back(values.back() + 0.5 * (values.back() - values[values.size() - 2]));
  return edges;
}

}  // namespace

PlotAxes phase_diagram_axes(const std::vector<const SweepRow*>& rows, double youngs_modulus) {
  std::vector<double> q, v;
  for (const SweepRow* r : rows) q.push_back(r->encounter.pericenter), v.push_back(r->encounter.pericenter_speed);
  double q_lo = *std::min_element(q.begin(), q.end()), q_hi = *std::max_element(q.begin(), q.end());
  const auto [v_lo, v_hi] = std::minmax_element(v.begin(), v.end());
  // Wide enough to show where eq. 5 crosses strain = eps_S over the speeds of the grid, which
  // may lie far from the encounters (the impulse estimate is an order of magnitude), up to 4 q_hi.
  if (!rows.empty() && youngs_modulus > 0) {
    const auto eq5_q = [&](double speed) {
      return std::sqrt(rows[0]->encounter.perturber_mass /
                       (std::sqrt(youngs_modulus) * speed * rows[0]->failure_strain));
    };
    const double far = eq5_q(*v_lo), near = eq5_q(*v_hi);
    if (std::isfinite(far)) q_hi = std::min(std::max(q_hi, 1.03 * far), 4 * q_hi);
    if (std::isfinite(near)) q_lo = std::max(std::min(q_lo, 0.97 * near), 0.5 * q_lo);
  }
  const double q_pad = std::max(0.08 * (q_hi - q_lo), 0.05), v_pad = std::max(0.08 * (*v_hi - *v_lo), 0.05);
  return PlotAxes(PageRect{66, 58, 370, 310}, q_lo - q_pad, q_hi + q_pad, *v_lo - v_pad, *v_hi + v_pad);
}

FigureFiles write_phase_diagram(const SweepReport& report, double perturber_mass, double failure_strain,
                                const std::filesystem::path& stem, bool crack_probability) {
  std::vector<const SweepRow*> rows;
  for (const auto& r : report.rows)
    if (r.encounter.perturber_mass == perturber_mass && r.failure_strain == failure_strain) rows.push_back(&r);
  if (rows.empty())
    throw InputError(fmt::format("{}: no encounter with M2 = {} and eps_S = {}", stem.string(), perturber_mass,
                                 failure_strain));
  const PlotAxes axes = phase_diagram_axes(rows, report.youngs_modulus);
  const PageRect& area = axes.area();
  const double top = crack_probability ? 1.0 : colour_scale_top(rows);
  // Cracked: in a probability diagram, more often than not.
  const auto cracked = [&](const SweepRow* r) {
    return crack_probability ? r->status == SweepStatus::finished && r->failed_fraction >= 0.5 : r->cracked();
  };
  std::size_t finished = 0;
  for (const SweepRow* r : rows) finished += r->status == SweepStatus::finished;
  const std::string title = fmt::format(
      "{}: {}, M\u2082 = {} M, \u03b5_S = {}\n{} of {} {} finished; "
      "eq. 5 with E = E_I = {} e_g",
      report.workflow, crack_probability ? "share of ensemble members cracked" : "failed fraction of the shell springs",
      general_text(perturber_mass), general_text(failure_strain), finished, rows.size(),
      crack_probability ? "points" : "encounters", general_text(report.youngs_modulus, 3));

  return write_figure(stem, page_width, page_height, [&](cairo_t* cr) {
    cairo_save(cr);
    axes.clip(cr);
    // Crack/no-crack boundary: a cell edge between two finished neighbours of the grid, one
    // cracked and one not.
    std::set<double> q_set, v_set;
    for (const SweepRow* r : rows) q_set.insert(r->encounter.pericenter), v_set.insert(r->encounter.pericenter_speed);
    const std::vector<double> qs(q_set.begin(), q_set.end()), vs(v_set.begin(), v_set.end());
    const std::vector<double> q_edges = cell_edges(qs, 0.1), v_edges = cell_edges(vs, 0.1);
    std::map<std::pair<std::size_t, std::size_t>, const SweepRow*> grid;
    for (const SweepRow* r : rows)
      if (r->status == SweepStatus::finished)
        grid[{static_cast<std::size_t>(std::lower_bound(qs.begin(), qs.end(), r->encounter.pericenter) - qs.begin()),
              static_cast<std::size_t>(std::lower_bound(vs.begin(), vs.end(), r->encounter.pericenter_speed) -
                                       vs.begin())}] = r;
    const auto differ = [&](std::pair<std::size_t, std::size_t> a, std::pair<std::size_t, std::size_t> b) {
      const auto ia = grid.find(a), ib = grid.find(b);
      return ia != grid.end() && ib != grid.end() && cracked(ia->second) != cracked(ib->second);
    };
    for (std::size_t i = 0; i < qs.size(); ++i)
      for (std::size_t j = 0; j < vs.size(); ++j) {
        if (i + 1 < qs.size() && differ({i, j}, {i + 1, j})) {
          cairo_move_to(cr, axes.page_x(q_edges[i + 1]), axes.page_y(v_edges[j]));
          cairo_line_to(cr, axes.page_x(q_edges[i + 1]), axes.page_y(v_edges[j + 1]));
        }
        if (j + 1 < vs.size() && differ({i, j}, {i, j + 1})) {
          cairo_move_to(cr, axes.page_x(q_edges[i]), axes.page_y(v_edges[j + 1]));
          cairo_line_to(cr, axes.page_x(q_edges[i + 1]), axes.page_y(v_edges[j + 1]));
        }
      }
    const double dashes[] = {6, 3};
    cairo_set_dash(cr, dashes, 2, 0);
    cairo_set_line_width(cr, 2.2);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_SQUARE);
    set_color(cr, boundary_color);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
    // Eq. 5 strain = eps_S: V_q = M2 / (E^(1/2) q^2 eps_S).
    std::vector<double> line_q, line_v;
    for (int k = 0; k <= 200; ++k) {
      const double q = axes.x_min() + (axes.x_max() - axes.x_min()) * k / 200.0;
      line_q.push_back(q);
      line_v.push_back(perturber_mass / (std::sqrt(report.youngs_modulus) * q * q * failure_strain));
    }
    axes.path(cr, line_q, line_v);
    set_color(cr, eq5_line_color);
    cairo_set_line_width(cr, 2.4);
    cairo_stroke(cr);
    // Encounters: filled (cracked) or open (no crack) circles in the colour of the failed
    // fraction; grey crosses for those not finished.
    for (const SweepRow* r : rows) {
      const double x = axes.page_x(r->encounter.pericenter), y = axes.page_y(r->encounter.pericenter_speed);
      if (r->status != SweepStatus::finished) {
        cairo_move_to(cr, x - 4, y - 4), cairo_line_to(cr, x + 4, y + 4);
        cairo_move_to(cr, x - 4, y + 4), cairo_line_to(cr, x + 4, y - 4);
        cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
        cairo_set_line_width(cr, 1.5);
        cairo_stroke(cr);
        continue;
      }
      cairo_new_sub_path(cr);
      cairo_arc(cr, x, y, marker_radius, 0, 2 * pi);
      if (crack_probability || r->cracked()) {
        set_color(cr, viridis(r->failed_fraction / top));
        cairo_fill_preserve(cr);
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_set_line_width(cr, 0.7);
      } else {
        cairo_set_source_rgb(cr, 1, 1, 1);
        cairo_fill_preserve(cr);
        set_color(cr, viridis(0));
        cairo_set_line_width(cr, 1.8);
      }
      cairo_stroke(cr);
    }
    cairo_restore(cr);
    axes.draw_frame(cr, "pericenter q [R]", "pericenter speed V_q [\u221a(GM/R)]");
    draw_title(cr, area, title);

    // Colour bar.
    const PageRect bar{area.right() + 22, area.top, 14, area.height};
    cairo_pattern_t* gradient = cairo_pattern_create_linear(0, bar.bottom(), 0, bar.top);
    for (int k = 0; k <= 8; ++k) {
      const Rgb c = viridis(k / 8.0);
      cairo_pattern_add_color_stop_rgb(gradient, k / 8.0, c[0], c[1], c[2]);
    }
    cairo_rectangle(cr, bar.left, bar.top, bar.width, bar.height);
    cairo_set_source(cr, gradient);
    cairo_fill_preserve(cr);
    cairo_pattern_destroy(gradient);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 0.7);
    cairo_stroke(cr);
    const auto ticks = nice_ticks(0, top, 5);
    const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : top;
    for (double t : ticks) {
      if (t < 0 || t > top * (1 + 1e-9)) continue;
      const double y = bar.bottom() - t / top * bar.height;
      cairo_move_to(cr, bar.right(), y), cairo_line_to(cr, bar.right() + 3, y);
      cairo_stroke(cr);
      draw_text(cr, tick_label(t, step), bar.right() + 5, y, 0, 0.5, tick_font_size);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    draw_text(cr, crack_probability ? "crack probability" : "failed fraction", bar.left + bar.width / 2, bar.top - 6, 0.5, 1, tick_font_size);

    // Legend below the plot.
    const double y = page_height - 16;
    double x = area.left;
    const auto legend_marker = [&](bool filled) {
      cairo_new_sub_path(cr);
      cairo_arc(cr, x + 6, y - 4, 5, 0, 2 * pi);
      set_color(cr, filled ? viridis(0.7) : Rgb{1, 1, 1});
      cairo_fill_preserve(cr);
      set_color(cr, filled ? Rgb{0, 0, 0} : viridis(0));
      cairo_set_line_width(cr, filled ? 0.7 : 1.6);
      cairo_stroke(cr);
      x += 14;
    };
    const auto legend_text = [&](const std::string& text) {
      cairo_set_source_rgb(cr, 0, 0, 0);
      draw_text(cr, text, x, y, 0, 1, tick_font_size);
      x += text_width(cr, text, tick_font_size) + 14;
    };
    const auto legend_line = [&](const Rgb& colour, bool dashed) {
      cairo_save(cr);
      if (dashed) cairo_set_dash(cr, dashes, 2, 0);
      cairo_move_to(cr, x, y - 4), cairo_line_to(cr, x + 22, y - 4);
      set_color(cr, colour);
      cairo_set_line_width(cr, 2.2);
      cairo_stroke(cr);
      cairo_restore(cr);
      x += 26;
    };
    if (!crack_probability) {
      legend_marker(true);
      legend_text("cracked");
      legend_marker(false);
      legend_text("no crack");
    }
    legend_line(boundary_color, true);
    legend_text(crack_probability ? "crack probability 1/2" : "crack/no-crack boundary");
    legend_line(eq5_line_color, false);
    legend_text("eq. 5: strain = \u03b5_S");
  });
}

}  // namespace tidalcrust
