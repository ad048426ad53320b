#pragma once
// Minimal 2-D plotting on cairo for the paper-style figures: a data-to-page mapping inside a
// rectangle, a frame with "nice" ticks, axis labels with units, titles and aligned text.
#include <cairo.h>

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace tidalcrust {

struct PageRect {
  double left = 0, top = 0, width = 0, height = 0;  ///< points
  double right() const { return left + width; }
  double bottom() const { return top + height; }
};

/// Font sizes (points) shared by all figures.
inline constexpr double title_font_size = 13;
inline constexpr double label_font_size = 11;
inline constexpr double tick_font_size = 9;

/// Draws UTF-8 text with its anchor at (x, y): align_x 0 left, 0.5 centre, 1 right; align_y 0
/// top, 0.5 middle, 1 baseline. `angle` in radians (counter-clockwise on the page when negative).
void draw_text(cairo_t* cr, std::string_view text, double x, double y, double align_x, double align_y,
               double size, bool bold = false, double angle = 0);

/// Advance width of `text` in points.
double text_width(cairo_t* cr, std::string_view text, double size, bool bold = false);

/// Tick positions covering [lo, hi] with a 1-2-5 step giving about `target` ticks.
std::vector<double> nice_ticks(double lo, double hi, int target = 6);

/// Tick label: shortest of fixed and scientific notation with 3 significant digits.
std::string tick_label(double value, double step);

class PlotAxes {
 public:
  /// Maps [x_min, x_max] x [y_min, y_max] onto `area` (y grows upward). A degenerate range is
  /// widened so the mapping stays finite.
  PlotAxes(PageRect area, double x_min, double x_max, double y_min, double y_max);

  double page_x(double x) const { return area_.left + (x - x_min_) / (x_max_ - x_min_) * area_.width; }
  double page_y(double y) const { return area_.bottom() - (y - y_min_) / (y_max_ - y_min_) * area_.height; }
  const PageRect& area() const { return area_; }
  double x_min() const { return x_min_; }
  double x_max() const { return x_max_; }
  double y_min() const { return y_min_; }
  double y_max() const { return y_max_; }

  /// Restricts drawing to the plot area (cairo_save before, cairo_restore after).
  void clip(cairo_t* cr) const;
  /// Frame, ticks on all four sides, tick labels bottom and left, axis labels.
  void draw_frame(cairo_t* cr, std::string_view x_label, std::string_view y_label) const;
  /// Same with given tick positions (e.g. every 30 degrees on a map).
  void draw_frame(cairo_t* cr, std::string_view x_label, std::string_view y_label, const std::vector<double>& x_ticks,
                  const std::vector<double>& y_ticks) const;
  /// Polyline through (x[i], y[i]) in data units (not stroked: caller sets colour and strokes).
  void path(cairo_t* cr, const std::vector<double>& x, const std::vector<double>& y) const;

 private:
  PageRect area_;
  double x_min_, x_max_, y_min_, y_max_;
};

/// A row of equal square panels centred in its figure: the layout of the snapshot figures.
struct PanelRow {
  double panel_size = 0;   ///< side of a panel, points
  double gap = 0;          ///< between panels, points
  double side_margin = 0;  ///< left and right of the row, points
  double top = 0;          ///< top edge of the panels, points
  double min_width = 0;    ///< the figure is at least this wide, points
  double bottom = 0;       ///< below the panels (the legend line), points
  /// Width of the figure for `panels` panels (at least one), points.
  double figure_width(std::size_t panels) const;
  /// Height of the figure: top + panel_size + bottom, points.
  double figure_height() const { return top + panel_size + bottom; }
  /// Panel `index` of `panels`, showing [-half_width, half_width] in both directions (data units).
  PlotAxes axes(std::size_t index, std::size_t panels, double half_width) const;
  /// Writes <stem>.png and .svg: draw_panel(cr, axes(i, panels, half_width), i) for each panel,
  /// then `title` above the row and legend(cr, width, height) (points). Returns both paths;
  /// InputError naming the stem when `panels` is 0 (and as write_figure).
  std::vector<std::filesystem::path> write(
      const std::filesystem::path& stem, std::size_t panels, double half_width, std::string_view title,
      const std::function<void(cairo_t* cr, const PlotAxes& axes, std::size_t index)>& draw_panel,
      const std::function<void(cairo_t* cr, double width, double height)>& legend) const;
};

/// Title centred above `area`; text after a '\n' is a second, smaller line (the parameters and
/// units of the run) between the first line and the area.
void draw_title(cairo_t* cr, const PageRect& area, std::string_view title);

}  // namespace tidalcrust
