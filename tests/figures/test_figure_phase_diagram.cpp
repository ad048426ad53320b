// The phase diagram of a sweep: a PNG of the expected size whose pixels show the eq. 5 line where
// the equation puts it, the crack/no-crack boundary between a cracked and an intact neighbour,
// cracked encounters filled and intact ones open.
#include <gtest/gtest.h>

#include <cairo.h>

#include <array>
#include <cmath>
#include <memory>

#include "base/errors.hpp"
#include "figures/figure_output.hpp"
#include "figures/figure_style.hpp"
#include "figures/figures.hpp"
#include "support/files.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

/// A 3 x 3 grid in q = 1.6, 2.0, 2.4 and V_q = 1.4, 1.8, 2.2 at M2 = 0.5: cracked (20% of the
/// shell) at q = 1.6, intact beyond; one encounter (q = 2.4, V_q = 2.2) not finished.
SweepReport synthetic_report() {
  SweepReport report;
  report.workflow = "synthetic";
  report.youngs_modulus = 4.0;
  for (double q : {1.6, 2.0, 2.4})
    for (double v : {1.4, 1.8, 2.2}) {
      SweepRow& r = report.rows.emplace_back();
      r.encounter = Encounter{"e", 0.5, q, v, {}, {}};
      r.failure_strain = 0.04;
      r.status = q == 2.4 && v == 2.2 ? SweepStatus::missing : SweepStatus::finished;
      r.failures = q == 1.6 ? 96 : 0;
      r.failed_fraction = q == 1.6 ? 0.2 : 0.0;
    }
  return report;
}

struct Rgb8 {
  int r, g, b;
};

class Png {
 public:
  explicit Png(const fs::path& file) : surface_(cairo_image_surface_create_from_png(file.c_str()), cairo_surface_destroy) {
    cairo_surface_flush(surface_.get());
  }
  int width() const { return cairo_image_surface_get_width(surface_.get()); }
  int height() const { return cairo_image_surface_get_height(surface_.get()); }
  /// The pixel under page point (x, y), in points.
  Rgb8 at(double x, double y) const {
    const int px = static_cast<int>(x * png_pixels_per_point), py = static_cast<int>(y * png_pixels_per_point);
    const auto* row = cairo_image_surface_get_data(surface_.get()) + py * cairo_image_surface_get_stride(surface_.get());
    const std::uint32_t argb = reinterpret_cast<const std::uint32_t*>(row)[px];
    return {static_cast<int>(argb >> 16 & 0xff), static_cast<int>(argb >> 8 & 0xff), static_cast<int>(argb & 0xff)};
  }
  /// True if a pixel within `radius` points of (x, y) has colour c (each channel within 3/255).
  bool has_colour_near(double x, double y, const tidalcrust::Rgb& c, double radius) const {
    for (double dx = -radius; dx <= radius; dx += 0.5)
      for (double dy = -radius; dy <= radius; dy += 0.5) {
        const Rgb8 p = at(x + dx, y + dy);
        if (std::abs(p.r - std::lround(255 * c[0])) <= 3 && std::abs(p.g - std::lround(255 * c[1])) <= 3 &&
            std::abs(p.b - std::lround(255 * c[2])) <= 3)
          return true;
      }
    return false;
  }

 private:
  std::unique_ptr<cairo_surface_t, void (*)(cairo_surface_t*)> surface_;
};

}  // namespace

TEST(PhaseDiagram, ShowsEq5LineBoundaryAndMarkers) {
  const ScratchFolder scratch("phase_diagram");
  const SweepReport report = synthetic_report();
  const FigureFiles files = write_phase_diagram(report, 0.5, 0.04, scratch.path / "phase");
  ASSERT_EQ(files.size(), 2u);
  ASSERT_EQ(files[0].extension(), ".png");
  EXPECT_TRUE(fs::exists(files[1]));
  const Png png(files[0]);
  EXPECT_EQ(png.width(), static_cast<int>(560 * png_pixels_per_point));
  EXPECT_EQ(png.height(), static_cast<int>(430 * png_pixels_per_point));

  std::vector<const SweepRow*> rows;
  for (const auto& r : report.rows) rows.push_back(&r);
  const PlotAxes axes = phase_diagram_axes(rows, report.youngs_modulus);
  // Eq. 5 strain = eps_S: V_q = M2 / (E^(1/2) q^2 eps_S) = 6.25 / q^2; at q = 1.8, V_q = 1.929.
  EXPECT_TRUE(png.has_colour_near(axes.page_x(1.8), axes.page_y(6.25 / (1.8 * 1.8)), eq5_line_color, 1.5));
  // ... and not where the equation does not put it.
  EXPECT_FALSE(png.has_colour_near(axes.page_x(1.8), axes.page_y(1.5), eq5_line_color, 3));
  // Boundary: the cell edge q = 1.8 between the cracked q = 1.6 and intact q = 2.0 columns, at
  // V_q = 1.6 (between two markers, off the eq. 5 line); none between the intact q = 2.0 and 2.4.
  EXPECT_TRUE(png.has_colour_near(axes.page_x(1.8), axes.page_y(1.52), boundary_color, 1.5));
  EXPECT_FALSE(png.has_colour_near(axes.page_x(2.2), axes.page_y(1.52), boundary_color, 3));
  // Cracked markers are filled with a colour of the scale, intact ones open (white inside).
  const Rgb8 filled = png.at(axes.page_x(1.6), axes.page_y(1.4));
  EXPECT_LT(filled.r + filled.g + filled.b, 3 * 250);
  const Rgb8 open = png.at(axes.page_x(2.0), axes.page_y(1.4));
  EXPECT_EQ(open.r + open.g + open.b, 3 * 255);
}

TEST(PhaseDiagram, NoMatchingEncounterIsInputError) {
  const ScratchFolder scratch("phase_diagram_none");
  EXPECT_THROW(write_phase_diagram(synthetic_report(), 0.1, 0.04, scratch.path / "phase"), InputError);
}
