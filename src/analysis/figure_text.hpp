#pragma once
// Every title and panel label the C++ side writes for a figure (figure_data.json, plot_data.hpp;
// the Python package prints them as given) goes through these helpers, so that no figure shows
// "-0.00" (a tiny negative value rounded to zero) and every quantity names its unit (README
// "Units": M, R, t_grav, sqrt(GM/R)).
#include <string>

#include "model/encounter.hpp"
#include "model/moon_units.hpp"
#include "model/stage_records.hpp"

namespace tidalcrust {

/// `value` with `decimals` digits after the point; a value that rounds to zero prints unsigned
/// ("0.00", never "-0.00"). Non-finite values print as fmt does ("nan", "inf", "-inf").
std::string fixed_text(double value, int decimals);

/// Same with an explicit sign on non-zero results: "+1.84", "-0.25", and "0.00" for a value that
/// rounds to zero (t = -1e-17 included).
std::string signed_fixed_text(double value, int decimals);

/// Shortest form with `significant` digits ("{:g}"): 0.5, 1e-05, 1.84; never "-0".
std::string general_text(double value, int significant = 6);

/// "t − t_peri = +1.84 t_grav" for `time_from_pericenter` in t_grav, two decimals; of a moon
/// (docs/moon.md, "Output in SI") in hours first: "t − t_peri = +0.97 h (+1.84 t_grav)".
std::string time_from_pericenter_text(double time_from_pericenter, const MoonScale* moon = nullptr);

/// "M₂ = 0.5 M, q = 1.84 R, V_q = 1.6 √(GM/R)": the encounter's parameters with their units.
std::string encounter_parameters_text(const Encounter& encounter);

/// "977 km": a model value of `dimension` in the SI output unit of `moon`, four significant digits.
std::string si_text(double model_value, Dimension dimension, const MoonScale& moon);

/// "Tethys: M₂ = 3.1e+20 kg, q = 977 km, V_q = 0.447 km/s; dt = 3.805 s": the encounter's
/// parameters and the time step in the moon's SI units.
std::string encounter_si_text(const Encounter& encounter, const StepClock& clock, const MoonScale& moon);

/// The label of the figures' time axes: "t − t_peri [h]" for a moon, else "t − t_peri [t_grav]".
std::string time_axis_label(const MoonScale* moon);

/// The ratio of the stage's time step to the mean time step before the stage began
/// (clock.start_time / clock.start_step), rounded to 6 significant digits: for an encounter
/// branched from the relaxed body (whose chain runs from t = 0 at step 0 at one dt) this is the
/// dt factor of `run --dt-factor` / `encounter --dt-factor`. 1 when the stage starts at step 0
/// or the ratio is not finite.
double dt_factor_of(const StepClock& clock);

/// "dt = 0.002 t_grav", and "dt = 0.001 t_grav = 0.5 × the body's dt" when dt_factor_of(clock)
/// is not 1: figures of a half-dt rerun never carry the same titles as the full-dt ones.
std::string time_step_text(const StepClock& clock);

/// Title of an encounter figure: `headline` on the first line, then a second line with the
/// encounter's parameters and the time step; of a moon a third, the same in SI (encounter_si_text).
std::string encounter_figure_title(const std::string& headline, const Encounter& encounter, const StepClock& clock,
                                   const MoonScale* moon = nullptr);

}  // namespace tidalcrust
