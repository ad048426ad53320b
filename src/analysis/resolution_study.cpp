#include "analysis/resolution_study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "base/errors.hpp"
#include "io/checkpoint_file.hpp"
#include "io/csv.hpp"
#include "io/state_hash.hpp"

namespace tidalcrust {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

/// What must be equal for two checkpoints to be one encounter at two resolutions.
struct EncounterIdentity {
  double perturber_mass, pericenter, pericenter_speed, failure_strain;
  FailureRuleKind failure_rule;
  bool operator==(const EncounterIdentity&) const = default;
};

EncounterIdentity identity_of(const EncounterRecord& r) {
  return {r.encounter.perturber_mass, r.encounter.pericenter, r.encounter.pericenter_speed, r.failure_strain,
          kind_of(r.failure_rule)};
}

std::string describe(const EncounterIdentity& e) {
  // Shortest round-trip numbers, so that values differing in the last digit show as different.
  return fmt::format("M2 = {} M, q = {} R, V_q = {} sqrt(GM/R), eps_S = {}, {} rule", e.perturber_mass, e.pericenter,
                     e.pericenter_speed, e.failure_strain, choice_name(e.failure_rule));
}

Json number_or_null(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

}  // namespace

int shell_level_of(std::size_t shell_nodes) {
  std::size_t nodes = 12;  // level 0: the icosahedron
  for (int level = 0; nodes <= shell_nodes; ++level, nodes = 4 * nodes - 6)  // 10 4^(L+1) + 2 = 4 (10 4^L + 2) - 6
    if (nodes == shell_nodes) return level;
  return -1;
}

double relative_change_percent(double x, double previous) {
  return std::isfinite(x) && std::isfinite(previous) && previous != 0 ? 100 * (x - previous) / previous : nan;
}

ResolutionStudy build_resolution_study(const std::vector<std::string>& files) {
  if (files.empty())
    throw InputError("compare --resolution: expected at least two encounter checkpoints, got none (see --help)");
  if (files.size() == 1)
    throw InputError(fmt::format("{}: compare --resolution needs at least two encounter checkpoints (the same "
                                 "encounter at different shell levels), got only this one",
                                 files.front()));
  ResolutionStudy study;
  EncounterIdentity first{};
  for (std::size_t i = 0; i < files.size(); ++i) {
    const std::string& file = files[i];
    // One checkpoint at a time: a level-6 body is ~60,000 particles; only its summary is kept.
    const Checkpoint c = read_checkpoint(file);
    const auto& record = stage_record<EncounterRecord>(c, file);
    if (!c.stage.complete)
      throw InputError(fmt::format("{}: not a finished encounter (at step {} of {}: a mid-stage, snapshot or diagnostic "
                                   "checkpoint); a resolution study compares finished encounters",
                                   file, c.state.step, c.stage.end_step));
    ResolutionRow row;
    row.file = file;
    row.shell_nodes = c.body.count_species(Species::shell);
    if (row.shell_nodes == 0)
      throw InputError(fmt::format("{}: the body has no crust (0 shell nodes); a resolution study compares crusts", file));
    const EncounterIdentity identity = identity_of(record);
    if (i == 0) {
      first = identity;
      study.encounter = record.encounter;
      study.failure_strain = record.failure_strain;
      study.failure_rule = kind_of(record.failure_rule);
    } else if (!(identity == first)) {
      throw InputError(fmt::format("{}: another encounter than {} ({}; there: {}); a resolution study compares one "
                                   "encounter at several resolutions",
                                   file, files.front(), describe(identity), describe(first)));
    }
    row.shell_level = shell_level_of(row.shell_nodes);
    row.particles = c.body.particle_count();
    row.dt = c.stage.clock.dt;
    row.state_hash = state_hash(c.state);
    row.fractures = analyze_fractures(c);
    study.rows.push_back(std::move(row));
  }
  std::stable_sort(study.rows.begin(), study.rows.end(),
                   [](const ResolutionRow& a, const ResolutionRow& b) { return a.shell_nodes < b.shell_nodes; });
  for (std::size_t i = 0; i < study.rows.size(); ++i) {
    ResolutionRow& row = study.rows[i];
    const FractureSummary* previous = i > 0 ? &study.rows[i - 1].fractures : nullptr;
    row.area_fraction_change_percent =
        previous ? relative_change_percent(row.fractures.failed_area_fraction, previous->failed_area_fraction) : nan;
    row.hemisphere_fraction_change_percent =
        previous ? relative_change_percent(row.fractures.hemisphere_fraction, previous->hemisphere_fraction) : nan;
    row.crack_length_change_percent =
        previous ? relative_change_percent(row.fractures.total_crack_length, previous->total_crack_length) : nan;
  }
  return study;
}

Json resolution_study_json(const ResolutionStudy& study) {
  Json rows = Json::array();
  for (const auto& r : study.rows)
    rows.push_back({{"file", r.file},
                    {"shell_level", r.shell_level >= 0 ? Json(r.shell_level) : Json(nullptr)},
                    {"shell_nodes", r.shell_nodes},
                    {"particles", r.particles},
                    {"dt", r.dt},
                    {"state_hash", r.state_hash},
                    {"failures", failure_summary_json(r.fractures)},
                    {"change_percent",
                     {{"failed_area_fraction", number_or_null(r.area_fraction_change_percent)},
                      {"hemisphere_fraction", number_or_null(r.hemisphere_fraction_change_percent)},
                      {"total_crack_length", number_or_null(r.crack_length_change_percent)}}}});
  return {{"encounter",
           {{"name", study.encounter.name},
            {"perturber_mass", study.encounter.perturber_mass},
            {"pericenter", study.encounter.pericenter},
            {"pericenter_speed", study.encounter.pericenter_speed},
            {"failure_strain", study.failure_strain},
            {"failure_rule", std::string(choice_name(study.failure_rule))}}},
          {"rows", rows}};
}

std::string resolution_study_csv(const ResolutionStudy& study) {
  std::string csv =
      "file,shell_level [1],shell_nodes [1],particles [1],dt [t_grav],failed_springs [1],failed_area_fraction [1],"
      "total_crack_length [R],largest_network_length [R],clusters [1],hemisphere_fraction [1],median_angle [deg],"
      "failed_area_fraction_change [%],hemisphere_fraction_change [%],total_crack_length_change [%],state_hash\n";
  for (const auto& r : study.rows) {
    const FractureSummary& f = r.fractures;
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", csv_text(r.file),
                       r.shell_level >= 0 ? std::to_string(r.shell_level) : "", r.shell_nodes, r.particles,
                       csv_number(r.dt), f.count(), csv_number(f.failed_area_fraction),
                       csv_number(f.total_crack_length), csv_number(f.longest_crack_length), f.clusters.size(),
                       csv_number(f.hemisphere_fraction), csv_number(f.median_angle_from_subsatellite_deg),
                       csv_number(r.area_fraction_change_percent), csv_number(r.hemisphere_fraction_change_percent),
                       csv_number(r.crack_length_change_percent), r.state_hash);
  }
  return csv;
}

}  // namespace tidalcrust
