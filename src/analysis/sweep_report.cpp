#include "analysis/sweep_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <fstream>
#include <map>
#include <tuple>

#include "analysis/energy_budget.hpp"
#include "analysis/fracture_analysis.hpp"
#include "analysis/si_output.hpp"
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
  const FractureSummary fractures = analyze_fractures(c);
  const EnergyBudget budget = energy_budget(c.observables.timeseries, c.stage.as<EncounterRecord>().encounter);
  row.failures = fractures.count();
  row.failed_fraction = fractures.fraction_shell;
  row.hemisphere_fraction = fractures.hemisphere_fraction;
  row.median_angle_deg = fractures.median_angle_from_subsatellite_deg;
  row.largest_network_length = fractures.longest_crack_length;
  row.energy_deposited = budget.internal_change;
  row.energy_dissipated = budget.dissipated;
  row.state_hash = state_hash(c.state);
  row.concentricity = fractures.geometry.orientations.concentricity;
  row.rose_sector_share = fractures.geometry.orientations.sector_share;
  row.fitted_arcs = fractures.geometry.arcs.size();
  row.median_arc_radius_deg = fractures.geometry.median_arc_radius_deg;
  row.median_arc_pole_axis_deg = fractures.geometry.median_pole_axis_from_subsatellite_deg;
  row.total_crack_length = fractures.total_crack_length;
  row.cracks = fractures.clusters.size();
}

/// The row of one encounter: its status from encounter.h5 or its mid-stage checkpoint in `dir`.
/// `parent_hash`: the state it must have begun from (the relaxed body's, or for an encounter of a
/// history the final state of the one it comes after; "" when that is not current), and
/// `other_parent` the note of a row that began from another.
SweepRow encounter_row(const Config& encounter_config, const Encounter& spec, const std::string& parent_hash,
                       const std::string& other_parent, double youngs, const fs::path& dir) {
  SweepRow row;
  row.encounter = spec;
  row.failure_strain = spec.failure_strain.value_or(encounter_config.shell.failure_strain);
  row.strain_estimate = eq5_strain(spec, youngs);
  row.failed_fraction = row.hemisphere_fraction = row.median_angle_deg = row.largest_network_length = row.energy_deposited =
      row.energy_dissipated = row.concentricity = row.median_arc_radius_deg = row.median_arc_pole_axis_deg = row.total_crack_length = nan;
  row.rose_sector_share.fill(nan);
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
                 c.stage.parent_hash != parent_hash) {
        row.status = SweepStatus::stale;
        row.note = c.stage.parent_hash != parent_hash ? other_parent : "computed with other values; rerun to refresh";
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

/// The (M2, eps_S, V_q) lines of the `rows` that `use` keeps, each ordered by q: where the line
/// switches from crack to no crack (`cracked` of a row) and where eq. 5 puts strain = eps_S;
/// `more(boundary, line)` fills the rest. One home for both kinds of row (SweepRow, EnsembleRow).
template <typename Row, typename Use, typename Cracked, typename More>
std::vector<CrackBoundary> boundaries_along_q(const std::vector<Row>& rows, double youngs, Use use, Cracked cracked,
                                              More more) {
  std::map<std::tuple<double, double, double>, std::vector<const Row*>> lines;
  for (const auto& r : rows)
    if (use(r)) lines[{r.encounter.perturber_mass, r.failure_strain, r.encounter.pericenter_speed}].push_back(&r);
  std::vector<CrackBoundary> out;
  for (auto& [key, line] : lines) {
    std::sort(line.begin(), line.end(),
              [](const Row* a, const Row* b) { return a->encounter.pericenter < b->encounter.pericenter; });
    CrackBoundary b;
    std::tie(b.perturber_mass, b.failure_strain, b.pericenter_speed) = key;
    b.largest_cracked_q = b.smallest_intact_q = b.half_probability_q = b.half_probability_q_low =
        b.half_probability_q_high = nan;
    for (const Row* r : line)
      if (cracked(*r)) b.largest_cracked_q = r->encounter.pericenter;
    for (const Row* r : line)
      if (!cracked(*r) && !(r->encounter.pericenter < b.largest_cracked_q)) {
        b.smallest_intact_q = r->encounter.pericenter;
        break;
      }
    b.eq5_q = std::sqrt(b.perturber_mass / (std::sqrt(youngs) * b.pericenter_speed * b.failure_strain));
    more(b, line);
    out.push_back(b);
  }
  return out;
}

/// The lines of an [ensemble] workflow: each point an encounter before the expansion, "cracked"
/// when any finished member cracked, with the q where the share of cracked members falls through 1/2.
std::vector<CrackBoundary> ensemble_boundaries(const std::vector<EnsembleRow>& rows, double youngs) {
  const auto half_probability = [](CrackBoundary& b, const std::vector<const EnsembleRow*>& line) {
    // The first fall of the cracked share through 1/2 along q.
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const double p0 = line[i]->cracked.fraction, p1 = line[i + 1]->cracked.fraction;
      if (p0 >= 0.5 && p1 < 0.5) {
        const double q0 = line[i]->encounter.pericenter, q1 = line[i + 1]->encounter.pericenter;
        b.half_probability_q = q0 + (q1 - q0) * (p0 - 0.5) / (p0 - p1);
        break;
      }
    }
    for (const EnsembleRow* r : line)
      if (r->cracked.low > 0.5 && !(r->encounter.pericenter > b.half_probability_q))
        b.half_probability_q_low = r->encounter.pericenter;
    for (const EnsembleRow* r : line)
      if (r->cracked.high < 0.5 && !(r->encounter.pericenter < b.half_probability_q_low) &&
          !(r->encounter.pericenter < b.half_probability_q)) {
        b.half_probability_q_high = r->encounter.pericenter;
        break;
      }
  };
  return boundaries_along_q(
      rows, youngs, [](const EnsembleRow& r) { return r.finished > 0; },
      [](const EnsembleRow& r) { return r.cracked.successes > 0; }, half_probability);
}

