#include "figures/plot_axes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "base/errors.hpp"
#include "figures/figure_output.hpp"
#include "figures/figure_text.hpp"

namespace tidalcrust {

namespace {
/// The one typeface of every figure, at `size` points.
void select_font(cairo_t* cr, double size, bool bold) {
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}
}  // namespace

void draw_text(cairo_t* cr, std::string_view text, double x, double y, double align_x, double align_y, double size,
               bool bold, double angle) {
  const std::string s(text);
  cairo_save(cr);
  select_font(cr, size, bold);
  cairo_text_extents_t extents;
  cairo_text_extents(cr, s.c_str(), &extents);
  cairo_font_extents_t font;
  cairo_font_extents(cr, &font);
  cairo_translate(cr, x, y);
  cairo_rotate(cr, angle);
  // Vertical alignment from the font's ascent so that labels of one row line up.
  const double dy = align_y >= 1 ? 0 : font.ascent * (1 - align_y) - (align_y > 0 ? font.descent * align_y : 0);
  cairo_move_to(cr, -extents.x_advance * align_x, dy);
  cairo_show_text(cr, s.c_str());
  cairo_restore(cr);
}

double text_width(cairo_t* cr, std::string_view text, double size, bool bold) {
  const std::string s(text);
  cairo_save(cr);
  select_font(cr, size, bold);
  cairo_text_extents_t extents;
  cairo_text_extents(cr, s.c_str(), &extents);
  cairo_restore(cr);
  return extents.x_advance;
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  std::vector<double> ticks;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return ticks;
  const double raw = (hi - lo) / std::max(1, target);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double step = magnitude;
  for (const double factor : {1.0, 2.0, 5.0, 10.0}) {
    step = factor * magnitude;
    if (step >= raw) break;
  }
  // Integer multiples of the step avoid accumulated rounding in the labels.
  const auto first = static_cast<long long>(std::ceil(lo / step - 1e-9));
  const auto last = static_cast<long long>(std::floor(hi / step + 1e-9));
  for (long long k = first; k <= last; ++k) ticks.push_back(static_cast<double>(k) * step);
  return ticks;
}

std::string tick_label(double value, double step) {
  if (std::abs(value) < 1e-9 * std::abs(step)) return "0";
  const double magnitude = std::max(std::abs(value), std::abs(step));
  if (magnitude >= 1e-3 && magnitude < 1e5) {
    const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(std::abs(step)) + 1e-9)));
    return fixed_text(value, decimals);
  }
  return general_text(value, 2);
}

double PanelRow::figure_width(std::size_t panels) const {
  const double n = static_cast<double>(std::max<std::size_t>(panels, 1));
  return std::max(min_width, 2 * side_margin + n * panel_size + (n - 1) * gap);
}

PlotAxes PanelRow::axes(std::size_t index, std::size_t panels, double half_width) const {
  const double n = static_cast<double>(std::max<std::size_t>(panels, 1));
  const double row = n * panel_size + (n - 1) * gap;
  const double left = 0.5 * (figure_width(panels) - row) + static_cast<double>(index) * (panel_size + gap);
  return PlotAxes({left, top, panel_size, panel_size}, -half_width, half_width, -half_width, half_width);
}

std::vector<std::filesystem::path> PanelRow::write(
    const std::filesystem::path& stem, std::size_t panels, double half_width, std::string_view title,
    const std::function<void(cairo_t* cr, const PlotAxes& axes, std::size_t index)>& draw_panel,
    const std::function<void(cairo_t* cr, double width, double height)>& legend) const {
  if (panels == 0) throw InputError(fmt::format("{}: no snapshot to draw", stem.string()));
  const double width = figure_width(panels), height = figure_height();
  return write_figure(stem, width, height, [&](cairo_t* cr) {
    for (std::size_t i = 0; i < panels; ++i) draw_panel(cr, axes(i, panels, half_width), i);
    cairo_set_source_rgb(cr, 0, 0, 0);
    draw_title(cr, {0, top - 24, width, 0}, title);
    legend(cr, width, height);
  });
}

