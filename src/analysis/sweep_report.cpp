#include "analysis/sweep_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "analysis/energy_budget.hpp"
#include "analysis/fracture_analysis.hpp"
#include "base/errors.hpp"
#include "io/checkpoint_file.hpp"
#include "io/checkpoint_names.hpp"
#include "io/csv.hpp"
#include "io/state_hash.hpp"
#include "model/derived_quantities.hpp"
#include "model/stage_fingerprint.hpp"
#include "physics/encounter_estimates.hpp"

namespace tidalcrust {

namespace fs = std::filesystem;

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

/// Fills the results of a finished encounter from its checkpoint.
void fill_results(SweepRow& row, const Checkpoint& c) {
  const FractureSummary fractures = analyze_fractures(c.body, c.state);
  const EnergyBudget budget = energy_budget(c.observables.timeseries, c.stage.as<EncounterRecord>().encounter);
  row.failures = fractures.count();
  row.failed_fraction = fractures.fraction_shell;
  row.hemisphere_fraction = fractures.hemisphere_fraction;
  row.median_angle_deg = fractures.median_angle_from_subsatellite_deg;
  row.longest_crack = fractures.longest_crack_length;
  row.energy_deposited = budget.internal_change;
  row.energy_dissipated = budget.dissipated;
  row.state_hash = state_hash(c.state);
  row.concentricity = fractures.geometry.orientations.concentricity;
  row.fitted_arcs = fractures.geometry.arcs.size();
  row.median_arc_radius_deg = fractures.geometry.median_arc_radius_deg;
  row.median_arc_pole_axis_deg = fractures.geometry.median_pole_axis_from_subsatellite_deg;
}

/// The row of one encounter: its status from encounter.h5 or its mid-stage checkpoint in `dir`.
SweepRow encounter_row(const Config& encounter_config, const Encounter& spec, const std::string& relaxed_hash,
                       double youngs, const fs::path& dir) {
  SweepRow row;
  row.encounter = spec;
  row.failure_strain = spec.failure_strain.value_or(encounter_config.shell.failure_strain);
  row.strain_estimate = eq5_strain(spec, youngs);
  row.failed_fraction = row.hemisphere_fraction = row.median_angle_deg = row.longest_crack = row.energy_deposited =
      row.energy_dissipated = row.concentricity = row.median_arc_radius_deg = row.median_arc_pole_axis_deg = nan;
  const fs::path file = dir / "encounter.h5";
  const fs::path mid = sibling_checkpoint(file, "mid");
  try {
    if (fs::exists(file)) {
      const Checkpoint c = read_checkpoint(file);
      stage_record<EncounterRecord>(c, file.string());
      if (!c.stage.complete) {
        row.status = SweepStatus::unreadable;
        row.note = file.string() + " is not a finished checkpoint";
      } else if (!same_fingerprint(c.stage.fingerprint, stage_fingerprint(encounter_config, StageId::encounter, &spec)) ||
                 c.stage.parent_hash != relaxed_hash) {
        row.status = SweepStatus::stale;
        row.note = c.stage.parent_hash != relaxed_hash ? "branched from another relaxed body; rerun to refresh"
                                                       : "computed with other values; rerun to refresh";
      } else {
        row.status = SweepStatus::finished;
        fill_results(row, c);
      }
    } else if (fs::exists(mid)) {
      row.status = SweepStatus::unfinished;
      const Checkpoint c = read_checkpoint(mid);
      row.note = fmt::format("mid-stage checkpoint at step {} of {}", c.state.step, c.stage.end_step);
    }
  } catch (const InputError& err) {
    row.status = row.status == SweepStatus::unfinished ? SweepStatus::unfinished : SweepStatus::unreadable;
    row.note = err.what();
  }
  return row;
}

std::vector<CrackBoundary> crack_boundaries(const std::vector<SweepRow>& rows, double youngs) {
  // Finished rows of each (M2, eps_S, V_q) line, ordered by q.
  std::map<std::tuple<double, double, double>, std::vector<const SweepRow*>> lines;
  for (const auto& r : rows)
    if (r.status == SweepStatus::finished)
      lines[{r.encounter.perturber_mass, r.failure_strain, r.encounter.pericenter_speed}].push_back(&r);
  std::vector<CrackBoundary> out;
  for (auto& [key, line] : lines) {
    std::sort(line.begin(), line.end(),
              [](const SweepRow* a, const SweepRow* b) { return a->encounter.pericenter < b->encounter.pericenter; });
    CrackBoundary b;
    std::tie(b.perturber_mass, b.failure_strain, b.pericenter_speed) = key;
    b.largest_cracked_q = b.smallest_intact_q = nan;
    for (const SweepRow* r : line)
      if (r->cracked()) b.largest_cracked_q = r->encounter.pericenter;
    for (const SweepRow* r : line)
      if (!r->cracked() && !(r->encounter.pericenter < b.largest_cracked_q)) {
        b.smallest_intact_q = r->encounter.pericenter;
        break;
      }
    b.eq5_q = std::sqrt(b.perturber_mass / (std::sqrt(youngs) * b.pericenter_speed * b.failure_strain));
    out.push_back(b);
  }
  return out;
}

}  // namespace