/// The ensemble rows of `rows`, whose encounters are the members of `config.ensemble_bases` in
/// order (expand_ensemble); none when they are not (a workflow without [ensemble]).
std::vector<EnsembleRow> ensemble_rows(const Config& config, const std::vector<SweepRow>& rows, double youngs) {
  if (!config.ensemble) return {};
  const std::size_t n = static_cast<std::size_t>(config.ensemble->members);
  if (rows.size() != config.ensemble_bases.size() * n) return {};
  std::vector<EnsembleRow> out;
  for (std::size_t b = 0; b < config.ensemble_bases.size(); ++b) {
    EnsembleRow e;
    e.encounter = config.ensemble_bases[b];
    e.failure_strain = rows[b * n].failure_strain;
    e.strain_estimate = eq5_strain(e.encounter, youngs);
    e.members = n;
    std::size_t cracked = 0;
    std::vector<std::vector<double>> values(ensemble_statistics().size());
    std::vector<double> offsets;
    for (std::size_t k = 0; k < n; ++k) {
      const SweepRow& r = rows[b * n + k];
      if (r.status != SweepStatus::finished) continue;
      ++e.finished;
      offsets.push_back(ensemble_pericenter_offset(*config.ensemble, static_cast<std::int64_t>(k)));
      cracked += r.failures > 0 ? 1 : 0;
      for (std::size_t s = 0; s < values.size(); ++s) values[s].push_back(ensemble_statistics()[s].value(r));
    }
    e.cracked = wilson_interval(cracked, e.finished);
    for (const auto& v : values) e.statistics.push_back(summarize_about_trend(v, offsets));
    out.push_back(std::move(e));
  }
  return out;
}

std::vector<CrackBoundary> crack_boundaries(const std::vector<SweepRow>& rows, double youngs) {
  return boundaries_along_q(
      // A second pass of a history cracks a cracked crust: it is no point of the phase diagram.
      rows, youngs, [](const SweepRow& r) { return r.status == SweepStatus::finished && !r.encounter.after; },
      [](const SweepRow& r) { return r.cracked(); }, [](CrackBoundary&, const std::vector<const SweepRow*>&) {});
}

}  // namespace

