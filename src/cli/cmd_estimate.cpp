// tidalcrust estimate: Table 1 units of a body and the impulse estimates of paper section 1.1.
#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cxxopts.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/cli_options.hpp"
#include "cli/commands.hpp"
#include "physics/encounter_estimates.hpp"
#include "base/errors.hpp"
#include "io/json.hpp"
#include "physics/physical_units.hpp"
#include "physics/hydrostatic_pressure.hpp"
#include "integrate/stability_bound.hpp"
#include "model/config.hpp"
#include "model/derived_quantities.hpp"
#include "stages/build_stage.hpp"
#include "stages/stretch_stage.hpp"
#include "stages/time_step.hpp"

namespace tidalcrust {
namespace {

/// Reads a number option as text so that malformed values ("abc", "nan") are reported
/// with the option's name.
std::optional<double> number_option(const cxxopts::ParseResult& parsed, const char* name) {
  if (!parsed.count(name)) return std::nullopt;
  const std::string text = parsed[name].as<std::string>();
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value))
    throw InputError(fmt::format("--{}: expected a finite number, got '{}'", name, text));
  return value;
}

double positive_option(const cxxopts::ParseResult& parsed, const char* name, double fallback,
                       bool allow_zero = false) {
  const double value = number_option(parsed, name).value_or(fallback);
  if (value < 0 || (!allow_zero && value == 0))
    throw InputError(fmt::format("--{} must be {} 0, got {}", name, allow_zero ? ">=" : ">", value));
  return value;
}

/// One body's units and the encounter estimates for it.
struct BodyReport {
  PhysicalBody body;
  BodyScales scales;
  double e_g_over_E = 0;
  EncounterEstimates estimates;
};

BodyReport report_for(const PhysicalBody& body, const Encounter& encounter, double youngs_GPa) {
  BodyReport r{body, body_scales(body), 0, {}};
  const double youngs = youngs_in_e_g(youngs_GPa, r.scales);
  r.e_g_over_E = 1.0 / youngs;
  r.estimates = estimate_encounter(encounter, youngs);
  return r;
}

Json body_json(const BodyReport& r) {
  const auto& e = r.estimates;
  return {{"body", r.body.name},
          {"mass_kg", r.body.mass_kg},
          {"radius_km", r.body.radius_km},
          {"e_g_GPa", r.scales.e_g_GPa},
          {"t_grav_s", r.scales.t_grav_s},
          {"rho_g_cm3", r.scales.density_g_cm3},
          {"v_c_km_s", r.scales.v_c_km_s},
          {"e_g_over_E", r.e_g_over_E},
          {"delta_v", e.delta_v},
          {"delta_v_km_s", e.delta_v * r.scales.v_c_km_s},
          {"strain", e.strain},
          {"t_enc_s", e.encounter_time * r.scales.t_grav_s},
          {"t_elas_s", e.elastic_time * r.scales.t_grav_s},
          {"t_enc_over_t_elas", e.encounter_time / e.elastic_time},
          {"eq11_time_ratio", e.time_ratio},
          {"strain_rate_per_s", e.strain_rate / r.scales.t_grav_s}};
}

Json inputs_json(const Encounter& g, double youngs_GPa) {
  return {{"m2", g.perturber_mass}, {"q", g.pericenter}, {"vq", g.pericenter_speed}, {"youngs_GPa", youngs_GPa}};
}

std::string inputs_line(const Encounter& g, double youngs_GPa) {
  return fmt::format("encounter M2 = {:g} M, q = {:g} R, V_q = {:.4g} v_c; E = {:g} GPa", g.perturber_mass,
                     g.pericenter, g.pericenter_speed, youngs_GPa);
}