const char* status_name(SweepStatus status) {
  switch (status) {
    case SweepStatus::finished: return "finished";
    case SweepStatus::unfinished: return "unfinished";
    case SweepStatus::missing: return "missing";
    case SweepStatus::stale: return "stale";
    case SweepStatus::unreadable: return "unreadable";
  }
  return "?";
}

std::size_t SweepReport::count(SweepStatus status) const {
  return static_cast<std::size_t>(std::count_if(rows.begin(), rows.end(), [&](const SweepRow& r) { return r.status == status; }));
}

double eq5_strain(const Encounter& encounter, double youngs_in_e_g) {
  return estimate_encounter(encounter, youngs_in_e_g).strain;
}

SweepReport build_sweep_report(const Config& config, const fs::path& root, double dt_factor) {
  const fs::path relax_file = root / "body" / "relax.h5";
  if (!fs::exists(relax_file))
    throw InputError(fmt::format("{}: nothing has been run for workflow '{}' here (no relaxed body); run "
                                 "`tidalcrust run WORKFLOW.toml --out {}` first",
                                 relax_file.string(), config.workflow.name, root.string()));
  const Checkpoint relaxed = read_checkpoint(relax_file);
  stage_record<RelaxRecord>(relaxed, relax_file.string());
  if (!relaxed.stage.complete)
    throw InputError(fmt::format("{}: the relaxed body is not finished; rerun `tidalcrust run` to finish it",
                                 relax_file.string()));
  SweepReport report;
  report.workflow = config.workflow.name;
  report.dt_factor = dt_factor;
  report.folder = dt_factor == 1.0 ? root : root / fmt::format("dt{}", dt_factor);
  report.youngs_modulus = derive_quantities(relaxed.body, relaxed.state, config.interior.radius).E_I;
  Config encounter_config = config;
  if (dt_factor != 1.0) scale_time_step(encounter_config, dt_factor);
  const std::string relaxed_hash = state_hash(relaxed.state);
  for (const auto& spec : config.encounters)
    report.rows.push_back(
        encounter_row(encounter_config, spec, relaxed_hash, report.youngs_modulus, report.folder / spec.name));
  report.boundaries = crack_boundaries(report.rows, report.youngs_modulus);
  return report;
}

