// The signal plots of `tidalcrust validate`.
#include <algorithm>

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

}  // namespace tidalcrust
