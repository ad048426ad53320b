// Stage 5: fracture statistics, paper-style figures and conservation diagnostics of one
// encounter (paper section 3): figures (PNG + SVG) and summary.json in one folder.
#include "stages/analysis_stage.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "analysis/conservation_drift.hpp"
#include "base/errors.hpp"
#include "figures/figures.hpp"
#include "analysis/fracture_analysis.hpp"
#include "analysis/fracture_comparison.hpp"
#include "io/atomic_file.hpp"
#include "io/json_writer.hpp"
#include "model/recorded_encounter.hpp"
#include "io/snapshot_files.hpp"
#include "io/state_hash.hpp"
#include "io/checkpoint_file.hpp"

namespace tidalcrust {

namespace fs = std::filesystem;

namespace {


constexpr std::size_t max_snapshot_panels = 5;

struct Snapshot {
  std::unique_ptr<Checkpoint> checkpoint;
  fs::path file;
};

/// Mid-stage snapshots beside `from` that belong to the same encounter (same body, earlier
/// step); unreadable or foreign files are reported and skipped.
std::vector<Snapshot> load_snapshots(const fs::path& from, const Checkpoint& final_checkpoint) {
  std::vector<Snapshot> snapshots;
  for (const auto& found : find_snapshots(from)) {
    if (found.step >= final_checkpoint.state.step) continue;
    try {
      auto c = std::make_unique<Checkpoint>(read_checkpoint(found.file));
      if (c->stage.stage != "encounter")
        throw InputError(fmt::format("{}: stage '{}' is not an encounter", found.file.string(), c->stage.stage));
      require_same_body(final_checkpoint.body, c->body, from.string(), found.file.string());
      snapshots.push_back({std::move(c), found.file});
    } catch (const InputError& err) {
      fmt::print(stderr, "tidalcrust analyze: skipping snapshot: {}\n", err.what());
    }
  }
  return snapshots;
}

std::string percent(double fraction) { return std::isfinite(fraction) ? fmt::format("{:.1f}%", 100 * fraction) : "n/a"; }

}  // namespace

std::vector<fs::path> analyze_encounter(const fs::path& from, const Checkpoint& checkpoint, const fs::path& out) {
  const RecordedEncounter encounter = recorded_encounter(checkpoint, from.string());
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec || !fs::is_directory(out)) throw InputError(fmt::format("{}: cannot create output folder: {}", out.string(), ec.message()));

  const FractureSummary fractures = analyze_fractures(checkpoint.body, checkpoint.state);
  const ConservationDrift drift = conservation_drift(checkpoint.observables.timeseries);
  const std::vector<Snapshot> snapshots = load_snapshots(from, checkpoint);

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
      choose_snapshot_panels(candidate_times, encounter.pericenter_time, max_snapshot_panels);
  std::vector<double> panel_times;
  for (const std::size_t i : panel_indices) panels.push_back(candidates[i]), panel_times.push_back(candidate_times[i]);

  const std::string name = encounter.name.empty() ? from.stem().string() : encounter.name;
  const std::string parameters = fmt::format("M\u2082 = {:g}, q = {:g} R, V_q = {:g}", encounter.perturber_mass,
                                             encounter.pericenter, encounter.pericenter_speed);
  const double t_after = checkpoint.state.time - encounter.pericenter_time;
  std::vector<fs::path> figures;
  auto add = [&](const FigureFiles& files) { figures.insert(figures.end(), files.begin(), files.end()); };
  add(write_fracture_map(fractures, out / "fracture_map",
                         fmt::format("{}: {} failed shell springs ({}), t \u2212 t_peri = {:+.2f}", name, fractures.count(),
                                     percent(fractures.fraction_shell), t_after)));
  add(write_hemisphere_views(panels, encounter.pericenter_time, out / "hemisphere",
                             fmt::format("{} ({}): hemisphere facing pericenter", name, parameters)));
  add(write_orbit_plot(checkpoint, encounter, panel_times, out / "orbit", fmt::format("{}: perturber orbit ({})", name, parameters)));
  add(write_failure_history(checkpoint, encounter.pericenter_time, out / "failures",
                            fmt::format("{}: shell spring failures", name)));
  add(write_conservation_plot(checkpoint, encounter.pericenter_time, out / "conservation",
                              fmt::format("{}: conservation diagnostics", name)));

