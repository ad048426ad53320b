#pragma once
// Colours and line widths shared by the figures, so that panels of one paper look alike.
#include <cairo.h>

#include <array>

namespace tidalcrust {

using Rgb = std::array<double, 3>;

inline constexpr Rgb surface_color{0.90, 0.89, 0.85};    ///< icy crust (map background)
inline constexpr Rgb graticule_color{0.72, 0.71, 0.68};  ///< map grid lines
inline constexpr Rgb crack_color{0.0, 0.0, 0.0};         ///< dual-lattice crack bars (Figure 4)
inline constexpr Rgb ring_color{1.0, 0.80, 0.0};         ///< subsatellite ring (Figure 8)
inline constexpr Rgb perturber_color{0.85, 0.0, 0.75};   ///< magenta perturber (Figure 4, 6)
inline constexpr Rgb tick_marker_color{0.85, 0.0, 0.0};  ///< red diamonds and arrows (Figure 7)
inline constexpr Rgb eq5_line_color{0.90, 0.10, 0.10};   ///< phase diagram: eq. 5 strain = eps_S line
inline constexpr Rgb boundary_color{0.0, 0.0, 0.0};      ///< phase diagram: crack/no-crack boundary
inline constexpr Rgb arc_color{0.05, 0.35, 0.85};      ///< crack geometry: fitted small circles and poles
inline constexpr Rgb rose_color{0.55, 0.70, 0.90};     ///< crack geometry: rose petals
inline constexpr double map_crack_width = 1.3;           ///< points

inline void set_color(cairo_t* cr, const Rgb& c, double alpha = 1.0) {
  cairo_set_source_rgba(cr, c[0], c[1], c[2], alpha);
}

/// Yellow ring with thin dark edges (visible on light and dark ground), centre (x, y) in points.
inline void draw_subsatellite_ring(cairo_t* cr, double x, double y, double radius) {
  cairo_save(cr);
  cairo_new_sub_path(cr);
  cairo_arc(cr, x, y, radius, 0, 2 * 3.14159265358979323846);
  cairo_set_line_width(cr, 3.6);
  cairo_set_source_rgb(cr, 0.25, 0.2, 0.0);
  cairo_stroke_preserve(cr);
  cairo_set_line_width(cr, 2.4);
  set_color(cr, ring_color);
  cairo_stroke(cr);
  cairo_restore(cr);
}

}  // namespace tidalcrust
