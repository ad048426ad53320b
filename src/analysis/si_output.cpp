#include "analysis/si_output.hpp"

#include <fmt/format.h>

#include <numbers>

#include "analysis/fracture_analysis.hpp"
#include "physics/orbital_frame.hpp"

namespace tidalcrust {

namespace {

constexpr double radians_per_degree = std::numbers::pi / 180;

/// `value` (a number or null) in the output unit of `dimension`.
Json output_value(const Json& value, Dimension dimension, const ModelUnits& units) {
  return value.is_number() ? Json(model_to_output(units, dimension, value.get<double>())) : Json(nullptr);
}

/// A time of the model's clock (t_grav) as hours from pericenter (`pericenter_time`, t_grav).
Json hours_from_pericenter(const Json& time, double pericenter_time, const ModelUnits& units) {
  return time.is_number() ? output_value(Json(time.get<double>() - pericenter_time), Dimension::time, units)
                          : Json(nullptr);
}

}  // namespace

std::string si_units_text(const MoonScale& moon) {
  return fmt::format(
      "SI for the moon ({}: R = {:g} km, M = {:g} kg, G = {:g} m^3 kg^-1 s^-2): lengths in km, masses in kg, speeds in km/s, "
      "times in hours (from pericenter where named so), energies in J; each the model value beside it times its "
      "model unit (R, M, v_c = sqrt(GM/R), t_grav = sqrt(R^3/(GM)), G M^2/R; docs/moon.md)",
      moon.name, moon.units.radius_m / 1e3, moon.units.mass_kg, gravitational_constant_si);
}

Json moon_json(const MoonScale& moon) {
  const ModelUnits& u = moon.units;
  return {{"name", moon.name},
          {"radius_km", model_to_output(u, Dimension::length, 1)},
          {"mass_kg", model_to_output(u, Dimension::mass, 1)},
          {"mean_density_kg_m3", u.mean_density_kg_m3},
          {"t_grav_s", u.time_s},
          {"v_c_km_s", model_to_output(u, Dimension::speed, 1)},
          {"e_g_Pa", u.modulus_Pa},
          {"energy_unit_J", u.energy_J},
          {"G", gravitational_constant_si}};
}

Json si_values(const Json& model, std::span<const ModelKey> keys, const ModelUnits& units) {
  Json out = Json::object();
  for (const auto& [key, dimension] : keys)
    if (const auto found = model.find(key); found != model.end())
      out[si_key(key, dimension)] = output_value(*found, dimension, units);
  return out;
}

Json failures_si_json(const Json& failures, const ModelUnits& units) {
  Json out = Json::object();
  for (const auto& [key, value] : failures.items())
    if (failure_summary_unit(key) == "R") out[si_key(key, Dimension::length)] = output_value(value, Dimension::length, units);
  return out;
}

Json summary_si_json(const MoonScale& moon, const Json& summary) {
  const ModelUnits& u = moon.units;
  const Json& encounter = summary.at("encounter");
  const double tq = encounter.at("pericenter_time").get<double>();
  static constexpr ModelKey encounter_keys[] = {{"perturber_mass", Dimension::mass},
                                                {"pericenter", Dimension::length},
                                                {"pericenter_speed", Dimension::speed},
                                                {"min_distance", Dimension::length},
                                                {"speed_at_min", Dimension::speed}};
  static constexpr ModelKey cluster_keys[] = {{"length", Dimension::length}, {"extent", Dimension::length}};
  static constexpr ModelKey arc_keys[] = {
      {"length", Dimension::length}, {"extent", Dimension::length}, {"arc_length", Dimension::length}};

  Json clusters = Json::array();
  for (const Json& cluster : summary.at("clusters")) clusters.push_back(si_values(cluster, cluster_keys, u));
  Json arcs = Json::array();
  for (const Json& arc : summary.at("crack_geometry").at("arcs")) {
    Json a = si_values(arc, arc_keys, u);
    // The small circle's angular radius as a distance along the surface.
    const Json& radius = arc.at("radius_deg");
    a["radius_km"] = radius.is_number() ? output_value(Json(radius.get<double>() * radians_per_degree),
                                                       Dimension::length, u)
                                        : Json(nullptr);
    const Json& pole = arc.at("pole_longitude_deg");
    a["pole_planetocentric_longitude_deg"] =
        pole.is_number() ? Json(planetocentric_longitude_deg(pole.get<double>())) : Json(nullptr);
    arcs.push_back(std::move(a));
  }
  const Json& trend = summary.at("failure_trend");
  Json energy = Json::object();
  for (const auto& [key, value] : summary.at("energy").items())
    if (value.is_number() || value.is_null()) energy[si_key(key, Dimension::energy)] = output_value(value, Dimension::energy, u);
  Json axis_times = Json::array();
  for (const Json& ratios : summary.at("principal_axis_ratios"))
    axis_times.push_back({{"time_from_pericenter_h", output_value(ratios.at("time_from_pericenter"), Dimension::time, u)}});
  Json encounter_si = si_values(encounter, encounter_keys, u);
  if (const auto orbit = encounter.find("orbit"); orbit != encounter.end() && orbit->contains("subsatellite_longitude_deg"))
    encounter_si["subsatellite_planetocentric_longitude_deg"] =
        planetocentric_longitude_deg(orbit->at("subsatellite_longitude_deg").get<double>());
  Json longitudes = Json::array();
  for (const Json& longitude : summary.at("failed_springs").at("longitude_deg"))
    longitudes.push_back(planetocentric_longitude_deg(longitude.get<double>()));

  return {{"units", si_units_text(moon)},
          {"moon", moon_json(moon)},
          {"map_frame",
           "planetocentric: latitude from the body's orbital plane, north toward its orbit normal; longitude "
           "east-positive from the subsatellite point at pericenter of the paper's orbit (the body frame's longitude "
           "- 90 deg), in (-180, 180]"},
          {"time_from_pericenter_h", hours_from_pericenter(summary.at("time"), tq, u)},
          {"encounter", encounter_si},
          {"failures", failures_si_json(summary.at("failures"), u)},
          {"clusters", clusters},
          {"crack_geometry", {{"arcs", arcs}}},
          {"failure_trend",
           {{"window_start_h", hours_from_pericenter(trend.at("window_start_time"), tq, u)},
            {"end_h", hours_from_pericenter(trend.at("end_time"), tq, u)},
            {"end_distance_km", output_value(trend.at("end_distance"), Dimension::length, u)}}},
          {"energy", energy},
          {"principal_axis_ratios", axis_times},
          {"failed_springs", {{"planetocentric_longitude_deg", longitudes}}}};
}

}  // namespace tidalcrust