  JsonWriter json;
  json.begin_object()
      .value("source", from.string())
      .value("stage", checkpoint.stage.stage)
      .value("complete", checkpoint.stage.complete)
      .value("time", checkpoint.state.time)
      .value("step", checkpoint.state.step)
      .value("state_hash", state_hash(checkpoint.state));
  json.begin_object("encounter")
      .value("name", encounter.name)
      .value("perturber_mass", encounter.perturber_mass)
      .value("pericenter", encounter.pericenter)
      .value("pericenter_speed", encounter.pericenter_speed)
      .value("pericenter_time", encounter.pericenter_time)
      .value("min_distance", encounter.min_distance)
      .value("speed_at_min", encounter.speed_at_min)
      .end_object();
  add_failure_summary(json, fractures);
  json.value("shell_springs", fractures.shell_springs);
  std::vector<double> springs, longitudes, latitudes, angles;
  for (const auto& f : fractures.failed) {
    springs.push_back(f.spring);
    longitudes.push_back(f.longitude_deg);
    latitudes.push_back(f.latitude_deg);
    angles.push_back(f.angle_from_subsatellite_deg);
  }
  json.begin_object("angles_from_subsatellite_deg")
      .value("mean", fractures.mean_angle_from_subsatellite_deg)
      .value("bin_width", FractureSummary::angle_bin_width_deg)
      .numbers("histogram", fractures.angle_histogram)
      .end_object();
  json.begin_object("failed_springs")
      .numbers("spring", springs)
      .numbers("longitude_deg", longitudes)
      .numbers("latitude_deg", latitudes)
      .numbers("angle_from_subsatellite_deg", angles)
      .end_object();
  json.begin_array("clusters");
  for (const auto& cluster : fractures.clusters)
    json.begin_object().value("springs", cluster.springs.size()).value("length", cluster.length).value("extent", cluster.extent).end_object();
  json.end_array();
  json.begin_object("conservation")
      .value("samples", drift.samples)
      .value("max_momentum_change", drift.max_momentum_change)
      .value("max_angular_momentum_change", drift.max_angular_momentum_change)
      .value("max_relative_angular_momentum_change", drift.max_relative_angular_momentum_change)
      .value("final_kinetic_energy_change", drift.final_kinetic_energy_change)
      .value("max_kinetic_energy_change", drift.max_kinetic_energy_change)
      .end_object();
  json.begin_array("snapshots");
  for (const std::size_t i : panel_indices)
    json.begin_object()
        .value("file", candidate_files[i].string())
        .value("step", candidates[i]->state.step)
        .value("time", candidates[i]->state.time)
        .end_object();
  json.end_array();
  json.begin_array("figures");
  for (const auto& f : figures) json.value({}, f.filename().string());
  json.end_array();
  json.end_object();
  // Atomic, so a summary.json is never half written: run uses it to decide whether the analysis
  // is up to date.
  write_file_atomically(out / "summary.json", json.str());

  return figures;
}

bool analysis_is_current(const fs::path& out, const Checkpoint& checkpoint) {
  const fs::path summary = out / "summary.json";
  if (!fs::exists(summary)) return false;
  std::ifstream in(summary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return text.find(fmt::format("\"state_hash\": \"{}\"", state_hash(checkpoint.state))) != std::string::npos;
}

std::string fracture_summary_line(const std::string& name, const FractureSummary& fractures) {
  return fmt::format("{}: {} failed shell springs ({} of {}), {} on the subsatellite hemisphere, "
                     "median angle from it {:.0f} deg, {} cracks, longest {:.2f} R",
                     name, fractures.count(), percent(fractures.fraction_shell), fractures.shell_springs,
                     percent(fractures.hemisphere_fraction), fractures.median_angle_from_subsatellite_deg,
                     fractures.clusters.size(), fractures.longest_crack_length);
}

}  // namespace tidalcrust
