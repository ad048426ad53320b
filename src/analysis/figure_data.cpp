#include "analysis/figure_data.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>

#include <fmt/format.h>

#include "analysis/body_shape.hpp"
#include "analysis/crack_geometry.hpp"
#include "analysis/figure_text.hpp"
#include "analysis/fracture_analysis.hpp"
#include "analysis/recorded_track.hpp"
#include "analysis/si_output.hpp"
#include "model/center_of_mass.hpp"
#include "physics/conservation.hpp"
#include "physics/orbital_frame.hpp"
#include "physics/two_body_orbit.hpp"

namespace tidalcrust {

namespace {

/// Positions are drawn, not computed with: 1e-6 R is far below a pixel and keeps the file small.
double rounded(double v) { return std::isfinite(v) ? std::round(v * 1e6) / 1e6 : v; }
Json xyz(const Vec3& p) { return Json::array({rounded(p.x()), rounded(p.y()), rounded(p.z())}); }
Json xy(const Vec3& p) { return Json::array({rounded(p.x()), rounded(p.y())}); }

Vec3 perturber_offset(const Checkpoint& c, const Vec3& center) {
  const auto& p = c.state.perturber.position;
  return Vec3(p[0], p[1], p[2]) - center;
}

/// One hemisphere panel: the shell nodes (positions), the crack bars (3D, with their face), the
/// perturber; the faces themselves are the body's (the same for every panel).
Json hemisphere_panel(const Checkpoint& c, double pericenter_time, const std::vector<std::int32_t>& nodes,
                      const MoonScale* moon) {
  const Vec3 center = body_center_of_mass(c.body, c.state);
  // Drawn with the perturber: in the inertial frame, also of a spinning body.
  const FractureSummary fractures = analyze_fractures(c.body, c.state, fracture_scope(c, /*in_body_frame=*/false));
  Json positions = Json::array();
  for (const std::int32_t i : nodes) positions.push_back(xyz(vec3_at(c.state.position, static_cast<std::size_t>(i)) - center));
  Json bars = Json::array();
  for (const CrackBar& bar : fractures.bars)
    bars.push_back({{"face", bar.face}, {"from", xyz(bar.centroid)}, {"to", xyz(bar.edge_midpoint)}});
  const bool has_perturber = c.state.perturber.present && c.state.perturber.mass > 0;
  return {{"time_from_pericenter", c.state.time - pericenter_time},
          {"label", time_from_pericenter_text(c.state.time - pericenter_time, moon)},
          {"failed", fractures.count()},
          {"positions", positions},
          {"crack_bars", bars},
          {"perturber", has_perturber ? Json{{"position", xyz(perturber_offset(c, center))},
                                             {"radius", std::cbrt(c.state.perturber.mass)}}
                                      : Json(nullptr)}};
}

Json hemisphere_json(const std::vector<const Checkpoint*>& panels, double pericenter_time, const MoonScale* moon) {
  // The shell nodes, numbered in the order of their particle index; faces renumbered to them.
  const Body& body = panels.front()->body;
  std::vector<std::int32_t> nodes;
  for (const auto& f : body.faces) nodes.insert(nodes.end(), f.begin(), f.end());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  std::map<std::int32_t, std::size_t> local;
  for (std::size_t k = 0; k < nodes.size(); ++k) local[nodes[k]] = k;
  Json faces = Json::array();
  for (const auto& f : body.faces) faces.push_back({local[f[0]], local[f[1]], local[f[2]]});
  Json list = Json::array();
  for (const Checkpoint* c : panels) list.push_back(hemisphere_panel(*c, pericenter_time, nodes, moon));
  return {{"view", "orthographic from +y (the subsatellite side) in the orbital plane, +z up: screen x = -x, y = z"},
          {"nodes", nodes},
          {"faces", faces},
          {"panels", list}};
}

/// Figure 7: the simulated track (timeseries perturber_offset) or the analytic two-body track.
Json orbit_json(const Checkpoint& checkpoint, const EncounterRecord& record, const std::vector<double>& snapshot_times,
                const MoonScale* moon) {
  constexpr double tick_interval = 0.1;  ///< t_grav between diamonds (as in the paper)
  constexpr double max_ticks = 400;      ///< a longer track gets a whole multiple of the interval
  double t_start = checkpoint.stage.clock.start_time, t_end = checkpoint.state.time;
  if (!(t_end > t_start)) t_start = record.pericenter_time - 1.5, t_end = record.pericenter_time + 1.5;
  const double tq = record.pericenter_time;
  const TwoBodyOrbit orbit =
      perturber_orbit(record.encounter.perturber_mass, record.encounter.pericenter, record.encounter.pericenter_speed);
  auto analytic = [&](double t) { return orbit.state_at_time(t - tq).position; };
  const RecordedTrack recorded(checkpoint.observables.timeseries);
  const bool simulated = !recorded.empty();
  auto position = [&](double t) { return recorded.covers(t) ? recorded.position_at(t) : analytic(t); };

  Json analytic_track = Json::array();
  constexpr int track_points = 600;
  for (int i = 0; i <= track_points; ++i)
    analytic_track.push_back(xy(analytic(t_start + (t_end - t_start) * static_cast<double>(i) / track_points)));
  const double span = t_end - t_start;
  const double interval =
      span / tick_interval > max_ticks ? tick_interval * std::ceil(span / (tick_interval * max_ticks)) : tick_interval;
  const double tick_count = std::isfinite(span / interval) ? std::floor(span / interval + 1e-9) : 0;
  Json ticks = Json::array();
  for (long k = 0; k <= static_cast<long>(std::clamp(tick_count, 0.0, max_ticks)); ++k) {
    const double t = t_start + static_cast<double>(k) * interval;
    if (!simulated || recorded.covers(t)) ticks.push_back(xy(position(t)));
  }
  Json snapshots = Json::array();
  for (const double t : snapshot_times) snapshots.push_back(xy(position(t)));

  Json track = analytic_track;
  double max_deviation = 0;
  Vec3 pericenter = analytic(tq), direction = (analytic(tq + 0.02) - pericenter).normalized();
  if (simulated) {
    track = Json::array();
    const auto& times = recorded.times();
    const auto& points = recorded.positions();
    std::size_t nearest = 0;
    for (std::size_t i = 0; i < times.size(); ++i) {
      track.push_back(xy(points[i]));
      max_deviation = std::max(max_deviation, (points[i] - analytic(times[i])).norm());
      if (points[i].norm() < points[nearest].norm()) nearest = i;
    }
    pericenter = points[nearest];
    const std::size_t before = nearest > 0 ? nearest - 1 : nearest;
    const std::size_t after = nearest + 1 < times.size() ? nearest + 1 : nearest;
    direction = after > before ? Vec3((points[after] - points[before]).normalized()) : Vec3(Vec3::UnitX());
  }
  const Vec3 center = body_center_of_mass(checkpoint.body, checkpoint.state);
  return {{"simulated", simulated},
          {"track", track},
          {"analytic_track", analytic_track},
          {"max_deviation", max_deviation},
          {"tick_every", interval},
          {"ticks", ticks},
          {"snapshots", snapshots},
          {"snapshot_radius", std::cbrt(record.encounter.perturber_mass)},
          {"pericenter", xy(pericenter)},
          {"direction", xy(direction)},
          {"stored_position", checkpoint.state.perturber.present ? xy(perturber_offset(checkpoint, center)) : Json(nullptr)},
          {"stored_label", "stored position, " + time_from_pericenter_text(checkpoint.state.time - tq, moon)}};
}

/// Cumulative failed shell springs: a step function of the failure events, else the samples.
Json failures_json(const Checkpoint& checkpoint, double pericenter_time) {
  std::vector<double> t, n;
  const double t_start = checkpoint.stage.clock.start_time - pericenter_time;
  const double t_end = checkpoint.state.time - pericenter_time;
  const auto& events = checkpoint.observables.failures;
  const auto& samples = checkpoint.observables.timeseries;
  const bool from_events = !events.empty() || samples.empty();
  if (from_events) {
    std::vector<double> times;
    for (const auto& e : events) times.push_back(e.time - pericenter_time);
    std::sort(times.begin(), times.end());
    t.push_back(std::min(t_start, times.empty() ? t_start : times.front())), n.push_back(0);
    for (std::size_t i = 0; i < times.size(); ++i) {
      t.push_back(times[i]), n.push_back(static_cast<double>(i));
      t.push_back(times[i]), n.push_back(static_cast<double>(i + 1));
    }
    t.push_back(std::max(t_end, t.back())), n.push_back(static_cast<double>(times.size()));
  } else {
    for (const auto& s : samples) t.push_back(s.time - pericenter_time), n.push_back(static_cast<double>(s.failed));
  }
  return {{"source", from_events ? "events" : "samples"},
          {"note", from_events ? "cumulative failure events (/checkpoint/failures)" : "sampled counts (/checkpoint/timeseries)"},
          {"events", events.size()},
          {"time_from_pericenter", t},
          {"failed", n}};
}

/// The energy budget's conserved total relative to the binding energy (the kinetic energy's
/// relative change for a record without the budget), |P - P0| and |L - L0|.
Json conservation_json(const Checkpoint& checkpoint, double pericenter_time) {
  const auto& samples = checkpoint.observables.timeseries;
  const bool budget = !samples.empty() && std::isfinite(samples.front().conserved_energy());
  Json t = Json::array(), energy = Json::array(), momentum = Json::array(), angular = Json::array();
  for (const auto& s : samples) {
    const auto& first = samples.front();
    t.push_back(s.time - pericenter_time);
    if (budget)
      energy.push_back((s.conserved_energy() - first.conserved_energy()) / uniform_sphere_binding_energy);
    else
      energy.push_back(first.kinetic_energy != 0 ? (s.kinetic_energy - first.kinetic_energy) / first.kinetic_energy
                                                 : s.kinetic_energy - first.kinetic_energy);
    double dp = 0, dl = 0;
    for (int k = 0; k < 3; ++k) {
      dp += (s.momentum[k] - first.momentum[k]) * (s.momentum[k] - first.momentum[k]);
      dl += (s.angular_momentum[k] - first.angular_momentum[k]) * (s.angular_momentum[k] - first.angular_momentum[k]);
    }
    momentum.push_back(std::sqrt(dp));
    angular.push_back(std::sqrt(dl));
  }
  return {{"budget", budget},
          {"energy_label", budget ? "(E \u2212 E\u2080)/(3/5 GM\u00b2/R)" : "(K \u2212 K\u2080)/K\u2080"},
          {"note", samples.empty() ? "no timeseries samples stored"
                   : budget ? "body + perturber about the origin; E = K + U + damping and failure losses \u2212 hinge work"
                            : "body + perturber about the origin; K: kinetic energy (damping and tides change it)"},
          {"time_from_pericenter", t},
          {"energy", energy},
          {"momentum", momentum},
          {"angular_momentum", angular}};
}

using Point = std::array<double, 2>;

/// Convex hull of points in the plane, counter-clockwise (Andrew's monotone chain).
std::vector<Point> convex_hull(std::vector<Point> points) {
  auto cross = [](const Point& o, const Point& a, const Point& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  };
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  std::vector<Point> hull(2 * points.size());
  std::size_t k = 0;
  for (const Point& p : points) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

/// Figure 5: the body seen from +z, its outline (convex hull of all particles projected onto the
/// orbital plane), the springs with both ends within body_slice_half_width of the plane and those
/// particles, the perturber's direction in the plane.
Json body_slice_panel(const Checkpoint& c, double pericenter_time, const MoonScale* moon) {
  const Vec3 center = body_center_of_mass(c.body, c.state);
  const std::size_t n = c.body.particle_count();
  std::vector<Vec3> r(n);
  std::vector<Point> projected(n);
  for (std::size_t i = 0; i < n; ++i) r[i] = vec3_at(c.state.position, i) - center, projected[i] = {r[i].x(), r[i].y()};
  auto in_slice = [&](std::size_t i) { return std::abs(r[i].z()) < body_slice_half_width; };
  Json hull = Json::array(), springs = Json::array(), particles = Json::array();
  for (const Point& p : convex_hull(projected)) hull.push_back({rounded(p[0]), rounded(p[1])});
  for (const auto& [a, b] : c.body.springs) {
    const auto i = static_cast<std::size_t>(a), j = static_cast<std::size_t>(b);
    if (in_slice(i) && in_slice(j)) springs.push_back({xy(r[i]), xy(r[j])});
  }
  for (std::size_t i = 0; i < n; ++i)
    if (in_slice(i)) particles.push_back(xy(r[i]));
  Json direction = nullptr;
  if (c.state.perturber.present) {
    const Vec3 toward = perturber_offset(c, center);
    const double length = std::hypot(toward.x(), toward.y());
    if (length > 0) direction = {toward.x() / length, toward.y() / length};
  }
  const PrincipalAxes shape = principal_axes(c.body.mass, c.state.position);
  return {{"time_from_pericenter", c.state.time - pericenter_time},
          {"label", time_from_pericenter_text(c.state.time - pericenter_time, moon)},
          {"b_over_a", shape.b_over_a()},
          {"c_over_a", shape.c_over_a()},
          {"hull", hull},
          {"springs", springs},
          {"particles", particles},
          {"perturber_direction", direction}};
}

/// The fitted circles of the crack geometry on the map: each as [lon, lat] points every 2 deg of
/// its azimuth about the pole, the arc the crack covers and the rest of the circle.
Json crack_circles_json(const CrackGeometry& geometry) {
  constexpr double step_deg = 2;
  auto points = [&](const SmallCircleFit& fit, double from, double to) {
    Json list = Json::array();
    const int steps = std::max(1, static_cast<int>(std::ceil((to - from) / step_deg)));
    for (int i = 0; i <= steps; ++i) {
      const Vec3 p = point_on_circle(fit, from + (to - from) * i / steps);
      list.push_back({rounded(longitude_deg(p)), rounded(latitude_deg(p))});
    }
    return list;
  };
  Json arcs = Json::array();
  for (const CrackArc& arc : geometry.arcs)
    arcs.push_back({{"covered", points(arc.fit, 0, arc.fit.arc_deg)}, {"rest", points(arc.fit, arc.fit.arc_deg, 360)}});
  return arcs;
}

/// A round length for the maps' scale bar: 1, 2 or 5 times a power of ten, at most half the radius.
double scale_bar_length(double radius) {
  const double half = radius / 2, decade = std::pow(10.0, std::floor(std::log10(half)));
  for (const double m : {5.0, 2.0, 1.0})
    if (m * decade <= half) return m * decade;
  return decade;
}

/// How the maps show the surface, and where on them the encounter's subsatellite point lies
/// (`subsatellite`, a direction from the centre of mass): in the body's orbital frame (longitude
/// of cracks.json and summary.json), or for a moon in planetocentric longitude
/// (physics/orbital_frame.hpp) with a km scale bar.
Json map_json(const MoonScale* moon, const Vec3& subsatellite) {
  const double lon = longitude_deg(subsatellite), lat = latitude_deg(subsatellite);
  if (!moon)
    return {{"frame", "orbital"},
            {"longitude_shift_deg", 0},
            {"subsatellite", {lon, lat}},
            {"scale_bar", nullptr},
            {"note", fmt::format("top: Mollweide (equal-area), longitude and latitude in degrees in the body's frame; "
                                 "below: orthographic; ring: subsatellite point ({}\u00b0, {}\u00b0)",
                                 fixed_text(lon, 0), fixed_text(lat, 0))}};
  const double radius_km = model_to_output(moon->units, Dimension::length, 1);
  const double bar_km = scale_bar_length(radius_km);
  const double map_lon = planetocentric_longitude_deg(lon);
  return {{"frame", "planetocentric"},
          {"longitude_shift_deg", planetocentric_longitude_deg(0)},
          {"subsatellite", {map_lon, lat}},
          {"scale_bar",
           {{"length_km", bar_km},
            {"length_R", output_to_model(moon->units, Dimension::length, bar_km)},
            {"label", fmt::format("{:g} {}", bar_km, output_unit(Dimension::length).symbol)}}},
          {"note", fmt::format("top: Mollweide (equal-area); planetocentric latitude and longitude in degrees "
                               "(equator = the body's orbital plane, north = its orbit normal, longitude 0 = the "
                               "subsatellite point at pericenter of the paper's orbit, east positive); below: "
                               "orthographic; ring: subsatellite point ({}\u00b0, {}\u00b0); bars: {:g} km along the "
                               "equator at the centre; {} R = {:g} km, 10\u00b0 = {}",
                               fixed_text(map_lon, 0), fixed_text(lat, 0), bar_km, moon->name, radius_km,
                               si_text(std::numbers::pi / 18, Dimension::length, *moon))}};
}

/// figure_data.json's `units`: for the paper's orbit one frame for all; for another orientation
/// the figures of the body in the orbit's frame, the crack circles in the body's.
std::string figure_data_units(bool paper_orbit) {
  return paper_orbit ? "lengths in R relative to the body's centre of mass in the orbital frame (orbital plane = "
                       "equator, subsatellite point on +y, longitude +90); times in t_grav from pericenter; angles in "
                       "degrees"
                     : "lengths in R relative to the body's centre of mass; hemisphere, orbit and body_shape in the "
                       "encounter's orbital frame (orbital plane = xy, subsatellite point on +y), crack_geometry in "
                       "the body's frame of the maps (cracks.json); times in t_grav from pericenter; angles in degrees";
}

/// `c` seen in the frame of its encounter's orbit (turned by the transpose of orbit_rotation: the
/// orbit in the xy plane, pericenter on +y, as the paper's): positions, velocities, the perturber
/// and the recorded perturber offsets, with the record's orientation reset to the paper's.
Checkpoint in_orbit_frame(const Checkpoint& c) {
  Checkpoint out = c;
  auto* record = std::get_if<EncounterRecord>(&out.stage.record);
  if (!record || record->orbit.is_default()) return out;
  const Matrix3 back = orbit_rotation(record->orbit).transpose();
  for (std::vector<double>* flat : {&out.state.position, &out.state.velocity})
    for (std::size_t i = 0; 3 * i < flat->size(); ++i) set_vec3(*flat, i, back * vec3_at(*flat, i));
  for (std::array<double, 3>* v : {&out.state.perturber.position, &out.state.perturber.velocity}) {
    const Vec3 turned = back * Vec3((*v)[0], (*v)[1], (*v)[2]);
    *v = {turned.x(), turned.y(), turned.z()};
  }
  for (TimeseriesSample& sample : out.observables.timeseries) {
    const Vec3 turned = back * Vec3(sample.perturber_offset[0], sample.perturber_offset[1], sample.perturber_offset[2]);
    sample.perturber_offset = {turned.x(), turned.y(), turned.z()};
  }
  record->orbit = OrbitOrientation{};
  return out;
}

}  // namespace

Json figure_data_json(const Checkpoint& final_checkpoint, const EncounterRecord& record,
                      const std::vector<const Checkpoint*>& panels, const Json& titles, const std::string& state_hash,
                      const MoonScale* moon) {
  const FractureSummary fractures = analyze_fractures(final_checkpoint);  // the circles: in the maps' (body's) frame
  if (!record.orbit.is_default()) {
    // The hemisphere, orbit and body figures are drawn in the encounter's orbital frame, as for the
    // paper's orbit; the maps stay in the body's frame.
    std::vector<Checkpoint> turned;
    turned.reserve(panels.size());
    std::vector<const Checkpoint*> turned_panels;
    for (const Checkpoint* c : panels) turned.push_back(in_orbit_frame(*c)), turned_panels.push_back(&turned.back());
    const Checkpoint turned_final = in_orbit_frame(final_checkpoint);
    Json data = figure_data_json(turned_final, turned_final.stage.as<EncounterRecord>(), turned_panels, titles, state_hash,
                                 moon);
    data["crack_geometry"] = {{"circles", crack_circles_json(fractures.geometry)}};
    data["map"] = map_json(moon, fractures.subsatellite);
    data["units"] = figure_data_units(false);
    return data;
  }
  const double tq = record.pericenter_time;
  std::vector<double> panel_times;
  for (const Checkpoint* c : panels) panel_times.push_back(c->state.time);
  Json slices = Json::array();
  for (const Checkpoint* c : panels) slices.push_back(body_slice_panel(*c, tq, moon));
  return {{"format", "tidalcrust-figure-data"},
          {"version", 1},
          {"state_hash", state_hash},
          {"units", figure_data_units(true)},
          {"figures", encounter_figure_names()},
          {"titles", titles},
          {"pericenter_time", tq},
          {"hemisphere", hemisphere_json(panels, tq, moon)},
          {"orbit", orbit_json(final_checkpoint, record, panel_times, moon)},
          {"failures", failures_json(final_checkpoint, tq)},
          {"conservation", conservation_json(final_checkpoint, tq)},
          {"body_shape", {{"slice_half_width", body_slice_half_width}, {"panels", slices}}},
          {"crack_geometry", {{"circles", crack_circles_json(fractures.geometry)}}},
          {"map", map_json(moon, fractures.subsatellite)},
          {"time_axis",
           {{"label", time_axis_label(moon)},
            {"per_t_grav", moon ? model_to_output(moon->units, Dimension::time, 1) : 1.0},
            {"model_label", time_axis_label(nullptr)}}},
          {"length_axis",
           moon ? Json{{"unit", output_unit(Dimension::length).symbol},
                       {"per_R", model_to_output(moon->units, Dimension::length, 1)}}
                : Json(nullptr)},
          {"si", moon ? Json{{"units", si_units_text(*moon)}, {"moon", moon_json(*moon)}} : Json(nullptr)}};
}

}  // namespace tidalcrust
