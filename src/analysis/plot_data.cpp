#include "analysis/plot_data.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include "analysis/figure_text.hpp"
#include "base/errors.hpp"
#include "io/atomic_file.hpp"

namespace tidalcrust {

namespace {
Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

/// Edges of the cells around sorted grid values: midpoints between neighbours, half a spacing
/// beyond the ends (a single value gets +-`lone` around it).
std::vector<double> cell_edges(const std::vector<double>& values, double lone) {
  if (values.size() == 1) return {values[0] - lone, values[0] + lone};
  std::vector<double> edges{values[0] - 0.5 * (values[1] - values[0])};
  for (std::size_t i = 0; i + 1 < values.size(); ++i) edges.push_back(0.5 * (values[i] + values[i + 1]));
  edges.push_back(values.back() + 0.5 * (values.back() - values[values.size() - 2]));
  return edges;
}
}  // namespace

Json signal_plot_json(const std::string& name, const std::vector<double>& time, const std::vector<double>& signal,
                      const std::vector<TimeMark>& marks, const std::string& title, const std::string& y_label) {
  if (time.size() != signal.size() || time.size() < 2)
    throw InputError(name + ": a signal plot needs equally many times and values, at least two");
  Json mark_list = Json::array();
  for (const auto& m : marks) mark_list.push_back({{"time", m.time}, {"label", m.label}, {"measured", m.measured}});
  return {{"kind", "signal"}, {"title", title},  {"x_label", "t [t_grav]"}, {"y_label", y_label},
          {"time", time},     {"signal", signal}, {"marks", mark_list}};
}

Json tidal_strain_plot_json(const std::string& name, const std::vector<TidalStrainBin>& bins, double h2, double l2,
                            const std::string& title) {
  if (bins.empty()) throw InputError(name + ": a strain plot needs at least one band");
  Json gamma = Json::array(), meridional = Json::array(), azimuthal = Json::array();
  for (int i = 0; i <= 90; ++i) {
    const SurfaceStrain e = continuum_surface_strain(h2, l2, i * std::numbers::pi / 180);
    gamma.push_back(i), meridional.push_back(e.meridional), azimuthal.push_back(e.azimuthal);
  }
  Json bands = Json::array();
  for (const auto& b : bins)
    bands.push_back({{"gamma_deg", 0.5 * (b.gamma_low + b.gamma_high)},
                     {"meridional", b.measured_meridional},
                     {"azimuthal", b.measured_azimuthal}});
  return {{"kind", "tidal_strain"},
          {"title", title},
          {"x_label", "angle from the tidal axis gamma [deg]"},
          {"y_label", "strain per unit tidal strength"},
          {"theory", {{"gamma_deg", gamma}, {"meridional", meridional}, {"azimuthal", azimuthal}}},
          {"bands", bands}};
}

Json phase_diagram_json(const std::string& name, const SweepReport& report, double perturber_mass,
                        double failure_strain, bool crack_probability) {
  std::vector<const SweepRow*> rows;
  for (const auto& r : report.rows)
    if (r.encounter.perturber_mass == perturber_mass && r.failure_strain == failure_strain) rows.push_back(&r);
  if (rows.empty())
    throw InputError(fmt::format("{}: no encounter with M2 = {} and eps_S = {}", name, perturber_mass, failure_strain));
  const double youngs = report.youngs_modulus;
  // Cracked: in a probability diagram, more often than not.
  const auto cracked = [&](const SweepRow* r) {
    return crack_probability ? r->status == SweepStatus::finished && r->failed_fraction >= 0.5 : r->cracked();
  };
  // The axes: the grid, widened to where eq. 5 crosses strain = eps_S over its speeds (the impulse
  // estimate is an order of magnitude; at most to 4 q_hi).
  std::set<double> q_set, v_set;
  for (const SweepRow* r : rows) q_set.insert(r->encounter.pericenter), v_set.insert(r->encounter.pericenter_speed);
  const std::vector<double> qs(q_set.begin(), q_set.end()), vs(v_set.begin(), v_set.end());
  double q_lo = qs.front(), q_hi = qs.back();
  const auto eq5_q = [&](double speed) { return std::sqrt(perturber_mass / (std::sqrt(youngs) * speed * failure_strain)); };
  if (youngs > 0) {
    const double far = eq5_q(vs.front()), near = eq5_q(vs.back());
    if (std::isfinite(far)) q_hi = std::min(std::max(q_hi, 1.03 * far), 4 * q_hi);
    if (std::isfinite(near)) q_lo = std::max(std::min(q_lo, 0.97 * near), 0.5 * q_lo);
  }
  const double q_pad = std::max(0.08 * (q_hi - q_lo), 0.05), v_pad = std::max(0.08 * (vs.back() - vs.front()), 0.05);
  const double x0 = q_lo - q_pad, x1 = q_hi + q_pad;

  // The boundary: a cell edge between two finished neighbours, one cracked and one not.
  const std::vector<double> q_edges = cell_edges(qs, 0.1), v_edges = cell_edges(vs, 0.1);
  std::map<std::pair<std::size_t, std::size_t>, const SweepRow*> grid;
  for (const SweepRow* r : rows)
    if (r->status == SweepStatus::finished)
      grid[{static_cast<std::size_t>(std::lower_bound(qs.begin(), qs.end(), r->encounter.pericenter) - qs.begin()),
            static_cast<std::size_t>(std::lower_bound(vs.begin(), vs.end(), r->encounter.pericenter_speed) - vs.begin())}] =
          r;
  const auto differ = [&](std::pair<std::size_t, std::size_t> a, std::pair<std::size_t, std::size_t> b) {
    const auto ia = grid.find(a), ib = grid.find(b);
    return ia != grid.end() && ib != grid.end() && cracked(ia->second) != cracked(ib->second);
  };
  Json boundary = Json::array();
  for (std::size_t i = 0; i < qs.size(); ++i)
    for (std::size_t j = 0; j < vs.size(); ++j) {
      if (i + 1 < qs.size() && differ({i, j}, {i + 1, j}))
        boundary.push_back({{q_edges[i + 1], v_edges[j]}, {q_edges[i + 1], v_edges[j + 1]}});
      if (j + 1 < vs.size() && differ({i, j}, {i, j + 1}))
        boundary.push_back({{q_edges[i], v_edges[j + 1]}, {q_edges[i + 1], v_edges[j + 1]}});
    }
  Json line_q = Json::array(), line_v = Json::array();
  for (int k = 0; k <= 200; ++k) {
    const double q = x0 + (x1 - x0) * k / 200.0;
    line_q.push_back(q), line_v.push_back(perturber_mass / (std::sqrt(youngs) * q * q * failure_strain));
  }
  // Colour scale: [0, 1] of the share, else [0, the largest failed fraction] (at least 0.01).
  double top = 1;
  if (!crack_probability) {
    top = 0.01;
    for (const SweepRow* r : rows)
      if (r->status == SweepStatus::finished && std::isfinite(r->failed_fraction)) top = std::max(top, r->failed_fraction);
  }
  Json points = Json::array();
  std::size_t finished = 0;
  for (const SweepRow* r : rows) {
    finished += r->status == SweepStatus::finished;
    points.push_back({{"encounter", r->encounter.name},
                      {"q", r->encounter.pericenter},
                      {"v_q", r->encounter.pericenter_speed},
                      {"finished", r->status == SweepStatus::finished},
                      {"cracked", crack_probability || cracked(r)},
                      {"value", number(r->failed_fraction)}});
  }
  const std::string title = fmt::format(
      "{}: {}, M\u2082 = {} M, \u03b5_S = {}\n{} of {} {} finished; eq. 5 with E = E_I = {} e_g", report.workflow,
      crack_probability ? "share of ensemble members cracked" : "failed fraction of the shell springs",
      general_text(perturber_mass), general_text(failure_strain), finished, rows.size(),
      crack_probability ? "points" : "encounters", general_text(youngs, 3));
  return {{"kind", "phase_diagram"},
          {"title", title},
          {"x_label", "pericenter q [R]"},
          {"y_label", "pericenter speed V_q [\u221a(GM/R)]"},
          {"x_range", {x0, x1}},
          {"y_range", {vs.front() - v_pad, vs.back() + v_pad}},
          {"crack_probability", crack_probability},
          {"colour_label", crack_probability ? "crack probability" : "failed fraction"},
          {"colour_top", top},
          {"boundary_label", crack_probability ? "crack probability 1/2" : "crack/no-crack boundary"},
          {"points", points},
          {"boundary", boundary},
          {"eq5", {{"label", "eq. 5: strain = \u03b5_S"}, {"q", line_q}, {"v_q", line_v}}}};
}

Json fracture_map_row_json(const std::string& name, const std::vector<const FractureSummary*>& panels,
                           const std::vector<std::string>& state_hashes, const std::vector<std::string>& panel_titles,
                           const std::string& title) {
  if (panels.empty() || panel_titles.size() != panels.size() || state_hashes.size() != panels.size())
    throw InputError(fmt::format("{}: {} fracture maps with {} titles to draw", name, panels.size(), panel_titles.size()));
  Json list = Json::array();
  for (std::size_t i = 0; i < panels.size(); ++i)
    list.push_back({{"title", panel_titles[i]}, {"cracks", crack_polylines_json(*panels[i], state_hashes[i])}});
  return {{"kind", "fracture_map_row"}, {"title", title}, {"panels", list}};
}

std::filesystem::path write_figure_data_file(const std::filesystem::path& folder, const Json& figures) {
  const Json file = {{"format", "tidalcrust-figure-data"}, {"version", 1}, {"figures", figures}};
  write_file_atomically(folder / "figure_data.json", file.dump() + "\n");
  return folder / "figure_data.json";
}

}  // namespace tidalcrust