void print_body(const BodyReport& r, const Encounter& g, double youngs_GPa) {
  const auto& s = r.scales;
  const auto& e = r.estimates;
  fmt::print("body {} (mass {:.4g} kg, radius {:g} km)\n", r.body.name, r.body.mass_kg, r.body.radius_km);
  fmt::print("  e_g     = {:.4g} GPa   (unit of moduli, G M^2/R^4)\n", s.e_g_GPa);
  fmt::print("  t_grav  = {:.5g} s     (unit of time, sqrt(R^3/GM))\n", s.t_grav_s);
  fmt::print("  rho     = {:.4g} g/cm^3\n", s.density_g_cm3);
  fmt::print("  v_c     = {:.4g} km/s  (unit of velocity, sqrt(GM/R))\n", s.v_c_km_s);
  fmt::print("{}; e_g/E = {:.3g}\n", inputs_line(g, youngs_GPa), r.e_g_over_E);
  fmt::print("  delta_v          = {:.3g} v_c = {:.3g} km/s   (eq. 3)\n", e.delta_v, e.delta_v * s.v_c_km_s);
  fmt::print("  strain           = {:.3g}   (eq. 5)\n", e.strain);
  fmt::print("  t_enc            = {:.4g} s,  t_elas = {:.4g} s\n", e.encounter_time * s.t_grav_s,
             e.elastic_time * s.t_grav_s);
  // The ratio of the two times printed above, then eq. 11 as the paper prints it, which takes
  // t_enc ~ q/V_q (half of eq. 2's 2q/V_q), labelled separately so the lines agree.
  fmt::print("  t_enc/t_elas     = {:.3g}\n", e.encounter_time / e.elastic_time);
  fmt::print("  eq. 11 as printed = {:.3g}   ((q/R)(v_c/V_q)(E/e_g)^(1/2), i.e. t_enc ~ q/V_q: half of t_enc/t_elas)\n",
             e.time_ratio);
  fmt::print("  strain rate      = {:.3g} /s   (eq. 10)\n", e.strain_rate / s.t_grav_s);
}

void print_table(const std::vector<BodyReport>& reports, const Encounter& g, double youngs_GPa) {
  fmt::print("Table 1 (Quillen et al. 2016) and section 1.1 estimates; {}\n", inputs_line(g, youngs_GPa));
  fmt::print("{:<8} {:>10} {:>8} {:>9} {:>9} {:>7} {:>7} {:>7} {:>7} {:>12} {:>10}\n", "body", "mass_kg",
             "R_km", "e_g_GPa", "t_grav_s", "rho", "v_c", "e_g/E", "strain", "t_enc/t_elas", "rate_1/s");
  for (const auto& r : reports) {
    fmt::print("{:<8} {:>10.3g} {:>8g} {:>9.3g} {:>9.4g} {:>7.3g} {:>7.3g} {:>7.3g} {:>7.3g} {:>12.3g} {:>10.3g}\n",
               r.body.name, r.body.mass_kg, r.body.radius_km, r.scales.e_g_GPa, r.scales.t_grav_s,
               r.scales.density_g_cm3, r.scales.v_c_km_s, r.e_g_over_E, r.estimates.strain,
               r.estimates.encounter_time / r.estimates.elastic_time, r.estimates.strain_rate / r.scales.t_grav_s);
  }
}

/// The material equivalents of the body a workflow builds (issue 12), built and stretched here
/// (nothing is written), in model units and, when `scales` is given, in physical units.
Json material_json(const Config& config) {
  const Checkpoint built = build_stage(config);
  const Checkpoint stretched = stretch_stage(built, config);
  const DerivedQuantities q = derive_quantities(built.body, built.state, config.interior.radius);
  const StabilityBound bound = stability_bound(stretched.body, stretched.state, strongest_damping(config));
  return {{"E_I", q.E_I},   {"E_2D", q.E_2D}, {"h_S", q.h_S},        {"D_F", q.D_F}, {"D_F_eq23", q.D_F_eq23},
          {"V_IP", q.V_IP}, {"V_SP", q.V_SP}, {"V_Co", q.V_Co},      {"M_S", q.M_S},
          {"dt", config.choose_dt ? 0.0 : config.integrator.dt},   {"dt_eq13", q.dt_max},
          {"dt_safe", bound.safe_dt},                               {"dt_unstable", bound.unstable_dt}};
}