std::span<const EnsembleStatistic> ensemble_statistics() {
  static constexpr EnsembleStatistic list[] = {
      {"failures", "1", [](const SweepRow& r) { return static_cast<double>(r.failures); }},
      {"failed_fraction", "1", [](const SweepRow& r) { return r.failed_fraction; }},
      {"total_crack_length", "R", [](const SweepRow& r) { return r.total_crack_length; }},
      {"largest_network_length", "R", [](const SweepRow& r) { return r.largest_network_length; }},
      {"cracks", "1", [](const SweepRow& r) { return static_cast<double>(r.cracks); }},
      {"hemisphere_fraction", "1", [](const SweepRow& r) { return r.hemisphere_fraction; }},
      {"median_angle", "deg", [](const SweepRow& r) { return r.median_angle_deg; }},
      {"concentricity", "1", [](const SweepRow& r) { return r.concentricity; }},
      // The rose in sectors of 45 deg: radial, oblique (counter-clockwise from radial), concentric, oblique.
      {"rose_0", "1", [](const SweepRow& r) { return r.rose_sector_share[0]; }},
      {"rose_45", "1", [](const SweepRow& r) { return r.rose_sector_share[1]; }},
      {"rose_90", "1", [](const SweepRow& r) { return r.rose_sector_share[2]; }},
      {"rose_135", "1", [](const SweepRow& r) { return r.rose_sector_share[3]; }},
      {"median_arc_radius", "deg", [](const SweepRow& r) { return r.median_arc_radius_deg; }},
      {"median_arc_pole_axis", "deg", [](const SweepRow& r) { return r.median_arc_pole_axis_deg; }},
      {"energy_deposited", "GM^2/R", [](const SweepRow& r) { return r.energy_deposited; }},
      {"energy_dissipated", "GM^2/R", [](const SweepRow& r) { return r.energy_dissipated; }},
  };
  return list;
}

std::span<const SweepSiColumn> sweep_si_columns() {
  static constexpr SweepSiColumn list[] = {
      {"M2", "perturber_mass", Dimension::mass, [](const SweepRow& r) { return r.encounter.perturber_mass; }},
      {"q", "pericenter", Dimension::length, [](const SweepRow& r) { return r.encounter.pericenter; }},
      {"V_q", "pericenter_speed", Dimension::speed, [](const SweepRow& r) { return r.encounter.pericenter_speed; }},
      {"largest_network_length", "largest_network_length", Dimension::length,
       [](const SweepRow& r) { return r.largest_network_length; }},
      {"total_crack_length", "total_crack_length", Dimension::length,
       [](const SweepRow& r) { return r.total_crack_length; }},
      {"energy_deposited", "energy_deposited", Dimension::energy, [](const SweepRow& r) { return r.energy_deposited; }},
      {"energy_dissipated", "energy_dissipated", Dimension::energy,
       [](const SweepRow& r) { return r.energy_dissipated; }},
  };
  return list;
}

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

SweepReport crack_probability_report(const SweepReport& report) {
  SweepReport out = report;
  out.rows.clear();
  for (const auto& e : report.ensembles) {
    SweepRow& row = out.rows.emplace_back();
    row.encounter = e.encounter;
    row.failure_strain = e.failure_strain;
    row.strain_estimate = e.strain_estimate;
    row.status = e.finished > 0 ? SweepStatus::finished : SweepStatus::missing;
    row.failures = e.cracked.successes;
    row.failed_fraction = e.cracked.fraction;
  }
  return out;
}

double eq5_strain(const Encounter& encounter, double youngs_in_e_g) {
  return estimate_encounter(encounter, youngs_in_e_g).strain;
}

