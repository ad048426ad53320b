// Figure 6 (fig:T5): orthographic views of the hemisphere facing the subsatellite point.
#include <Eigen/Geometry>  // cross()
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include "base/errors.hpp"
#include "figures/figure_output.hpp"
#include "figures/figure_style.hpp"
#include "figures/figure_text.hpp"
#include "figures/figures.hpp"
#include "physics/orbital_frame.hpp"

namespace tidalcrust {

namespace {
constexpr double side_margin = 16;
constexpr PanelRow panel_row{220, 12, side_margin, 70, 460, 34};
constexpr double view_half_width = 1.45;  ///< R from the centre of mass to the panel edge

const Vec3 toward_viewer{0, 1, 0};              // the viewer sits far out on +y
const Vec3 light_direction = Vec3(0.35, 0.85, 0.40).normalized();  // upper left, in front
constexpr Rgb space_color{0.04, 0.04, 0.07};
constexpr Rgb ice_color{0.93, 0.91, 0.86};

double page_of_x(const PlotAxes& axes, const Vec3& p) { return axes.page_x(-p.x()); }
double page_of_y(const PlotAxes& axes, const Vec3& p) { return axes.page_y(p.z()); }

void perturber_disc_path(cairo_t* cr, const PlotAxes& axes, const Vec3& position, double radius) {
  const double scale = axes.area().width / (axes.x_max() - axes.x_min());
  cairo_new_sub_path(cr);
  cairo_arc(cr, page_of_x(axes, position), page_of_y(axes, position), radius * scale, 0, 2 * std::numbers::pi);
}

void fill_perturber(cairo_t* cr, const PlotAxes& axes, const Vec3& position, double radius) {
  perturber_disc_path(cr, axes, position, radius);
  set_color(cr, perturber_color, 0.28);
  cairo_fill(cr);
}

void outline_perturber(cairo_t* cr, const PlotAxes& axes, const Vec3& position, double radius) {
  perturber_disc_path(cr, axes, position, radius);
  set_color(cr, perturber_color, 0.75);
  cairo_set_line_width(cr, 1.0);
  cairo_stroke(cr);
}

/// Shell faces turned toward the viewer, far to near (painter's order), Lambert shaded; marks
/// them in `is_visible` (by face index).
void draw_faces(cairo_t* cr, const PlotAxes& axes, const Body& body, const std::function<Vec3(std::int32_t)>& position,
                std::vector<bool>& is_visible) {
  struct VisibleFace {
    std::size_t face;
    double depth;
    double brightness;
  };
  std::vector<VisibleFace> visible;
  is_visible.assign(body.faces.size(), false);
  for (std::size_t f = 0; f < body.faces.size(); ++f) {
    const auto& v = body.faces[f];
    const Vec3 a = position(v[0]), b = position(v[1]), c = position(v[2]);
    const Vec3 normal = (b - a).cross(c - a).normalized();
    if (normal.dot(toward_viewer) <= 0) continue;
    visible.push_back({f, (a + b + c).dot(toward_viewer), 0.2 + 0.8 * std::max(0.0, normal.dot(light_direction))});
    is_visible[f] = true;
  }
  std::stable_sort(visible.begin(), visible.end(),
                   [](const VisibleFace& p, const VisibleFace& q) { return p.depth < q.depth; });
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_width(cr, 0.35);  // stroking in the fill colour hides hairline seams
  for (const auto& face : visible) {
    const auto& v = body.faces[face.face];
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = position(v[k]);
      if (k == 0) cairo_move_to(cr, page_of_x(axes, p), page_of_y(axes, p));
      else cairo_line_to(cr, page_of_x(axes, p), page_of_y(axes, p));
    }
    cairo_close_path(cr);
    set_color(cr, {ice_color[0] * face.brightness, ice_color[1] * face.brightness, ice_color[2] * face.brightness});
    cairo_fill_preserve(cr);
    cairo_stroke(cr);
  }
}

/// Crack bars of the faces in view, in black.
void draw_cracks(cairo_t* cr, const PlotAxes& axes, const FractureSummary& fractures,
                 const std::vector<bool>& is_visible) {
  set_color(cr, crack_color);
  cairo_set_line_width(cr, 1.1);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  for (const auto& bar : fractures.bars) {
    if (!is_visible[static_cast<std::size_t>(bar.face)]) continue;
    cairo_move_to(cr, page_of_x(axes, bar.centroid), page_of_y(axes, bar.centroid));
    cairo_line_to(cr, page_of_x(axes, bar.edge_midpoint), page_of_y(axes, bar.edge_midpoint));
  }
  cairo_stroke(cr);
}

void draw_panel(cairo_t* cr, const PlotAxes& axes, const Checkpoint& checkpoint, double pericenter_time) {
  const Body& body = checkpoint.body;
  const State& state = checkpoint.state;
  const Vec3 center = body_center_of_mass(body, state);
  const FractureSummary fractures = analyze_fractures(body, state);
  const std::function<Vec3(std::int32_t)> position = [&](std::int32_t i) {
    return Vec3(vec3_at(state.position, static_cast<std::size_t>(i)) - center);
  };

  cairo_save(cr);
  axes.clip(cr);
  set_color(cr, space_color);
  cairo_paint(cr);

  const bool has_perturber = state.perturber.present && state.perturber.mass > 0;
  const Vec3 perturber = Vec3(state.perturber.position[0], state.perturber.position[1], state.perturber.position[2]) - center;
  const double perturber_radius = std::cbrt(state.perturber.mass);
  std::vector<bool> is_visible;
  for (const HemisphereLayer layer : hemisphere_panel_layers(has_perturber, perturber.dot(toward_viewer) >= 0)) {
    switch (layer) {
      case HemisphereLayer::faces: draw_faces(cr, axes, body, position, is_visible); break;
      case HemisphereLayer::cracks: draw_cracks(cr, axes, fractures, is_visible); break;
      case HemisphereLayer::perturber_fill: fill_perturber(cr, axes, perturber, perturber_radius); break;
      case HemisphereLayer::perturber_outline: outline_perturber(cr, axes, perturber, perturber_radius); break;
    }
  }
  cairo_restore(cr);

  const PageRect& area = axes.area();
  cairo_set_source_rgb(cr, 0, 0, 0);
  draw_text(cr, time_from_pericenter_text(state.time - pericenter_time), area.left + 0.5 * area.width, area.top - 5,
            0.5, 1, label_font_size);
  cairo_save(cr);
  cairo_set_source_rgb(cr, 1, 1, 1);
  draw_text(cr, fmt::format("{} failed", fractures.count()), area.left + 6, area.bottom() - 6, 0, 1, tick_font_size);
  cairo_restore(cr);
}
}  // namespace