void print_material(const Json& m, const std::string& workflow, const BodyScales* scales) {
  fmt::print("material equivalents of {} (the built body; G = M = R = 1{})\n", workflow,
             scales ? ", and in physical units" : "");
  const double eg = scales ? scales->e_g_GPa : 0, v = scales ? scales->v_c_km_s : 0, t = scales ? scales->t_grav_s : 0;
  auto line = [&](const char* name, const char* unit, const char* source, double x, double physical, const char* punit) {
    if (scales && punit[0] != '-') fmt::print("  {:<11} = {:<10.4g} {:<8} = {:.4g} {:<6} ({})\n", name, x, unit, physical, punit, source);
    else fmt::print("  {:<11} = {:<10.4g} {:<8} ({})\n", name, x, unit, source);
  };
  line("E_I", "e_g", "eq. 15", m["E_I"].get<double>(), m["E_I"].get<double>() * eg, "GPa");
  line("E_2D", "e_g R", "eq. 20", m["E_2D"].get<double>(), 0, "-");
  line("h_S", "R", "E_2D / E_I", m["h_S"].get<double>(), 0, "-");
  line("D_F", "e_g R^3", "hinge lattice, k_e / 4", m["D_F"].get<double>(), 0, "-");
  line("D_F_eq23", "e_g R^3", "eq. 23, k_e L_S / 2", m["D_F_eq23"].get<double>(), 0, "-");
  line("V_IP", "v_c", "eq. 16", m["V_IP"].get<double>(), m["V_IP"].get<double>() * v, "km/s");
  line("V_SP", "v_c", "eq. 19", m["V_SP"].get<double>(), m["V_SP"].get<double>() * v, "km/s");
  line("V_Co", "v_c", "eq. 25", m["V_Co"].get<double>(), m["V_Co"].get<double>() * v, "km/s");
  line("dt_eq13", "t_grav", "eq. 13, springs only", m["dt_eq13"].get<double>(), m["dt_eq13"].get<double>() * t, "s");
  line("dt_safe", "t_grav", "stretched body, springs + hinges + damping", m["dt_safe"].get<double>(),
       m["dt_safe"].get<double>() * t, "s");
  line("dt_unstable", "t_grav", "unstable above", m["dt_unstable"].get<double>(), m["dt_unstable"].get<double>() * t,
       "s");
}

/// Central and core-boundary pressure of the uniform and the layered body (issue 12), e_g.
Json layered_json(double core_radius, double density_ratio) {
  const LayeredSphere layered{core_radius, density_ratio};
  return {{"core_radius", core_radius},
          {"density_ratio", density_ratio},
          {"mantle_density", layered.mantle_density()},
          {"core_density", layered.core_density()},
          {"central_pressure_uniform", hydrostatic_pressure(0)},
          {"central_pressure_layered", layered.pressure(0)},
          {"core_boundary_pressure_layered", layered.pressure(core_radius)}};
}

}  // namespace

