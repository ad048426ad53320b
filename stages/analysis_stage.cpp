// Stage 5: fracture statistics, paper-style figures and conservation diagnostics of one
// encounter (paper section 3): figures (PNG + SVG) and summary.json in one folder.
#include "stages/analysis_stage.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "analysis/crust_statistics.hpp"
#include "analysis/conservation_drift.hpp"
#include "analysis/energy_budget.hpp"
#include "analysis/failure_trend.hpp"
#include "analysis/body_shape.hpp"
#include "base/errors.hpp"
#include "analysis/figure_data.hpp"
#include "analysis/figure_text.hpp"
#include "figures/figure_script.hpp"
#include "analysis/fracture_analysis.hpp"
#include "physics/spin_frame.hpp"
#include "physics/orbital_frame.hpp"
#include "analysis/fracture_comparison.hpp"
#include "analysis/si_output.hpp"
#include "io/atomic_file.hpp"
#include "io/json.hpp"
#include "io/checkpoint_names.hpp"
#include "io/state_hash.hpp"
#include "io/checkpoint_file.hpp"
#include "model/config.hpp"
#include "model/stage_fingerprint.hpp"

namespace tidalcrust {

namespace fs = std::filesystem;

namespace {


constexpr std::size_t max_snapshot_panels = 5;

struct Snapshot {
  std::unique_ptr<Checkpoint> checkpoint;
  fs::path file;
};

/// Mid-stage snapshots beside `from` that belong to the same encounter (same body, fingerprint
/// and parent, earlier step); unreadable or foreign files are reported, skipped and listed in
/// `skipped` (an analysis without them is not finished: analysis_is_current).
std::vector<Snapshot> load_snapshots(const fs::path& from, const Checkpoint& final_checkpoint,
                                     std::vector<std::string>& skipped) {
  std::vector<Snapshot> snapshots;
  for (const auto& found : find_snapshots(from)) {
    if (found.step >= final_checkpoint.state.step) continue;
    try {
      auto c = std::make_unique<Checkpoint>(read_checkpoint(found.file));
      if (!std::holds_alternative<EncounterRecord>(c->stage.record))
        throw InputError(fmt::format("{}: stage '{}' is not an encounter", found.file.string(), c->stage.name()));
      require_same_body(final_checkpoint.body, c->body, from.string(), found.file.string());
      // A snapshot left by a superseded run of this encounter (other values, dt or parent).
      if (!same_fingerprint(c->stage.fingerprint, final_checkpoint.stage.fingerprint) ||
          c->stage.parent_hash != final_checkpoint.stage.parent_hash)
        throw InputError(fmt::format("{}: belongs to another run of the encounter (its fingerprint or parent differs "
                                     "from {})", found.file.string(), from.string()));
      snapshots.push_back({std::move(c), found.file});
    } catch (const InputError& err) {
      fmt::print(stderr, "tidalcrust analyze: skipping snapshot: {}\n", err.what());
      skipped.push_back(found.file.filename().string());
    }
  }
  return snapshots;
}

std::string percent(double fraction) { return std::isfinite(fraction) ? fmt::format("{:.1f}%", 100 * fraction) : "n/a"; }

/// summary.json's `history`: null for an encounter that began from the relaxed body; for one that
/// came after another, that encounter's name, the springs failed before it began (left out of
/// `failures`) and the whole crust after it, every failed spring, about this encounter's
/// subsatellite point.
Json history_json(const Checkpoint& checkpoint, const EncounterRecord& record, const FractureSummary& fractures) {
  if (!record.encounter.after) return nullptr;
  FractureScope whole_crust = fracture_scope(checkpoint);  // its frame and subsatellite point, every failure
  whole_crust.earlier.clear();
  return {{"after", *record.encounter.after},
          {"earlier_failed", fractures.earlier_failed.size()},
          {"note", "failures counts this encounter's failures; all_failures every failed shell spring of the crust"},
          {"all_failures", failure_summary_json(analyze_fractures(checkpoint.body, checkpoint.state, whole_crust))}};
}

/// summary.json's `spin` of a spinning body (docs/spin.md; written only then): the spin, the
/// frame of the maps and statistics, the angle the body frame had turned at pericenter (by which
/// the subsatellite point of `orbit` lies west of the pericenter direction's longitude), the spin
/// measured at the end (the tide's torque changes it) and the final shape's flattening.
Json spin_json(const Checkpoint& checkpoint, const EncounterRecord& record, double spin) {
  const double deg = 180 / std::numbers::pi;
  const Vec3 measured = body_angular_velocity(checkpoint.body, checkpoint.state);
  const ShellFlattening shape =
      shell_flattening(checkpoint.body, checkpoint.state, spin_rotation(spin, checkpoint.state.time).transpose());
  const double start = checkpoint.stage.clock.start_time;
  return {{"angular_velocity", spin},
          {"frame", "body frame: x_body = Rz(Omega t)^T (x - x_cm), spin axis = +z (north); the failures, maps and "
                    "angles are in it, the subsatellite point at the pericenter time t_q"},
          {"turned_at_pericenter_deg", std::fmod(spin * record.pericenter_time * deg, 360.0)},
          {"turned_start_to_pericenter_deg", spin * (record.pericenter_time - start) * deg},
          {"turned_during_encounter_deg", spin * (checkpoint.state.time - start) * deg},
          {"final_angular_velocity", {measured.x(), measured.y(), measured.z()}},
          {"final_spin_change", measured.z() - spin},
          {"final_flattening", shape.flattening}};
}

}  // namespace

std::vector<fs::path> analyze_encounter(const fs::path& from, const Checkpoint& checkpoint, const fs::path& out,
                                        bool with_figures) {
  const EncounterRecord& record = stage_record<EncounterRecord>(checkpoint, from.string());
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec || !fs::is_directory(out)) throw InputError(fmt::format("{}: cannot create output folder: {}", out.string(), ec.message()));

