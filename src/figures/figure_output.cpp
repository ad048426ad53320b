#include "figures/figure_output.hpp"

#include <cairo-svg.h>
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <string>

#include "base/errors.hpp"
#include "io/atomic_file.hpp"

namespace tidalcrust {

namespace {
struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};
using SurfaceHandle = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;
using ContextHandle = std::unique_ptr<cairo_t, ContextDeleter>;

void render(cairo_surface_t* surface, double scale, const DrawFigure& draw) {
  ContextHandle cr(cairo_create(surface));
  cairo_scale(cr.get(), scale, scale);
  cairo_set_source_rgb(cr.get(), 1, 1, 1);
  cairo_paint(cr.get());
  cairo_set_source_rgb(cr.get(), 0, 0, 0);
  draw(cr.get());
  if (cairo_status(cr.get()) != CAIRO_STATUS_SUCCESS)
    throw SimulationError(fmt::format("cairo drawing failed: {}", cairo_status_to_string(cairo_status(cr.get()))));
}

void check(cairo_status_t status, const std::filesystem::path& file) {
  if (status != CAIRO_STATUS_SUCCESS)
    throw InputError(fmt::format("{}: cannot write figure: {}", file.string(), cairo_status_to_string(status)));
}
/// Cairo write callback appending to a std::string (figures are rendered in memory and then
/// written with write_file_atomically, so a failed write names its errno text and never leaves
/// half a figure).
cairo_status_t append_bytes(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}
}  // namespace

std::vector<std::filesystem::path> write_figure(const std::filesystem::path& stem, double width, double height,
                                                const DrawFigure& draw) {
  std::filesystem::path png = stem, svg = stem;
  png += ".png";
  svg += ".svg";
  {
    SurfaceHandle surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32,
                                                     static_cast<int>(std::lround(width * png_pixels_per_point)),
                                                     static_cast<int>(std::lround(height * png_pixels_per_point))));
    check(cairo_surface_status(surface.get()), png);
    render(surface.get(), png_pixels_per_point, draw);
    std::string bytes;
    check(cairo_surface_write_to_png_stream(surface.get(), append_bytes, &bytes), png);
    write_file_atomically(png, bytes);
  }
  {
    std::string bytes;
    {
      SurfaceHandle surface(cairo_svg_surface_create_for_stream(append_bytes, &bytes, width, height));
      check(cairo_surface_status(surface.get()), svg);
      render(surface.get(), 1.0, draw);
      cairo_surface_finish(surface.get());
      check(cairo_surface_status(surface.get()), svg);
    }
    write_file_atomically(svg, bytes);
  }
  return {png, svg};
}

}  // namespace tidalcrust