std::string sweep_report_csv(const SweepReport& report) {
  std::string csv =
      "name,status,M2 [M],q [R],V_q [sqrt(GM/R)],eps_S [1],strain_eq5 [1],failures [1],failed_fraction [1],"
      "hemisphere_fraction [1],median_angle [deg],longest_crack [R],energy_deposited [GM^2/R],"
      "energy_dissipated [GM^2/R],state_hash,note,concentricity [1],fitted_arcs [1],median_arc_radius [deg],"
      "median_arc_pole_axis [deg]\n";
  for (const auto& r : report.rows) {
    const bool done = r.status == SweepStatus::finished;
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", csv_text(r.encounter.name),
                       status_name(r.status), r.encounter.perturber_mass, r.encounter.pericenter,
                       r.encounter.pericenter_speed, r.failure_strain, r.strain_estimate,
                       done ? std::to_string(r.failures) : "", csv_number(r.failed_fraction),
                       csv_number(r.hemisphere_fraction), csv_number(r.median_angle_deg), csv_number(r.longest_crack),
                       csv_number(r.energy_deposited), csv_number(r.energy_dissipated), r.state_hash, csv_text(r.note),
                       csv_number(r.concentricity), done ? std::to_string(r.fitted_arcs) : "",
                       csv_number(r.median_arc_radius_deg), csv_number(r.median_arc_pole_axis_deg));
  }
  return csv;
}

Json sweep_report_json(const SweepReport& report) {
  const auto number = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
  Json counts = Json::object();
  for (const auto s : {SweepStatus::finished, SweepStatus::unfinished, SweepStatus::missing, SweepStatus::stale,
                       SweepStatus::unreadable})
    counts[status_name(s)] = report.count(s);
  Json encounters = Json::array();
  for (const auto& r : report.rows) {
    const bool done = r.status == SweepStatus::finished;
    encounters.push_back({{"name", r.encounter.name},
                          {"status", status_name(r.status)},
                          {"perturber_mass", r.encounter.perturber_mass},
                          {"pericenter", r.encounter.pericenter},
                          {"pericenter_speed", r.encounter.pericenter_speed},
                          {"failure_strain", r.failure_strain},
                          {"strain_eq5", number(r.strain_estimate)},
                          {"failures", done ? Json(r.failures) : Json(nullptr)},
                          {"failed_fraction", number(r.failed_fraction)},
                          {"hemisphere_fraction", number(r.hemisphere_fraction)},
                          {"median_angle_deg", number(r.median_angle_deg)},
                          {"longest_crack", number(r.longest_crack)},
                          {"energy_deposited", number(r.energy_deposited)},
                          {"energy_dissipated", number(r.energy_dissipated)},
                          {"state_hash", done ? Json(r.state_hash) : Json(nullptr)},
                          {"note", r.note},
                          {"concentricity", number(r.concentricity)},
                          {"fitted_arcs", done ? Json(r.fitted_arcs) : Json(nullptr)},
                          {"median_arc_radius_deg", number(r.median_arc_radius_deg)},
                          {"median_arc_pole_axis_deg", number(r.median_arc_pole_axis_deg)}});
  }
  Json boundaries = Json::array();
  for (const auto& b : report.boundaries)
    boundaries.push_back({{"perturber_mass", b.perturber_mass},
                          {"failure_strain", b.failure_strain},
                          {"pericenter_speed", b.pericenter_speed},
                          {"largest_cracked_q", number(b.largest_cracked_q)},
                          {"smallest_intact_q", number(b.smallest_intact_q)},
                          {"eq5_q", number(b.eq5_q)}});
  return {{"workflow", report.workflow},
          {"folder", report.folder.string()},
          {"dt_factor", report.dt_factor},
          {"units", "G = M = R = 1: M2 in M, q in R, V_q in sqrt(GM/R), energies in G M^2/R, angles in degrees"},
          {"youngs_modulus_E_I", report.youngs_modulus},
          {"strain_eq5", "paper eq. 5: (e_g/E)^(1/2) (R/q)^2 (M2/M) (v_c/V_q) with E = E_I of the relaxed body"},
          {"counts", counts},
          {"encounters", encounters},
          {"crack_boundaries", boundaries}};
}

}  // namespace tidalcrust