int command_estimate(int argc, char** argv) {
  cxxopts::Options options = command_options("estimate", "Without --body or --mass: all Table 1 bodies.");
  options.add_options()
      ("body",
       "a Table 1 body (Tethys, Dione, Rhea, Ariel, Titania, Charon, Mars) or a [moon] preset (Enceladus, Europa, "
       "Mimas, Miranda; docs/moon.md)",
       cxxopts::value<std::string>())
      ("mass", "body mass (kg), with --radius", cxxopts::value<std::string>())
      ("radius", "body radius (km), with --mass", cxxopts::value<std::string>())
      ("m2", "perturber mass (body masses; default 1)", cxxopts::value<std::string>())
      ("q", "--q: pericenter distance (body radii; default 2)", cxxopts::value<std::string>())
      ("vq", "speed at pericenter (v_c = sqrt(GM/R); default parabolic, sqrt(2 (1 + M2) / q): sqrt(2) at the defaults)",
       cxxopts::value<std::string>())
      ("youngs", "Young's modulus of the crust (GPa; default 0.9, Vaughan 1995)", cxxopts::value<std::string>())
      ("config", "also the material equivalents (E_I, E_2D, h_S, D_F, V_IP, V_SP, V_Co) and time-step bounds of "
                 "the body this workflow builds", cxxopts::value<std::string>())
      ("core-radius", "also the hydrostatic pressure of a body with a core of this radius (R)",
       cxxopts::value<std::string>())
      ("core-density-ratio", "core density / mantle density, with --core-radius (default 3)",
       cxxopts::value<std::string>())
      ("json", "print one JSON object")
      ("h,help", "show this help");
  const auto parsed = parse_arguments(options, argc, argv);
  if (parsed.count("help")) {
    fmt::print("{}", options.help());
    return exit_ok;
  }

  Encounter geometry = grazing_parabolic_encounter();
  geometry.perturber_mass = positive_option(parsed, "m2", geometry.perturber_mass, /*allow_zero=*/true);
  geometry.pericenter = positive_option(parsed, "q", geometry.pericenter);
  geometry.pericenter_speed =
      positive_option(parsed, "vq", parabolic_speed(geometry.perturber_mass, geometry.pericenter));
  const double youngs_GPa = positive_option(parsed, "youngs", ice_youngs_modulus_GPa);

  const bool has_mass = parsed.count("mass") > 0, has_radius = parsed.count("radius") > 0;
  if (parsed.count("body") && (has_mass || has_radius))
    throw InputError("--body cannot be combined with --mass/--radius");
  if (has_mass != has_radius)
    throw InputError(has_mass ? "--mass needs --radius (km)" : "--radius needs --mass (kg)");

  std::vector<BodyReport> reports;
  if (parsed.count("body")) {
    reports.push_back(report_for(find_named_body(parsed["body"].as<std::string>()), geometry, youngs_GPa));
  } else if (has_mass) {
    const double mass = positive_option(parsed, "mass", 0);
    const double radius = positive_option(parsed, "radius", 0);
    reports.push_back(report_for(body_from_mass_radius(mass, radius), geometry, youngs_GPa));
  } else {
    for (const auto& body : table1_bodies()) reports.push_back(report_for(body, geometry, youngs_GPa));
  }
  const bool single = parsed.count("body") || has_mass;

  std::optional<Json> material, layered;
  if (parsed.count("config")) {
    const std::string file = parsed["config"].as<std::string>();
    material = material_json(load_config(file));
  }
  if (parsed.count("core-radius")) {
    const double rc = positive_option(parsed, "core-radius", 0);
    if (rc >= 1) throw InputError(fmt::format("--core-radius must be < 1 (R), got {}", rc));
    layered = layered_json(rc, positive_option(parsed, "core-density-ratio", 3.0));
  } else if (parsed.count("core-density-ratio")) {
    throw InputError("--core-density-ratio needs --core-radius");
  }

  if (parsed.count("json")) {
    Json json = {{"encounter", inputs_json(geometry, youngs_GPa)}};
    if (material) json["material"] = *material;
    if (layered) json["layered"] = *layered;
    if (single) {
      json.update(body_json(reports.front()));
    } else {
      json["bodies"] = Json::array();
      for (const auto& r : reports) json["bodies"].push_back(body_json(r));
    }
    fmt::print("{}", json_text(json));
  } else if (single) {
    print_body(reports.front(), geometry, youngs_GPa);
  } else {
    print_table(reports, geometry, youngs_GPa);
  }
  if (!parsed.count("json")) {
    if (material) print_material(*material, parsed["config"].as<std::string>(), single ? &reports.front().scales : nullptr);
    if (layered) {
      const Json& l = *layered;
      fmt::print("layered body (core radius {:g} R, {:g}x the mantle density): central pressure {:.4g} e_g (uniform "
                 "body {:.4g} e_g), {:.4g} e_g at the core boundary{}\n",
                 l["core_radius"].get<double>(), l["density_ratio"].get<double>(),
                 l["central_pressure_layered"].get<double>(), l["central_pressure_uniform"].get<double>(),
                 l["core_boundary_pressure_layered"].get<double>(),
                 single ? fmt::format("; central pressure {:.4g} GPa",
                                      l["central_pressure_layered"].get<double>() * reports.front().scales.e_g_GPa)
                        : std::string());
    }
  }
  return exit_ok;
}

}  // namespace tidalcrust