std::vector<HemisphereLayer> hemisphere_panel_layers(bool perturber_present, bool perturber_in_front) {
  using enum HemisphereLayer;
  if (!perturber_present) return {faces, cracks};
  // Behind the body the disc is hidden by the faces drawn over it; in front it is translucent
  // and the cracks are drawn over its fill, so it never hides them, with its outline on top.
  if (!perturber_in_front) return {perturber_fill, perturber_outline, faces, cracks};
  return {faces, perturber_fill, cracks, perturber_outline};
}

PlotAxes hemisphere_panel_axes(std::size_t index, std::size_t panel_count) {
  return panel_row.axes(index, panel_count, view_half_width);
}

FigureFiles write_hemisphere_views(const std::vector<const Checkpoint*>& snapshots, double pericenter_time,
                                   const std::filesystem::path& stem, const std::string& title) {
  return panel_row.write(
      stem, snapshots.size(), view_half_width, title,
      [&](cairo_t* cr, const PlotAxes& axes, std::size_t i) { draw_panel(cr, axes, *snapshots[i], pericenter_time); },
      [](cairo_t* cr, double width, double height) {
        const std::string view =
            "orthographic; viewer on +y in the orbital plane, facing the subsatellite point; +z up, +x left";
        const std::string perturber =
            "magenta: perturber, radius M\u2082^(1/3) R (same density), translucent, cracks drawn over it";
        if (text_width(cr, view + "; " + perturber, tick_font_size) < width - 2 * side_margin) {
          draw_text(cr, view + "; " + perturber, 0.5 * width, height - 12, 0.5, 1, tick_font_size);
        } else {
          draw_text(cr, view, 0.5 * width, height - 17, 0.5, 1, tick_font_size);
          draw_text(cr, perturber, 0.5 * width, height - 5, 0.5, 1, tick_font_size);
        }
      });
}

}  // namespace tidalcrust