SweepReport build_sweep_report(const Config& config, const fs::path& root, double dt_factor,
                               const BodyChainConfig& prepared) {
  const fs::path relax_file = body_folder(root, config) / "relax.h5";
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
  // Per body seed: the configuration its encounters ran with (at dt * dt_factor) and its relaxed
  // state's hash ("" while that body is not relaxed: its encounters cannot be current).
  struct BodyOfEncounters {
    Config config;
    std::string relaxed_hash;
  };
  const auto at_dt_factor = [&](Config c) {
    if (dt_factor != 1.0) scale_time_step(c, dt_factor);
    return c;
  };
  std::map<std::uint64_t, BodyOfEncounters> bodies;
  bodies.emplace(config.workflow.seed, BodyOfEncounters{at_dt_factor(prepared(nullptr)), state_hash(relaxed.state)});
  // The rows in the workflow's order; an encounter of a history once the one it comes after has
  // its row (it is current only when that one is finished and it began from its final state).
  report.rows.resize(config.encounters.size());
  std::vector<bool> done(config.encounters.size(), false);
  std::map<std::string, std::size_t> index_of;
  for (std::size_t i = 0; i < config.encounters.size(); ++i) index_of[config.encounters[i].name] = i;
  for (bool progress = true; progress;) {
    progress = false;
    for (std::size_t i = 0; i < config.encounters.size(); ++i) {
      const Encounter& spec = config.encounters[i];
      if (done[i]) continue;
      const std::size_t before = spec.after ? index_of.at(*spec.after) : i;  // validate checked the name
      if (spec.after && !done[before]) continue;
      const std::uint64_t seed = body_seed_of(config, spec);
      auto body = bodies.find(seed);
      if (body == bodies.end()) {
        const fs::path own_relax = body_folder(root, config, &spec) / "relax.h5";
        std::string hash;
        try {
          if (fs::exists(own_relax))
            if (const Checkpoint c = read_checkpoint(own_relax); c.stage.complete) hash = state_hash(c.state);
        } catch (const InputError&) {  // its encounters are then stale or missing rows, as of an unrun body
        }
        body = bodies.emplace(seed, BodyOfEncounters{at_dt_factor(prepared(&spec)), hash}).first;
      }
      const SweepRow* first = spec.after ? &report.rows[before] : nullptr;
      const std::string parent_hash =
          !first ? body->second.relaxed_hash : first->status == SweepStatus::finished ? first->state_hash : std::string();
      const std::string other_parent =
          !first ? "branched from another relaxed body; rerun to refresh"
                 : fmt::format("began from another state of {}{}; rerun to refresh", *spec.after,
                               first->status == SweepStatus::finished ? "" : " (which is not current)");
      report.rows[i] = encounter_row(body->second.config, spec, parent_hash, other_parent, report.youngs_modulus,
                                     report.folder / spec.name);
      done[i] = progress = true;
    }
  }
  report.ensembles = ensemble_rows(config, report.rows, report.youngs_modulus);
  if (config.ensemble) report.ensemble_vary = config.ensemble->vary;
  report.moon = output_moon(config, config.workflow.name);
  report.boundaries = config.ensemble ? ensemble_boundaries(report.ensembles, report.youngs_modulus)
                                      : crack_boundaries(report.rows, report.youngs_modulus);
  return report;
}

std::string sweep_report_csv(const SweepReport& report) {
  std::string csv =
      "name,status,M2 [M],q [R],V_q [sqrt(GM/R)],eps_S [1],strain_eq5 [1],failures [1],failed_fraction [1],"
      "hemisphere_fraction [1],median_angle [deg],largest_network_length [R],energy_deposited [GM^2/R],"
      "energy_dissipated [GM^2/R],state_hash,note,concentricity [1],fitted_arcs [1],median_arc_radius [deg],"
      "median_arc_pole_axis [deg],total_crack_length [R],cracks [1],after";
  if (report.moon)
    for (const auto& c : sweep_si_columns()) csv += fmt::format(",{} [{}]", c.csv_name, output_unit(c.dimension).symbol);
  csv += "\n";
  for (const auto& r : report.rows) {
    const bool done = r.status == SweepStatus::finished;
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}", csv_text(r.encounter.name),
                       status_name(r.status), r.encounter.perturber_mass, r.encounter.pericenter,
                       r.encounter.pericenter_speed, r.failure_strain, r.strain_estimate,
                       done ? std::to_string(r.failures) : "", csv_number(r.failed_fraction),
                       csv_number(r.hemisphere_fraction), csv_number(r.median_angle_deg), csv_number(r.largest_network_length),
                       csv_number(r.energy_deposited), csv_number(r.energy_dissipated), r.state_hash, csv_text(r.note),
                       csv_number(r.concentricity), done ? std::to_string(r.fitted_arcs) : "",
                       csv_number(r.median_arc_radius_deg), csv_number(r.median_arc_pole_axis_deg),
                       csv_number(r.total_crack_length), done ? std::to_string(r.cracks) : "",
                       csv_text(r.encounter.after.value_or("")));
    if (report.moon)
      for (const auto& c : sweep_si_columns())
        csv += "," + csv_number(model_to_output(report.moon->units, c.dimension, c.value(r)));
    csv += "\n";
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
                          {"largest_network_length", number(r.largest_network_length)},
                          {"energy_deposited", number(r.energy_deposited)},
                          {"energy_dissipated", number(r.energy_dissipated)},
                          {"state_hash", done ? Json(r.state_hash) : Json(nullptr)},
                          {"note", r.note},
                          {"concentricity", number(r.concentricity)},
                          {"fitted_arcs", done ? Json(r.fitted_arcs) : Json(nullptr)},
                          {"median_arc_radius_deg", number(r.median_arc_radius_deg)},
                          {"median_arc_pole_axis_deg", number(r.median_arc_pole_axis_deg)},
                          {"total_crack_length", number(r.total_crack_length)},
                          {"cracks", done ? Json(r.cracks) : Json(nullptr)},
                          {"after", r.encounter.after ? Json(*r.encounter.after) : Json(nullptr)}});
    if (report.moon) {
      Json si = Json::object();
      for (const auto& c : sweep_si_columns())
        si[si_key(c.json_key, c.dimension)] = number(model_to_output(report.moon->units, c.dimension, c.value(r)));
      encounters.back()["si"] = std::move(si);
    }
  }
  Json boundaries = Json::array();
  for (const auto& b : report.boundaries)
    boundaries.push_back({{"perturber_mass", b.perturber_mass},
                          {"failure_strain", b.failure_strain},
                          {"pericenter_speed", b.pericenter_speed},
                          {"largest_cracked_q", number(b.largest_cracked_q)},
                          {"smallest_intact_q", number(b.smallest_intact_q)},
                          {"eq5_q", number(b.eq5_q)},
                          {"half_probability_q", number(b.half_probability_q)},
                          {"half_probability_q_low", number(b.half_probability_q_low)},
                          {"half_probability_q_high", number(b.half_probability_q_high)}});
  if (report.moon)
    for (Json& b : boundaries) {
      static constexpr ModelKey boundary_keys[] = {
          {"perturber_mass", Dimension::mass},        {"pericenter_speed", Dimension::speed},
          {"largest_cracked_q", Dimension::length},   {"smallest_intact_q", Dimension::length},
          {"eq5_q", Dimension::length},               {"half_probability_q", Dimension::length},
          {"half_probability_q_low", Dimension::length}, {"half_probability_q_high", Dimension::length}};
      b["si"] = si_values(b, boundary_keys, report.moon->units);
    }
  Json out = {{"workflow", report.workflow},
          {"folder", report.folder.string()},
          {"dt_factor", report.dt_factor},
          {"units", "G = M = R = 1: M2 in M, q in R, V_q in sqrt(GM/R), energies in G M^2/R, angles in degrees"},
          {"youngs_modulus_E_I", report.youngs_modulus},
          {"strain_eq5", "paper eq. 5: (e_g/E)^(1/2) (R/q)^2 (M2/M) (v_c/V_q) with E = E_I of the relaxed body"},
          {"counts", counts},
          {"encounters", encounters},
          {"crack_boundaries", boundaries}};
  if (report.moon) out["si"] = {{"units", si_units_text(*report.moon)}, {"moon", moon_json(*report.moon)}};
  return out;
}