PlotAxes::PlotAxes(PageRect area, double x_min, double x_max, double y_min, double y_max)
    : area_(area), x_min_(x_min), x_max_(x_max), y_min_(y_min), y_max_(y_max) {
  auto widen = [](double& lo, double& hi) {
    if (!std::isfinite(lo) || !std::isfinite(hi)) lo = 0, hi = 1;
    if (hi > lo) return;
    const double pad = lo != 0 ? 0.1 * std::abs(lo) : 1.0;
    lo -= pad;
    hi += pad;
  };
  widen(x_min_, x_max_);
  widen(y_min_, y_max_);
}

void PlotAxes::clip(cairo_t* cr) const {
  cairo_rectangle(cr, area_.left, area_.top, area_.width, area_.height);
  cairo_clip(cr);
}

void PlotAxes::draw_frame(cairo_t* cr, std::string_view x_label, std::string_view y_label) const {
  draw_frame(cr, x_label, y_label, nice_ticks(x_min_, x_max_), nice_ticks(y_min_, y_max_, 5));
}

void PlotAxes::draw_frame(cairo_t* cr, std::string_view x_label, std::string_view y_label,
                          const std::vector<double>& x_ticks, const std::vector<double>& y_ticks) const {
  constexpr double tick_length = 4;
  cairo_save(cr);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 0.8);
  cairo_rectangle(cr, area_.left, area_.top, area_.width, area_.height);
  cairo_stroke(cr);
  const double x_step = x_ticks.size() > 1 ? x_ticks[1] - x_ticks[0] : 1;
  const double y_step = y_ticks.size() > 1 ? y_ticks[1] - y_ticks[0] : 1;
  for (const double t : x_ticks) {
    const double x = page_x(t);
    cairo_move_to(cr, x, area_.bottom());
    cairo_line_to(cr, x, area_.bottom() - tick_length);
    cairo_move_to(cr, x, area_.top);
    cairo_line_to(cr, x, area_.top + tick_length);
    draw_text(cr, tick_label(t, x_step), x, area_.bottom() + 3, 0.5, 0, tick_font_size);
  }
  double widest = 0;
  for (const double t : y_ticks) {
    const double y = page_y(t);
    cairo_move_to(cr, area_.left, y);
    cairo_line_to(cr, area_.left + tick_length, y);
    cairo_move_to(cr, area_.right(), y);
    cairo_line_to(cr, area_.right() - tick_length, y);
    const std::string label = tick_label(t, y_step);
    draw_text(cr, label, area_.left - 4, y, 1, 0.5, tick_font_size);
    widest = std::max(widest, text_width(cr, label, tick_font_size));
  }
  cairo_stroke(cr);
  draw_text(cr, x_label, area_.left + 0.5 * area_.width, area_.bottom() + 6 + tick_font_size, 0.5, 0,
            label_font_size);
  draw_text(cr, y_label, area_.left - 10 - widest, area_.top + 0.5 * area_.height, 0.5, 1, label_font_size, false,
            -std::numbers::pi / 2);
  cairo_restore(cr);
}

void PlotAxes::path(cairo_t* cr, const std::vector<double>& x, const std::vector<double>& y) const {
  const std::size_t n = std::min(x.size(), y.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (i == 0) cairo_move_to(cr, page_x(x[i]), page_y(y[i]));
    else cairo_line_to(cr, page_x(x[i]), page_y(y[i]));
  }
}

void draw_title(cairo_t* cr, const PageRect& area, std::string_view title) {
  const double x = area.left + 0.5 * area.width;
  // Each line shrinks, if need be, to fit the page (the clip extents) centred on x.
  double page_left = 0, page_top = 0, page_right = 0, page_bottom = 0;
  cairo_clip_extents(cr, &page_left, &page_top, &page_right, &page_bottom);
  const double room = 2 * std::min(x - page_left, page_right - x) - 8;
  auto line = [&](std::string_view text, double y, double size, bool bold) {
    const double width = text_width(cr, text, size, bold);
    draw_text(cr, text, x, y, 0.5, 1, width > room && room > 0 ? size * room / width : size, bold);
  };
  const auto newline = title.find('\n');
  if (newline == std::string_view::npos) {
    line(title, area.top - 8, title_font_size, true);
    return;
  }
  line(title.substr(0, newline), area.top - 8 - label_font_size - 4, title_font_size, true);
  line(title.substr(newline + 1), area.top - 7, label_font_size, false);
}

}  // namespace tidalcrust
