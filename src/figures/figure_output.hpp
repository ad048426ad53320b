#pragma once
// Renders one drawing to both a PNG (raster, for a quick look) and an SVG (vector, for papers).
#include <cairo.h>

#include <filesystem>
#include <functional>
#include <vector>

namespace tidalcrust {

/// Draws the whole figure on `cr` in points; (0, 0) is the top-left corner.
using DrawFigure = std::function<void(cairo_t* cr)>;

/// PNG pixels per point: figures are laid out in points and rasterised at this scale.
inline constexpr double png_pixels_per_point = 2.0;

/// Writes <stem>.png and <stem>.svg of a width x height (points) figure on a white background.
/// Returns both paths; throws InputError naming the file if cairo cannot write it.
std::vector<std::filesystem::path> write_figure(const std::filesystem::path& stem, double width, double height,
                                                const DrawFigure& draw);

}  // namespace tidalcrust
