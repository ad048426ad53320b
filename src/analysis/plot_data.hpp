#pragma once
// What the figures of `report`, `compare --resolution` and `validate` draw, as JSON: each of
// those commands writes one FOLDER/figure_data.json (figure_data_file) holding one such object per
// figure under its file stem, and the Python package draws them (python/tidalcrust/figures/,
// docs/python.md "Figures"): every number on a figure is computed here.
#include <filesystem>
#include <string>
#include <vector>

#include "analysis/fracture_analysis.hpp"
#include "analysis/sweep_report.hpp"
#include "analysis/tidal_response.hpp"
#include "io/json.hpp"

namespace tidalcrust {

/// A vertical line at time x (t_grav) with a short label; dashed grey for a theory, solid red
/// for a measurement.
struct TimeMark {
  double time = 0;
  std::string label;  ///< drawn beside the line (may be empty)
  bool measured = false;
};

/// "signal" (`validate`): signal[i] against time[i] (t_grav) with the marks. InputError naming
/// `name` unless time and signal are equally long with at least two samples.
Json signal_plot_json(const std::string& name, const std::vector<double>& time, const std::vector<double>& signal,
                      const std::vector<TimeMark>& marks, const std::string& title, const std::string& y_label);

/// "tidal_strain" (`validate --measure tide`): the bands' fitted meridional and azimuthal strains
/// against the angle from the tidal axis, and continuum_surface_strain(h2, l2, gamma) every
/// degree from 0 to 90 (per unit eps). InputError naming `name` without a band.
Json tidal_strain_plot_json(const std::string& name, const std::vector<TidalStrainBin>& bins, double h2, double l2,
                            const std::string& title);

/// "phase_diagram" (`report`): the encounters of `report` with this M2 and eps_S over pericenter q
/// and speed V_q, each with its status and colour value (the failed fraction of the shell
/// springs, or with `crack_probability` the share of cracked members), the crack/no-crack
/// boundary (grid-cell edges between a cracked and an intact finished neighbour; with
/// crack_probability, between shares on either side of 1/2), the eq. 5 strain = eps_S line
/// (V_q = M2 / (E^(1/2) q^2 eps_S), E = report.youngs_modulus) over the axes' q range (widened
/// to where that line crosses the grid's speeds, at most to 4x its largest q), the colour scale's
/// top and the title. InputError naming `name` if no encounter matches.
Json phase_diagram_json(const std::string& name, const SweepReport& report, double perturber_mass,
                        double failure_strain, bool crack_probability);

/// "fracture_map_row" (`compare --resolution`): one fracture map per panel (its cracks as
/// crack_polylines_json gives them, the format of cracks.json) with its title, and the title of
/// the row. InputError naming `name` if there is no panel or the titles do not match the panels.
Json fracture_map_row_json(const std::string& name, const std::vector<const FractureSummary*>& panels,
                           const std::vector<std::string>& state_hashes, const std::vector<std::string>& panel_titles,
                           const std::string& title);

/// FOLDER/figure_data.json of these figures ({"format", "version", "figures": {stem: figure}}),
/// written atomically; returns its path. The figures are then drawn into FOLDER as <stem>.png
/// and <stem>.svg (figures/figure_script.hpp).
std::filesystem::path write_figure_data_file(const std::filesystem::path& folder, const Json& figures);

}  // namespace tidalcrust
