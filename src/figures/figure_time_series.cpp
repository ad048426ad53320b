// Failures and conservation diagnostics against time from pericenter.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "figures/figure_output.hpp"
#include "figures/figure_style.hpp"
#include "figures/figures.hpp"
#include "physics/conservation.hpp"

namespace tidalcrust {

namespace {
std::pair<double, double> range_of(const std::vector<double>& v) {
  if (v.empty()) return {0, 1};
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return {*lo, *hi};
}

/// Vertical dashed line at pericenter (x = 0) if it is inside the axes.
void draw_pericenter_line(cairo_t* cr, const PlotAxes& axes, bool label) {
  if (axes.x_min() > 0 || axes.x_max() < 0) return;
  cairo_save(cr);
  const double dashes[] = {4, 3};
  cairo_set_dash(cr, dashes, 2, 0);
  cairo_set_source_rgb(cr, 0.45, 0.45, 0.45);
  cairo_set_line_width(cr, 0.8);
  cairo_move_to(cr, axes.page_x(0), axes.area().top);
  cairo_line_to(cr, axes.page_x(0), axes.area().bottom());
  cairo_stroke(cr);
  if (label) draw_text(cr, "pericenter", axes.page_x(0) + 4, axes.area().top + 4, 0, 0, tick_font_size);
  cairo_restore(cr);
}

std::string_view time_axis_label() { return "t \u2212 t_peri [t_grav]"; }
}  // namespace

FigureFiles write_failure_history(const Checkpoint& checkpoint, double pericenter_time,
                                  const std::filesystem::path& stem, const std::string& title) {
  // Cumulative count as a step function of the failure events; the sampled counts otherwise.
  std::vector<double> t, n;
  const double t_start = checkpoint.stage.clock.start_time - pericenter_time;
  const double t_end = checkpoint.state.time - pericenter_time;
  const auto& events = checkpoint.observables.failures;
  const auto& samples = checkpoint.observables.timeseries;
  const bool from_events = !events.empty() || samples.empty();
  if (from_events) {
    std::vector<double> times;
    for (const auto& e : events) times.push_back(e.time - pericenter_time);
    std::sort(times.begin(), times.end());
    t.push_back(std::min(t_start, times.empty() ? t_start : times.front()));
    n.push_back(0);
    for (std::size_t i = 0; i < times.size(); ++i) {
      t.push_back(times[i]), n.push_back(static_cast<double>(i));
      t.push_back(times[i]), n.push_back(static_cast<double>(i + 1));
    }
    t.push_back(std::max(t_end, t.back())), n.push_back(static_cast<double>(times.size()));
  } else {
    for (const auto& s : samples) t.push_back(s.time - pericenter_time), n.push_back(static_cast<double>(s.failed));
  }
  const auto [x_lo, x_hi] = range_of(t);
  const double n_max = std::max(1.0, *std::max_element(n.begin(), n.end()));
  const PageRect area{72, 40, 520, 280};
  const PlotAxes axes(area, x_lo, x_hi, 0, 1.08 * n_max);
  return write_figure(stem, 620, 370, [&](cairo_t* cr) {
    cairo_save(cr);
    axes.clip(cr);
    draw_pericenter_line(cr, axes, true);
    axes.path(cr, t, n);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.4);
    cairo_stroke(cr);
    cairo_restore(cr);
    axes.draw_frame(cr, time_axis_label(), "failed shell springs");
    draw_title(cr, area, title);
    draw_text(cr, from_events ? "cumulative failure events (/checkpoint/failures)" : "sampled counts (/checkpoint/timeseries)",
              area.left, 370 - 10, 0, 1, tick_font_size);
  });
}

FigureFiles write_conservation_plot(const Checkpoint& checkpoint, double pericenter_time,
                                    const std::filesystem::path& stem, const std::string& title) {
  const auto& samples = checkpoint.observables.timeseries;
  // The energy budget's conserved total (docs/energy-budget.md) relative to the binding energy
  // 3/5 G M^2/R; a record without the budget (NaN terms) falls back to the kinetic energy.
  const bool budget = !samples.empty() && std::isfinite(samples.front().conserved_energy());
  std::vector<double> t, energy, momentum, angular;
  if (!samples.empty()) {
    const auto& first = samples.front();
    for (const auto& s : samples) {
      t.push_back(s.time - pericenter_time);
      if (budget)
        energy.push_back((s.conserved_energy() - first.conserved_energy()) / uniform_sphere_binding_energy);
      else
        energy.push_back(first.kinetic_energy != 0 ? (s.kinetic_energy - first.kinetic_energy) / first.kinetic_energy
                                                   : s.kinetic_energy - first.kinetic_energy);
      double dp = 0, dl = 0;
      for (int k = 0; k < 3; ++k) {
        dp += (s.momentum[k] - first.momentum[k]) * (s.momentum[k] - first.momentum[k]);
        dl += (s.angular_momentum[k] - first.angular_momentum[k]) * (s.angular_momentum[k] - first.angular_momentum[k]);
      }
      momentum.push_back(std::sqrt(dp));
      angular.push_back(std::sqrt(dl));
    }
  }
  struct Panel {
    const std::vector<double>* values;
    const char* label;
  };
  const Panel panels[] = {{&energy, budget ? "(E \u2212 E\u2080)/(3/5 GM\u00b2/R)" : "(K \u2212 K\u2080)/K\u2080"},
                          {&momentum, "|P \u2212 P\u2080| [M \u221a(GM/R)]"},
                          {&angular, "|L \u2212 L\u2080| [M R \u221a(GM/R)]"}};
  const auto [x_lo, x_hi] = range_of(t);
  constexpr double panel_height = 130, panel_gap = 22, top = 40, left = 92, width = 520;
  const double height = top + 3 * panel_height + 2 * panel_gap + 58;
  return write_figure(stem, left + width + 28, height, [&](cairo_t* cr) {
    for (int p = 0; p < 3; ++p) {
      const PageRect area{left, top + p * (panel_height + panel_gap), width, panel_height};
      auto [y_lo, y_hi] = range_of(*panels[p].values);
      if (p > 0) y_lo = 0;  // magnitudes
      const double pad = 0.06 * (y_hi - y_lo);
      const PlotAxes axes(area, x_lo, x_hi, y_lo - (p > 0 ? 0 : pad), y_hi + pad);
      cairo_save(cr);
      axes.clip(cr);
      draw_pericenter_line(cr, axes, p == 0);
      axes.path(cr, t, *panels[p].values);
      cairo_set_source_rgb(cr, 0, 0, 0);
      cairo_set_line_width(cr, 1.2);
      cairo_stroke(cr);
      cairo_restore(cr);
      axes.draw_frame(cr, p == 2 ? time_axis_label() : "", panels[p].label);
      if (p == 0) draw_title(cr, area, title);
    }
    draw_text(cr,
              samples.empty() ? "no timeseries samples stored"
              : budget ? "body + perturber about the origin; E = K + U + damping and failure losses \u2212 hinge work"
                       : "body + perturber about the origin; K: kinetic energy (damping and tides change it)",
              left, height - 10, 0, 1, tick_font_size);
  });
}

}  // namespace tidalcrust
