#pragma once
// Figures of `tidalcrust validate` (docs/validation.md): a measured signal against time with the
// times continuum theory predicts marked on it, written as <stem>.png and <stem>.svg.
#include <filesystem>
#include <string>
#include <vector>

#include "analysis/tidal_response.hpp"
#include "figures/plot_axes.hpp"

namespace tidalcrust {

/// A vertical line at time x (t_grav) with a short label; dashed grey for a theory (labels from
/// the top down), solid red for a measurement (labels from the bottom up), one line per label.
struct TimeMark {
  double time = 0;
  std::string label;  ///< drawn beside the line (may be empty)
  bool measured = false;
};

/// Where write_signal_plot puts time (x, t_grav) and signal (y), in points.
PlotAxes signal_plot_axes(const std::vector<double>& time, const std::vector<double>& signal);

/// Plot of signal[i] against time[i] (same length, >= 2 samples) with the marks; returns the PNG
/// and SVG paths. InputError naming the file if it cannot be written.
std::vector<std::filesystem::path> write_signal_plot(const std::vector<double>& time, const std::vector<double>& signal,
                                                     const std::vector<TimeMark>& marks, const std::filesystem::path& stem,
                                                     const std::string& title, const std::string& y_label);

/// Measured against continuum crust strain by angle from the tidal axis (`validate --measure tide`):
/// the bands' fitted meridional (eps_psipsi, red) and azimuthal (eps_lamlam, blue) strains as points,
/// and continuum_surface_strain(h2, l2, gamma) as lines (per unit eps). Returns the PNG and SVG
/// paths; InputError naming the file if it cannot be written or there is no band.
std::vector<std::filesystem::path> write_tidal_strain_plot(const std::vector<TidalStrainBin>& bins, double h2, double l2,
                                                           const std::filesystem::path& stem, const std::string& title);

}  // namespace tidalcrust