  const std::optional<MoonScale> moon = stored_moon(checkpoint.config_toml, from.string() + ":/parameters/config");
  const FractureSummary fractures = analyze_fractures(checkpoint);
  const ConservationDrift drift = conservation_drift(checkpoint.observables.timeseries);
  const EnergyBudget budget = energy_budget(checkpoint.observables.timeseries, record.encounter);
  const FailureTrend trend =
      failure_trend(checkpoint.observables.failures, checkpoint.stage.clock.start_time, checkpoint.state.time);
  std::vector<std::string> skipped_snapshots;
  const std::vector<Snapshot> snapshots = load_snapshots(from, checkpoint, skipped_snapshots);

  // Snapshot row: mid-stage snapshots and the final state, at most a handful of panels.
  std::vector<const Checkpoint*> candidates;
  std::vector<fs::path> candidate_files;
  for (const auto& s : snapshots) candidates.push_back(s.checkpoint.get()), candidate_files.push_back(s.file);
  candidates.push_back(&checkpoint);
  candidate_files.push_back(from);
  std::vector<double> candidate_times;
  for (const auto* c : candidates) candidate_times.push_back(c->state.time);
  std::vector<const Checkpoint*> panels;
  std::vector<std::size_t> panel_indices =
      choose_snapshot_panels(candidate_times, record.pericenter_time, max_snapshot_panels);
  for (const std::size_t i : panel_indices) panels.push_back(candidates[i]);

  const std::string name = record.encounter.name.empty() ? from.stem().string() : record.encounter.name;
  const double t_after = checkpoint.state.time - record.pericenter_time;
  // Of a moon, the largest crack network in km on the map's title.
  const std::string largest_network =
      moon && fractures.count() > 0
          ? ", largest crack network " + si_text(fractures.longest_crack_length, Dimension::length, *moon)
          : "";
  auto title = [&](const std::string& headline) {
    return encounter_figure_title(headline, record.encounter, checkpoint.stage.clock, moon ? &*moon : nullptr);
  };
  // The figures' titles (two lines: headline, then the encounter's parameters and dt).
  const Json titles = {
      {"fracture_map",
       title(fmt::format("{}: {} failed shell springs ({}){}{}, {}", name, fractures.count(),
                         percent(fractures.fraction_shell),
                         record.encounter.after ? fmt::format(" after {} ({} earlier, grey)", *record.encounter.after,
                                                              fractures.earlier_failed.size())
                                                : std::string(),
                         largest_network, time_from_pericenter_text(t_after, moon ? &*moon : nullptr)))},
      {"hemisphere", title(name + ": hemisphere facing pericenter")},
      {"orbit", title(name + ": perturber orbit")},
      {"failures", title(name + ": shell spring failures")},
      {"conservation", title(name + ": conservation diagnostics")},
      {"body_shape", title(name + ": the body in the orbital plane")},
      {"axis_ratios", title(name + ": principal axis ratios")},
      {"crack_geometry",
       title(fmt::format("{}: crack geometry, {} fitted arcs, concentricity {}", name, fractures.geometry.arcs.size(),
                         std::isfinite(fractures.geometry.orientations.concentricity)
                             ? fixed_text(fractures.geometry.orientations.concentricity, 2)
                             : "n/a"))}};
  std::vector<fs::path> figures;
  for (const std::string& figure : encounter_figure_names())
    for (const char* extension : {".png", ".svg"}) figures.push_back(out / (figure + extension));
  const std::vector<fs::path> earlier_figures = figures;
  if (!with_figures) figures.clear();
  // Figure 5 (fig:mush): the body's shape at every snapshot and at the end.
  std::vector<double> shape_times;
  std::vector<PrincipalAxes> shapes;
  for (const auto* c : candidates) {
    shape_times.push_back(c->state.time - record.pericenter_time);
    shapes.push_back(principal_axes(c->body.mass, c->state.position));
  }
  Json shape_list = Json::array();
  for (std::size_t k = 0; k < shapes.size(); ++k)
    shape_list.push_back({{"time_from_pericenter", shape_times[k]},
                          {"b_over_a", shapes[k].b_over_a()},
                          {"c_over_a", shapes[k].c_over_a()}});