std::string ensemble_report_csv(const SweepReport& report) {
  std::string csv = "name,M2 [M],q [R],V_q [sqrt(GM/R)],eps_S [1],strain_eq5 [1],members [1],finished [1],"
                    "cracked [1],cracked_fraction [1],cracked_low [1],cracked_high [1]";
  for (const auto& s : ensemble_statistics())
    csv += fmt::format(",{0}_mean [{1}],{0}_sd [{1}],{0}_low [{1}],{0}_high [{1}]", s.name, s.unit);
  // Of a moon, the inputs and the statistics in a model unit again in SI.
  const auto in_si = [&](const char* unit) { return report.moon ? dimension_of_model_unit(unit) : std::nullopt; };
  if (report.moon) {
    for (const auto& c : sweep_si_columns().first(3))
      csv += fmt::format(",{} [{}]", c.csv_name, output_unit(c.dimension).symbol);
    for (const auto& s : ensemble_statistics())
      if (const auto d = in_si(s.unit))
        csv += fmt::format(",{0}_mean [{1}],{0}_sd [{1}],{0}_low [{1}],{0}_high [{1}]", s.name, output_unit(*d).symbol);
  }
  csv += "\n";
  for (const auto& e : report.ensembles) {
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}", csv_text(e.encounter.name), e.encounter.perturber_mass,
                       e.encounter.pericenter, e.encounter.pericenter_speed, e.failure_strain, e.strain_estimate,
                       e.members, e.finished, e.cracked.successes, csv_number(e.cracked.fraction),
                       csv_number(e.cracked.low), csv_number(e.cracked.high));
    for (const auto& s : e.statistics)
      csv += fmt::format(",{},{},{},{}", csv_number(s.mean), csv_number(s.standard_deviation), csv_number(s.low),
                         csv_number(s.high));
    if (report.moon) {
      SweepRow inputs;
      inputs.encounter = e.encounter;
      for (const auto& c : sweep_si_columns().first(3))
        csv += "," + csv_number(model_to_output(report.moon->units, c.dimension, c.value(inputs)));
      for (std::size_t i = 0; i < e.statistics.size(); ++i)
        if (const auto d = in_si(ensemble_statistics()[i].unit)) {
          const SampleSummary& s = e.statistics[i];
          for (const double v : {s.mean, s.standard_deviation, s.low, s.high})
            csv += "," + csv_number(model_to_output(report.moon->units, *d, v));
        }
    }
    csv += "\n";
  }
  return csv;
}

