#pragma once
// What the figures of an encounter draw (docs/python.md, "Figures"): analyze writes it into
// analysis/figure_data.json (figure_data_json, its one writer) beside summary.json and cracks.json,
// and the Python package draws the figures from these files (python/tidalcrust/figures.py), so
// that every number on a figure is defined here, in C++, and the figures only draw them.
#include <string>
#include <vector>

#include "io/json.hpp"
#include "model/checkpoint.hpp"
#include "model/moon_units.hpp"

namespace tidalcrust {

/// The figures of one encounter, in the order analyze draws them: each is written as
/// <name>.png and <name>.svg into the analysis folder (summary.json's "figures" lists the files).
inline const std::vector<std::string>& encounter_figure_names() {
  static const std::vector<std::string> names{"fracture_map", "hemisphere",  "orbit",       "failures",
                                              "conservation", "body_shape",  "axis_ratios", "crack_geometry"};
  return names;
}

/// Half thickness of the slice about the orbital plane that the body_shape panels draw, R.
inline constexpr double body_slice_half_width = 0.12;

/// The data of every figure of `final_checkpoint` (an encounter, record `record`): `panels` are
/// the hemisphere and body-shape panels (snapshots and the final state, of one body, in time
/// order), `shape_checkpoints` every checkpoint whose principal axes summary.json lists,
/// `titles` one two-line title per name of encounter_figure_names(). Positions are relative to the
/// body's centre of mass in the maps' orbital frame (orbital plane = equator, subsatellite point
/// +y), lengths in R, times in t_grav from pericenter. Keys: docs/python.md. Of a [moon] workflow
/// (`moon`; docs/moon.md, "Output in SI") the labels give times in hours beside t_grav, and `map`,
/// `time_axis`, `length_axis` and `si` say how the figures show SI: maps in planetocentric
/// longitude (0 at the subsatellite point) with a km scale bar, time axes in hours, a km axis
/// beside R.
Json figure_data_json(const Checkpoint& final_checkpoint, const EncounterRecord& record,
                      const std::vector<const Checkpoint*>& panels, const Json& titles,
                      const std::string& state_hash, const MoonScale* moon = nullptr);

}  // namespace tidalcrust
