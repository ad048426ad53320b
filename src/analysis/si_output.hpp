#pragma once
// Output in SI beside the model units (issue 25, docs/moon.md "Output in SI"): for a workflow with
// a [moon] table, summary.json, report's tables, inspect and the figures give every dimensional
// value also in the moon's units, converted by model/moon_units.hpp (the one home of the
// conversion; lengths in km, masses in kg, speeds in km/s, times in hours, energies in J). The
// model values stay where they were; without [moon] none of this is written.
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include "io/json.hpp"
#include "model/moon_units.hpp"

namespace tidalcrust {

/// One line saying what the SI values are and how they follow from the model's, naming the moon.
std::string si_units_text(const MoonScale& moon);

/// The moon of the SI values: name, radius_km, mass_kg, mean_density_kg_m3, and what one model
/// unit is worth: t_grav_s, v_c_km_s, e_g_Pa, energy_unit_J (G M^2/R), G (m^3 kg^-1 s^-2).
Json moon_json(const MoonScale& moon);

/// A key of a model-unit JSON object and the dimension of its value.
using ModelKey = std::pair<std::string_view, Dimension>;

/// For each of `keys` that `model` holds: si_key(key, dimension) -> the value in the output unit
/// of its dimension (a null stays null), in the order of `keys`.
Json si_values(const Json& model, std::span<const ModelKey> keys, const ModelUnits& units);

/// The crack lengths of a `failures` object (failure_summary_json) in km: the keys whose
/// failure_summary_unit is R, as <key>_km.
Json failures_si_json(const Json& failures, const ModelUnits& units);

/// The "si" object of summary.json (stages/analysis_stage.cpp) from the model-unit summary beside
/// it: units (si_units_text), moon (moon_json), map_frame, time_from_pericenter_h, then the
/// encounter, failures, clusters, crack_geometry arcs, failure_trend, energy and principal axis
/// times in SI, and the failed springs' planetocentric longitudes. Keys: docs/moon.md.
Json summary_si_json(const MoonScale& moon, const Json& summary);

}  // namespace tidalcrust