Json ensemble_report_json(const SweepReport& report) {
  const auto number = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
  Json units = Json::object();
  for (const auto& s : ensemble_statistics()) units[s.name] = s.unit;
  Json rows = Json::array();
  for (const auto& e : report.ensembles) {
    Json stats = Json::object();
    for (std::size_t i = 0; i < e.statistics.size(); ++i) {
      const SampleSummary& s = e.statistics[i];
      stats[ensemble_statistics()[i].name] = {{"count", s.count},
                                              {"mean", number(s.mean)},
                                              {"sd", number(s.standard_deviation)},
                                              {"standard_error", number(s.standard_error)},
                                              {"low", number(s.low)},
                                              {"high", number(s.high)},
                                              {"degrees_of_freedom", s.degrees_of_freedom},
                                              {"slope_per_ln_q", number(s.slope)}};
    }
    rows.push_back({{"name", e.encounter.name},
                    {"perturber_mass", e.encounter.perturber_mass},
                    {"pericenter", e.encounter.pericenter},
                    {"pericenter_speed", e.encounter.pericenter_speed},
                    {"failure_strain", e.failure_strain},
                    {"strain_eq5", number(e.strain_estimate)},
                    {"members", e.members},
                    {"finished", e.finished},
                    {"cracked", {{"members", e.cracked.successes},
                                 {"fraction", number(e.cracked.fraction)},
                                 {"low", number(e.cracked.low)},
                                 {"high", number(e.cracked.high)}}},
                    {"statistics", stats}});
  }
  return {{"workflow", report.workflow},
          {"folder", report.folder.string()},
          {"confidence", ensemble_confidence},
          {"vary", choice_name(report.ensemble_vary)},
          {"method", report.ensemble_vary == EnsembleVariation::body_seed
                         ? "over the finished members (each on a body of its own seed, one pericenter): mean, sd "
                           "(n - 1 degrees of freedom); interval of the mean: Student t with n - 1 degrees of "
                           "freedom; cracked share: Wilson score interval"
                         : "over the finished members, the least-squares line of each statistic against the members' "
                           "relative pericenter offsets: mean = the line at offset 0 (the unperturbed encounter), sd "
                           "= the scatter about the line (n - 2 degrees of freedom), slope_per_ln_q = its slope; "
                           "interval of the mean: Student t with n - 2 degrees of freedom; cracked share: Wilson "
                           "score interval"},
          {"units", units},
          {"ensembles", rows}};
}

std::vector<StoredEnsemble> read_ensemble_report(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{}: cannot read the ensemble table: {}", file.string(), std::strerror(errno)));
  const Json json = Json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (json.is_discarded() || !json.is_object() || !json.contains("ensembles") || !json["ensembles"].is_array())
    throw InputError(fmt::format("{}: not an ensemble table (`tidalcrust report` writes report/ensembles.json)",
                                 file.string()));
  const auto number = [](const Json& v) {
    return v.is_number() ? v.get<double>() : std::numeric_limits<double>::quiet_NaN();
  };
  std::vector<StoredEnsemble> out;
  try {
    for (const Json& row : json["ensembles"]) {
      StoredEnsemble e;
      e.name = row.at("name").get<std::string>();
      e.finished = row.at("finished").get<std::size_t>();
      for (const auto& statistic : ensemble_statistics()) {
        SampleSummary s{0, nan, nan, nan, nan, nan, 0, nan};
        if (row.at("statistics").contains(statistic.name)) {
          const Json& v = row["statistics"][statistic.name];
          s = {v.at("count").get<std::size_t>(), number(v.at("mean")), number(v.at("sd")),
               number(v.at("standard_error")), number(v.at("low")), number(v.at("high")),
               v.at("degrees_of_freedom").get<double>(), number(v.at("slope_per_ln_q"))};
        }
        e.statistics.push_back(s);
      }
      out.push_back(std::move(e));
    }
  } catch (const Json::exception& err) {
    throw InputError(fmt::format("{}: not an ensemble table: {}", file.string(), err.what()));
  }
  return out;
}

}  // namespace tidalcrust