  Json failed_springs = {{"spring", Json::array()},
                         {"longitude_deg", Json::array()},
                         {"latitude_deg", Json::array()},
                         {"angle_from_subsatellite_deg", Json::array()},
                         {"crack_azimuth_deg", Json::array()}};
  for (const auto& f : fractures.failed) {
    failed_springs["spring"].push_back(f.spring);
    failed_springs["longitude_deg"].push_back(f.longitude_deg);
    failed_springs["latitude_deg"].push_back(f.latitude_deg);
    failed_springs["angle_from_subsatellite_deg"].push_back(f.angle_from_subsatellite_deg);
    failed_springs["crack_azimuth_deg"].push_back(f.crack_azimuth_deg);
  }
  Json clusters = Json::array();
  for (const auto& cluster : fractures.clusters)
    clusters.push_back({{"springs", cluster.springs.size()}, {"length", cluster.length}, {"extent", cluster.extent}});
  Json snapshot_list = Json::array();
  for (const std::size_t i : panel_indices)
    snapshot_list.push_back(
        {{"file", candidate_files[i].string()}, {"step", candidates[i]->state.step}, {"time", candidates[i]->state.time}});
  Json figure_names = Json::array();
  for (const auto& f : figures) figure_names.push_back(f.filename().string());

  Json summary = {
      {"source", from.string()},
      {"stage", checkpoint.stage.name()},
      {"complete", checkpoint.stage.complete},
      {"time", checkpoint.state.time},
      {"step", checkpoint.state.step},
      {"state_hash", state_hash(checkpoint.state)},
      {"encounter",
       {{"name", record.encounter.name},
        {"perturber_mass", record.encounter.perturber_mass},
        {"pericenter", record.encounter.pericenter},
        {"pericenter_speed", record.encounter.pericenter_speed},
        {"pericenter_time", record.pericenter_time},
        {"min_distance", record.min_distance},
        {"speed_at_min", record.speed_at_min},
        {"after", record.encounter.after ? Json(*record.encounter.after) : Json(nullptr)},
        {"orbit",
         {{"inclination_deg", record.orbit.inclination},
          {"ascending_node_deg", record.orbit.ascending_node},
          {"argument_of_pericenter_deg", record.orbit.argument_of_pericenter},
          {"subsatellite_longitude_deg", longitude_deg(fractures.subsatellite)},
          {"subsatellite_latitude_deg", latitude_deg(fractures.subsatellite)}}}}},
      {"failures", failure_summary_json(fractures)},
      {"history", history_json(checkpoint, record, fractures)},
      {"failure_trend",
       {{"still_rising", trend.still_rising},
        {"rule", fmt::format("still rising: at least {} failures and {:g} of them in the last {:g} of the "
                             "encounter's time (docs/failure-rule.md)",
                             failure_trend_min_count, failure_trend_share, failure_trend_window)},
        {"failures", trend.failures},
        {"failures_in_window", trend.failures_in_window},
        {"share_in_window", trend.share_in_window},
        {"window_start_time", trend.window_start},
        {"end_time", trend.end_time},
        {"end_distance", record.end_distance}}},
      {"shell_springs", fractures.shell_springs},
      {"angles_from_subsatellite_deg",
       {{"mean", fractures.mean_angle_from_subsatellite_deg},
        {"bin_width", FractureSummary::angle_bin_width_deg},
        {"histogram", fractures.angle_histogram}}},
      {"failed_springs", failed_springs},
      {"clusters", clusters},
      {"conservation",
       {{"samples", drift.samples},
        {"max_momentum_change", drift.max_momentum_change},
        {"max_angular_momentum_change", drift.max_angular_momentum_change},
        {"max_relative_angular_momentum_change", drift.max_relative_angular_momentum_change},
        {"final_kinetic_energy_change", drift.final_kinetic_energy_change},
        {"max_kinetic_energy_change", drift.max_kinetic_energy_change},
        {"max_energy_error", budget.max_error},
        {"final_energy_error", budget.final_error}}},
      {"energy",
       {{"units", "G M^2/R; errors relative to the binding energy 3/5 G M^2/R (docs/energy-budget.md)"},
        {"deposited_in_body", budget.internal_change},
        {"internal_kinetic_change", budget.internal_kinetic_change},
        {"elastic_change", budget.elastic_change},
        {"self_gravity_change", budget.self_gravity_change},
        {"dissipated", budget.dissipated},
        {"impulse_estimate_eq4", budget.impulse_estimate},
        {"impulse_estimate_uniform_sphere", budget.impulse_estimate_uniform_sphere}}},
      {"snapshots", snapshot_list},
      {"skipped_snapshots", skipped_snapshots},
      {"principal_axis_ratios", shape_list},
      {"figures", figure_names},
      {"crack_geometry", crack_geometry_json(fractures.geometry)},
      {"crust", crust_statistics_json(crust_statistics(checkpoint.body, fractures))}};
  if (const double spin = stored_spin(checkpoint, from.string()); spin != 0)
    summary["spin"] = spin_json(checkpoint, record, spin);
  // A [moon] workflow's values in SI beside the model's, last (readers rely on the order before it).
  if (moon) summary["si"] = summary_si_json(*moon, summary);
  // Atomic, so a summary.json is never half written: run uses it to decide whether the analysis
  // is up to date. cracks.json (the crack polylines for GIS products, read by the Python
  // package) first, so that a summary.json naming this state is never beside an older one.
  // figure_data.json (what the figures draw besides those two) before them too. The figures are
  // drawn last, by the Python package, from these files: the numbers never depend on it.
  const std::string hash = state_hash(checkpoint.state);
  Json cracks = crack_polylines_json(fractures, hash);
  cracks["crust"] = crust_field_json(checkpoint.body, checkpoint.state);  // drawn under the cracks
  write_file_atomically(out / "cracks.json", json_text(cracks));
  write_file_atomically(out / "figure_data.json", figure_data_json(checkpoint, record, panels, titles, hash, moon ? &*moon : nullptr).dump() + "\n");
  write_file_atomically(out / "summary.json", json_text(summary));
  // Figures of an earlier analysis are removed first, so that a figure process that fails leaves
  // no figure of another state beside this summary.json (analysis_is_current then redoes it).
  for (const fs::path& figure : earlier_figures) fs::remove(figure, ec);
  if (with_figures) draw_figures("analysis", {out.string()});
  return figures;
}

