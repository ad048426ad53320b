// The signal plots of `tidalcrust validate`.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "base/errors.hpp"
#include "figures/figure_output.hpp"
#include "figures/figure_style.hpp"
#include "figures/plot_axes.hpp"
#include "figures/validation_figures.hpp"

namespace tidalcrust {

PlotAxes signal_plot_axes(const std::vector<double>& time, const std::vector<double>& signal) {
  const auto [lo, hi] = std::minmax_element(signal.begin(), signal.end());
  const double margin = 0.06 * std::max(*hi - *lo, 1e-300);
  return PlotAxes(PageRect{84, 48, 520, 280}, time.front(), time.back(), *lo - margin, *hi + margin);
}

std::vector<std::filesystem::path> write_signal_plot(const std::vector<double>& time, const std::vector<double>& signal,
                                                     const std::vector<TimeMark>& marks, const std::filesystem::path& stem,
                                                     const std::string& title, const std::string& y_label) {
  if (time.size() != signal.size() || time.size() < 2)
    throw InputError(stem.string() + ": a signal plot needs equally many times and values, at least two");
  const PlotAxes axes = signal_plot_axes(time, signal);
  const PageRect& area = axes.area();
  return write_figure(stem, 640, 380, [&](cairo_t* cr) {
    cairo_save(cr);
    axes.clip(cr);
    int labelled = 0;  // labels step down the plot one line each, so that close marks stay legible
    for (const auto& mark : marks) {
      cairo_save(cr);
      if (mark.measured) {
        set_color(cr, tick_marker_color);
      } else {
        const double dashes[] = {4, 3};
        cairo_set_dash(cr, dashes, 2, 0);
        cairo_set_source_rgb(cr, 0.45, 0.45, 0.45);
      }
      cairo_set_line_width(cr, 0.9);
      cairo_move_to(cr, axes.page_x(mark.time), area.top);
      cairo_line_to(cr, axes.page_x(mark.time), area.bottom());
      cairo_stroke(cr);
      // Theory labels from the top down, measured ones from the bottom up.
      if (!mark.label.empty()) {
        const double step = 12.0 * labelled++;
        draw_text(cr, mark.label, axes.page_x(mark.time) + 3,
                  mark.measured ? area.bottom() - 4 - step : area.top + 4 + step, 0, mark.measured ? 1 : 0,
                  tick_font_size);
      }
      cairo_restore(cr);
    }
    axes.path(cr, time, signal);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.2);
    cairo_stroke(cr);
    cairo_restore(cr);
    axes.draw_frame(cr, "t [t_grav]", y_label);
    draw_title(cr, area, title);
  });
}

std::vector<std::filesystem::path> write_tidal_strain_plot(const std::vector<TidalStrainBin>& bins, double h2, double l2,
                                                           const std::filesystem::path& stem, const std::string& title) {
  if (bins.empty()) throw InputError(stem.string() + ": a strain plot needs at least one band");
  std::vector<double> gamma, meridional, azimuthal;
  for (int i = 0; i <= 90; ++i) {
    const SurfaceStrain e = continuum_surface_strain(h2, l2, i * std::numbers::pi / 180);
    gamma.push_back(i);
    meridional.push_back(e.meridional);
    azimuthal.push_back(e.azimuthal);
  }
  double lo = std::min(*std::min_element(meridional.begin(), meridional.end()),
                       *std::min_element(azimuthal.begin(), azimuthal.end()));
  double hi = std::max(*std::max_element(meridional.begin(), meridional.end()),
                       *std::max_element(azimuthal.begin(), azimuthal.end()));
  for (const auto& b : bins) {
    lo = std::min({lo, b.measured_meridional, b.measured_azimuthal});
    hi = std::max({hi, b.measured_meridional, b.measured_azimuthal});
  }
  const double margin = 0.06 * std::max(hi - lo, 1e-300);
  const PlotAxes axes(PageRect{84, 48, 520, 280}, 0, 90, lo - margin, hi + margin);
  const Rgb red{0.85, 0.0, 0.0}, blue{0.0, 0.25, 0.8};
  return write_figure(stem, 640, 380, [&](cairo_t* cr) {
    cairo_save(cr);
    axes.clip(cr);
    cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
    cairo_set_line_width(cr, 0.6);
    cairo_move_to(cr, axes.page_x(0), axes.page_y(0));
    cairo_line_to(cr, axes.page_x(90), axes.page_y(0));
    cairo_stroke(cr);
    for (const auto& [curve, color] : {std::pair{&meridional, red}, std::pair{&azimuthal, blue}}) {
      axes.path(cr, gamma, *curve);
      set_color(cr, color);
      cairo_set_line_width(cr, 1.2);
      cairo_stroke(cr);
    }
    for (const auto& b : bins) {
      const double x = axes.page_x(0.5 * (b.gamma_low + b.gamma_high));
      for (const auto& [value, color] : {std::pair{b.measured_meridional, red}, std::pair{b.measured_azimuthal, blue}}) {
        cairo_arc(cr, x, axes.page_y(value), 3.2, 0, 2 * std::numbers::pi);
        set_color(cr, color);
        cairo_fill(cr);
      }
    }
    cairo_restore(cr);
    set_color(cr, red);
    draw_text(cr, "meridional eps_psipsi", axes.area().right() - 6, axes.area().top + 6, 1, 0, tick_font_size);
    set_color(cr, blue);
    draw_text(cr, "azimuthal eps_lamlam", axes.area().right() - 6, axes.area().top + 18, 1, 0, tick_font_size);
    cairo_set_source_rgb(cr, 0, 0, 0);
    draw_text(cr, "lines: continuum (TS72), points: crust springs", axes.area().right() - 6, axes.area().top + 30, 1, 0,
              tick_font_size);
    axes.draw_frame(cr, "angle from the tidal axis gamma [deg]", "strain per unit tidal strength");
    draw_title(cr, axes.area(), title);
  });
}

}  // namespace tidalcrust
