#include "analysis/figure_text.hpp"

#include <fmt/format.h>

#include <cmath>

namespace tidalcrust {

namespace {
/// Removes the sign of a printed finite number whose digits are all zero ("-0.00" -> "0.00",
/// "-0" -> "0"): the value rounded to zero at the printed precision.
std::string without_negative_zero(std::string text, double value) {
  if (!std::isfinite(value) || text.empty() || text.front() != '-') return text;
  for (const char ch : text) {
    if (ch == 'e' || ch == 'E') break;  // the exponent's digits do not make the mantissa non-zero
    if (ch >= '1' && ch <= '9') return text;
  }
  return text.substr(1);
}
}  // namespace

std::string fixed_text(double value, int decimals) {
  return without_negative_zero(fmt::format("{:.{}f}", value, decimals), value);
}

std::string signed_fixed_text(double value, int decimals) {
  std::string text = fixed_text(value, decimals);
  if (std::isfinite(value) && text.front() != '-' && text.find_first_of("123456789") != std::string::npos)
    text.insert(0, 1, '+');
  return text;
}

std::string general_text(double value, int significant) {
  return without_negative_zero(fmt::format("{:.{}g}", value, significant), value);
}

std::string time_from_pericenter_text(double time_from_pericenter, const MoonScale* moon) {
  const std::string model = fmt::format("{} t_grav", signed_fixed_text(time_from_pericenter, 2));
  if (!moon) return "t \u2212 t_peri = " + model;
  return fmt::format("t \u2212 t_peri = {} {} ({})",
                     signed_fixed_text(model_to_output(moon->units, Dimension::time, time_from_pericenter), 2),
                     output_unit(Dimension::time).symbol, model);
}

std::string si_text(double model_value, Dimension dimension, const MoonScale& moon) {
  return fmt::format("{} {}", general_text(model_to_output(moon.units, dimension, model_value), 4),
                     output_unit(dimension).symbol);
}

std::string encounter_parameters_text(const Encounter& encounter) {
  return fmt::format("M\u2082 = {} M, q = {} R, V_q = {} \u221a(GM/R)", general_text(encounter.perturber_mass),
                     general_text(encounter.pericenter), general_text(encounter.pericenter_speed));
}

std::string encounter_si_text(const Encounter& encounter, const StepClock& clock, const MoonScale& moon) {
  return fmt::format("{}: M\u2082 = {}, q = {}, V_q = {}; dt = {} s", moon.name,
                     si_text(encounter.perturber_mass, Dimension::mass, moon),
                     si_text(encounter.pericenter, Dimension::length, moon),
                     si_text(encounter.pericenter_speed, Dimension::speed, moon),
                     general_text(model_to_si(moon.units, Dimension::time, clock.dt), 4));
}

std::string time_axis_label(const MoonScale* moon) {
  return fmt::format("t \u2212 t_peri [{}]", moon ? output_unit(Dimension::time).symbol : "t_grav");
}

double dt_factor_of(const StepClock& clock) {
  if (clock.start_step <= 0) return 1;
  const double before = clock.start_time / static_cast<double>(clock.start_step);
  const double factor = clock.dt / before;
  if (!std::isfinite(factor) || !(factor > 0)) return 1;
  // start_time = start_step * dt_before was rounded once: keep 6 significant digits.
  const double scale = std::pow(10.0, 5 - std::floor(std::log10(factor)));
  return std::round(factor * scale) / scale;
}

std::string time_step_text(const StepClock& clock) {
  const std::string dt = fmt::format("dt = {} t_grav", general_text(clock.dt));
  const double factor = dt_factor_of(clock);
  return factor == 1 ? dt : fmt::format("{} = {} \u00d7 the body's dt", dt, general_text(factor));
}

std::string encounter_figure_title(const std::string& headline, const Encounter& encounter, const StepClock& clock,
                                   const MoonScale* moon) {
  const std::string title = fmt::format("{}\n{}; {}", headline, encounter_parameters_text(encounter), time_step_text(clock));
  return moon ? title + "\n" + encounter_si_text(encounter, clock, *moon) : title;
}

}  // namespace tidalcrust
