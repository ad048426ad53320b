#include "analysis/fracture_analysis.hpp"

#include <Eigen/Geometry>  // cross()
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include "base/errors.hpp"
#include "physics/orbital_frame.hpp"
#include "physics/spin_frame.hpp"
#include "model/config.hpp"
#include "bodies/shell_topology.hpp"

namespace tidalcrust {

namespace {
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

bool is_failed_shell_spring(const Body& body, const State& state, std::size_t s) {
  return body.spring_kind[s] == static_cast<std::uint8_t>(SpringKind::shell) &&
         state.springs.failed[s] != 0;
}

/// Union-find over spring indices with path halving; the root is the smallest index.
struct DisjointSets {
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  std::size_t find(std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void unite(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
  std::vector<std::size_t> parent;
};

double great_circle_extent(const std::vector<Vec3>& points) {
  std::vector<Vec3> directions;
  directions.reserve(points.size());
  for (const Vec3& p : points) directions.push_back(p.normalized());
  double largest = 0;
  for (std::size_t i = 0; i < directions.size(); ++i)
    for (std::size_t j = i + 1; j < directions.size(); ++j)
      largest = std::max(largest, std::acos(std::clamp(directions[i].dot(directions[j]), -1.0, 1.0)));
  return largest;
}
}  // namespace

std::vector<double> FractureSummary::angles_from_subsatellite_deg() const {
  std::vector<double> angles;
  angles.reserve(failed.size());
  for (const auto& f : failed) angles.push_back(f.angle_from_subsatellite_deg);
  return angles;
}

FractureSummary analyze_fractures(const Body& body, const State& state, const FractureScope& scope) {
  if (state.springs.failed.size() != body.spring_count() || state.position.size() != 3 * body.particle_count())
    throw InputError(fmt::format("state: {} failed flags and {} positions for a body of {} springs and {} particles",
                                 state.springs.failed.size(), state.position.size() / 3, body.spring_count(),
                                 body.particle_count()));
  if (!scope.earlier.empty() && scope.earlier.size() != body.spring_count())
    throw InputError(fmt::format("fracture scope: {} earlier-failure flags for a body of {} springs",
                                 scope.earlier.size(), body.spring_count()));
  const auto counted = [&](std::size_t s) {
    return is_failed_shell_spring(body, state, s) && (scope.earlier.empty() || !scope.earlier[s]);
  };
  const Vec3& subsatellite = scope.subsatellite;
  const ShellTopology topology = shell_topology(body);
  const Vec3 center = body_center_of_mass(body, state);
  const Matrix3& to_body = scope.to_body;
  auto position = [&](std::int32_t i) {
    return Vec3(to_body * (vec3_at(state.position, static_cast<std::size_t>(i)) - center));
  };

  FractureSummary summary;
  summary.shell_springs = body.count_springs(SpringKind::shell);
  std::size_t on_subsatellite_hemisphere = 0;
  double angle_sum = 0;
  for (std::size_t s = 0; s < body.spring_count(); ++s) {
    if (!counted(s)) {
      if (is_failed_shell_spring(body, state, s)) summary.earlier_failed.push_back(static_cast<std::int32_t>(s));
      continue;
    }
    FailedShellSpring f;
    f.spring = static_cast<std::int32_t>(s);
    f.midpoint = 0.5 * (position(body.springs[s][0]) + position(body.springs[s][1]));
    f.longitude_deg = longitude_deg(f.midpoint);
    f.latitude_deg = latitude_deg(f.midpoint);
    f.angle_from_subsatellite_deg = angle_from_subsatellite_deg(f.midpoint, subsatellite);
    f.crack_azimuth_deg =
        crack_azimuth_deg(f.midpoint, position(body.springs[s][1]) - position(body.springs[s][0]), subsatellite);
    on_subsatellite_hemisphere += f.midpoint.dot(subsatellite) > 0;
    angle_sum += f.angle_from_subsatellite_deg;
    const auto bin = std::min(summary.angle_bins - 1,
                              static_cast<std::size_t>(f.angle_from_subsatellite_deg / summary.angle_bin_width_deg));
    ++summary.angle_histogram[bin];
    summary.failed.push_back(f);
  }
  const double count = static_cast<double>(summary.failed.size());
  summary.fraction_shell = summary.shell_springs ? count / static_cast<double>(summary.shell_springs) : nan;
  summary.hemisphere_fraction = count > 0 ? static_cast<double>(on_subsatellite_hemisphere) / count : nan;
  summary.mean_angle_from_subsatellite_deg = count > 0 ? angle_sum / count : nan;
  std::vector<double> angles = summary.angles_from_subsatellite_deg();
  std::sort(angles.begin(), angles.end());
  const std::size_t n = angles.size();
  summary.median_angle_from_subsatellite_deg =
      n == 0 ? nan : (n % 2 ? angles[n / 2] : 0.5 * (angles[n / 2 - 1] + angles[n / 2]));

  // Dual-lattice bars, and clusters: failed edges of one face are joined at its centroid. Each
  // face also gives a third of its area to each of its three edge springs.
  DisjointSets sets(body.spring_count());
  std::vector<double> spring_area(body.spring_count(), 0.0);
  double shell_area = 0;
  for (std::size_t f = 0; f < body.faces.size(); ++f) {
    const auto& face = body.faces[f];
    const Vec3 centroid = (position(face[0]) + position(face[1]) + position(face[2])) / 3.0;
    const double area = 0.5 * (position(face[1]) - position(face[0])).cross(position(face[2]) - position(face[0])).norm();
    shell_area += area;
    for (int k = 0; k < 3; ++k) spring_area[static_cast<std::size_t>(topology.face_edge_spring[f][k])] += area / 3.0;
    std::int32_t first_failed = -1;
    for (int k = 0; k < 3; ++k) {
      const std::int32_t s = topology.face_edge_spring[f][k];
      if (!is_failed_shell_spring(body, state, static_cast<std::size_t>(s))) continue;
      const Vec3 midpoint = 0.5 * (position(face[k]) + position(face[(k + 1) % 3]));
      if (!counted(static_cast<std::size_t>(s))) {
        summary.earlier_bars.push_back({static_cast<std::int32_t>(f), s, centroid, midpoint});
        continue;
      }
      summary.bars.push_back({static_cast<std::int32_t>(f), s, centroid, midpoint});
      if (first_failed < 0) first_failed = s;
      sets.unite(static_cast<std::size_t>(first_failed), static_cast<std::size_t>(s));
    }
  }

  double failed_area = 0;
  for (const auto& f : summary.failed) failed_area += spring_area[static_cast<std::size_t>(f.spring)];
  summary.failed_area_fraction = shell_area > 0 ? failed_area / shell_area : nan;
  for (const auto& bar : summary.bars) summary.total_crack_length += (bar.edge_midpoint - bar.centroid).norm();

  std::vector<std::int64_t> cluster_of_root(body.spring_count(), -1);
  for (const auto& f : summary.failed) {
    const std::size_t root = sets.find(static_cast<std::size_t>(f.spring));
    if (cluster_of_root[root] < 0) {
      cluster_of_root[root] = static_cast<std::int64_t>(summary.clusters.size());
      summary.clusters.emplace_back();
    }
    summary.clusters[static_cast<std::size_t>(cluster_of_root[root])].springs.push_back(f.spring);
  }
  std::vector<std::vector<Vec3>> cluster_centroids(summary.clusters.size());
  for (const auto& bar : summary.bars) {
    const auto c = static_cast<std::size_t>(cluster_of_root[sets.find(static_cast<std::size_t>(bar.spring))]);
    summary.clusters[c].length += (bar.edge_midpoint - bar.centroid).norm();
    auto& centroids = cluster_centroids[c];
    // Bars of one face are consecutive and share the centroid: store it once.
    if (centroids.empty() || centroids.back() != bar.centroid) centroids.push_back(bar.centroid);
  }
  for (std::size_t c = 0; c < summary.clusters.size(); ++c)
    summary.clusters[c].extent = great_circle_extent(cluster_centroids[c]);
  // Clusters were created in order of their smallest spring; a stable sort keeps that for ties.
  std::stable_sort(summary.clusters.begin(), summary.clusters.end(),
                   [](const CrackCluster& a, const CrackCluster& b) { return a.length > b.length; });
  if (!summary.clusters.empty()) {
    summary.longest_crack_length = summary.clusters.front().length;
    summary.longest_crack_extent = summary.clusters.front().extent;
  }

  // Crack geometry: each cluster by its failed springs' midpoints (ascending spring order), every
  // failed spring's crack azimuth.
  std::vector<std::vector<Vec3>> cluster_points;
  std::vector<double> cluster_lengths, cluster_extents, azimuths;
  for (const auto& cluster : summary.clusters) {
    cluster_points.emplace_back();
    for (const std::int32_t s : cluster.springs) {
      const auto f = std::lower_bound(summary.failed.begin(), summary.failed.end(), s,
                                      [](const FailedShellSpring& a, std::int32_t b) { return a.spring < b; });
      cluster_points.back().push_back(f->midpoint);
    }
    cluster_lengths.push_back(cluster.length);
    cluster_extents.push_back(cluster.extent);
  }
  for (const auto& f : summary.failed) azimuths.push_back(f.crack_azimuth_deg);
  summary.geometry = crack_geometry(cluster_points, cluster_lengths, cluster_extents, azimuths, subsatellite);
  summary.subsatellite = subsatellite;
  return summary;
}

double stored_spin(const Checkpoint& c, const std::string& origin) {
  if (c.config_toml.empty()) return 0;  // a checkpoint made in memory (tests), not by a stage
  return parse_config(c.config_toml, origin + ":/parameters/config").spin.rate();
}

FractureScope fracture_scope(const Checkpoint& c, bool in_body_frame) {
  FractureScope scope;
  const auto* record = std::get_if<EncounterRecord>(&c.stage.record);
  if (!record) return scope;
  scope.subsatellite = subsatellite_direction_of(record->orbit);
  if (const double spin = in_body_frame ? stored_spin(c) : 0.0; spin != 0) {
    scope.to_body = spin_rotation(spin, c.state.time).transpose();
    scope.subsatellite = spin_rotation(spin, record->pericenter_time).transpose() * scope.subsatellite;
  }
  if (!record->encounter.after) return scope;
  // An encounter of a history: what failed before it began is every failed spring its own
  // failure log does not name.
  scope.earlier.assign(c.body.spring_count(), false);
  for (std::size_t s = 0; s < c.body.spring_count() && s < c.state.springs.failed.size(); ++s)
    scope.earlier[s] = c.state.springs.failed[s] != 0;
  for (const FailureEvent& e : c.observables.failures)
    if (e.spring >= 0 && static_cast<std::size_t>(e.spring) < scope.earlier.size())
      scope.earlier[static_cast<std::size_t>(e.spring)] = false;
  return scope;
}

FractureSummary analyze_fractures(const Checkpoint& c) { return analyze_fractures(c.body, c.state, fracture_scope(c)); }

Json failure_summary_json(const FractureSummary& summary) {
  const CrackGeometry& g = summary.geometry;
  const SmallCircleFit longest = g.arcs.empty() ? SmallCircleFit{} : g.arcs.front().fit;
  // The crack-geometry keys hold null where undefined, so that two summaries compare equal.
  const auto number = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
  return {{"count", summary.count()},
          {"fraction_shell", summary.fraction_shell},
          {"hemisphere_fraction", summary.hemisphere_fraction},
          {"mean_angle_from_subsatellite_deg", summary.mean_angle_from_subsatellite_deg},
          {"median_angle_from_subsatellite_deg", summary.median_angle_from_subsatellite_deg},
          {"largest_network_length", summary.longest_crack_length},
          {"largest_network_extent", summary.longest_crack_extent},
          {"clusters", summary.clusters.size()},
          {"total_crack_length", summary.total_crack_length},
          {"failed_area_fraction", summary.failed_area_fraction},
          {"concentricity", number(g.orientations.concentricity)},
          {"crack_rose_peak_deg", number(g.orientations.rose_peak_deg)},
          {"fitted_arcs", g.arcs.size()},
          {"median_arc_radius_deg", number(g.median_arc_radius_deg)},
          {"median_arc_pole_axis_from_subsatellite_deg", number(g.median_pole_axis_from_subsatellite_deg)},
          {"longest_arc_radius_deg", number(longest.radius_deg)},
          {"longest_arc_pole_axis_from_subsatellite_deg", number(longest.pole_axis_from_subsatellite_deg)},
          {"longest_arc_span_deg", number(longest.arc_deg)},
          {"longest_arc_misfit_deg", number(longest.rms_misfit_deg)}};
}

std::string_view failure_summary_unit(std::string_view key) {
  if (key.starts_with("largest_network") || key == "total_crack_length") return "R";
  return key.ends_with("_deg") ? "deg" : "1";
}

Json crack_polylines_json(const FractureSummary& summary, const std::string& state_hash) {
  const auto lon_lat = [](const Vec3& r) { return Json::array({longitude_deg(r), latitude_deg(r)}); };
  // Each failed spring's polyline through its bars (one per face it borders, in face order):
  // centroid, edge midpoint, the next centroid.
  const auto polylines_of = [&](const std::vector<CrackBar>& all_bars, const std::vector<std::int32_t>& springs) {
    std::map<std::int32_t, std::vector<const CrackBar*>> bars_of_spring;
    for (const auto& bar : all_bars) bars_of_spring[bar.spring].push_back(&bar);
    Json polylines = Json::array();
    for (const std::int32_t s : springs) {
      const auto& bars = bars_of_spring[s];
      Json line = Json::array();
      if (!bars.empty()) line.push_back(lon_lat(bars[0]->centroid)), line.push_back(lon_lat(bars[0]->edge_midpoint));
      for (std::size_t k = 1; k < bars.size(); ++k) line.push_back(lon_lat(bars[k]->centroid));
      polylines.push_back(std::move(line));
    }
    return polylines;
  };
  Json cracks = Json::array();
  for (std::size_t c = 0; c < summary.clusters.size(); ++c) {
    const CrackCluster& cluster = summary.clusters[c];
    cracks.push_back({{"crack", c},
                      {"springs", cluster.springs},
                      {"length", cluster.length},
                      {"extent", cluster.extent},
                      {"polylines", polylines_of(summary.bars, cluster.springs)}});
  }
  return {{"format", "tidalcrust-cracks"},
          {"version", 1},
          {"frame", "the maps' frame: planetocentric longitude and latitude of directions from the body's centre of "
                    "mass; for the paper's orbit the subsatellite point (the perturber at pericenter) is at longitude "
                    "+90, latitude 0 and the orbital plane is the equator; `subsatellite` gives this encounter's "
                    "(docs/crack-geometry.md)"},
          {"units", {{"longitude", "deg"}, {"latitude", "deg"}, {"length", "R"}, {"extent", "R (unit sphere)"}}},
          {"state_hash", state_hash},
          {"crack_count", summary.clusters.size()},
          {"cracks", std::move(cracks)},
          {"subsatellite", lon_lat(summary.subsatellite)},
          {"earlier", {{"springs", summary.earlier_failed}, {"polylines", polylines_of(summary.earlier_bars, summary.earlier_failed)}}}};
}

}  // namespace tidalcrust