bool analysis_is_current(const fs::path& out, const Checkpoint& checkpoint, bool with_figures) {
  std::ifstream in(out / "summary.json");
  if (!in) return false;
  const Json summary = Json::parse(in, nullptr, /*allow_exceptions=*/false);
  const auto hash = summary.find("state_hash");  // end() for a non-object or a parse failure
  if (hash == summary.end() || *hash != state_hash(checkpoint.state)) return false;
  // An analysis written before summary.json had its newest object (crack_geometry) is redone, and
  // one that had to skip a snapshot (unreadable, or of another run) is not finished: the next run
  // tries again.
  if (!summary.contains("crack_geometry") || !summary.contains("failure_trend")) return false;
  // One of a [moon] workflow written before the output in SI.
  if (!summary.contains("si") && stored_moon(checkpoint.config_toml, "/parameters/config")) return false;
  // Likewise one written before cracks.json existed.
  if (!fs::exists(out / "cracks.json") || !fs::exists(out / "figure_data.json")) return false;
  // And one whose figures were not all drawn (the figure script failed or was interrupted).
  const auto figures = summary.find("figures");
  if (figures == summary.end() || !figures->is_array() || (with_figures && figures->empty())) return false;
  for (const auto& figure : *figures)
    if (!figure.is_string() || !fs::exists(out / figure.get<std::string>())) return false;
  const auto skipped = summary.find("skipped_snapshots");
  return skipped != summary.end() && skipped->is_array() && skipped->empty();
}

std::string failure_trend_line(const std::string& name, const Checkpoint& encounter) {
  const EncounterRecord& record = stage_record<EncounterRecord>(encounter, name);
  return failure_trend_warning(
      name, failure_trend(encounter.observables.failures, encounter.stage.clock.start_time, encounter.state.time),
      record.end_distance);
}

std::string fracture_summary_line(const std::string& name, const FractureSummary& fractures) {
  // No failure: no hemisphere, angle or crack to speak of (and no "nan deg").
  if (fractures.count() == 0)
    return fmt::format("{}: no failed shell springs (0 of {})", name, fractures.shell_springs);
  return fmt::format("{}: {} failed shell springs ({} of {}), {} on the subsatellite hemisphere, "
                     "median angle from it {:.0f} deg, {} cracks, largest network {:.2f} R",
                     name, fractures.count(), percent(fractures.fraction_shell), fractures.shell_springs,
                     percent(fractures.hemisphere_fraction), fractures.median_angle_from_subsatellite_deg,
                     fractures.clusters.size(), fractures.longest_crack_length);
}

}  // namespace tidalcrust
