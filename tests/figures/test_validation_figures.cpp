// The signal plot of `validate`: the curve and the marks land where its axes say.
#include <gtest/gtest.h>

#include <cairo.h>

#include <cmath>
#include <cstdint>
#include <memory>

#include "base/errors.hpp"
#include "figures/figure_output.hpp"
#include "figures/validation_figures.hpp"
#include "support/files.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;

TEST(ValidationFigures, SignalPlotDrawsTheCurveAndTheMeasuredMarkInRed) {
  const ScratchFolder scratch("validation_figure");
  std::vector<double> t, s;
  for (int i = 0; i <= 400; ++i) t.push_back(0.01 * i), s.push_back(std::cos(2 * M_PI * t.back() / 0.5));
  const auto files = write_signal_plot(t, s, {{0.5, "Lamb", false}, {1.25, "measured", true}}, scratch.path / "b",
                                       "test", "signal");
  ASSERT_EQ(files.size(), 2u);
  std::unique_ptr<cairo_surface_t, void (*)(cairo_surface_t*)> png(
      cairo_image_surface_create_from_png(files[0].c_str()), cairo_surface_destroy);
  ASSERT_EQ(cairo_surface_status(png.get()), CAIRO_STATUS_SUCCESS);
  const auto rgb_at = [&](double x, double y) {
    const int px = static_cast<int>(x * png_pixels_per_point), py = static_cast<int>(y * png_pixels_per_point);
    const auto* row = cairo_image_surface_get_data(png.get()) + py * cairo_image_surface_get_stride(png.get());
    const std::uint32_t argb = reinterpret_cast<const std::uint32_t*>(row)[px];
    return std::array<int, 3>{static_cast<int>(argb >> 16 & 0xff), static_cast<int>(argb >> 8 & 0xff),
                              static_cast<int>(argb & 0xff)};
  };
  const PlotAxes axes = signal_plot_axes(t, s);
  // The curve's minimum at t = 0.25 is dark; the measured mark at t = 1.25, away from the curve, red.
  const auto curve = rgb_at(axes.page_x(0.25), axes.page_y(-1.0) - 0.5);
  EXPECT_LT(curve[0] + curve[1] + curve[2], 3 * 128);
  const auto mark = rgb_at(axes.page_x(1.25), axes.page_y(0.0) + 20);
  EXPECT_GT(mark[0], 150);
  EXPECT_LT(mark[1], 100);
  EXPECT_THROW(write_signal_plot({0.0}, {1.0}, {}, scratch.path / "c", "x", "y"), InputError);
}
