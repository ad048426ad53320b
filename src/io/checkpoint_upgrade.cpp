// Upgrade steps of the checkpoint format (io/checkpoint_upgrade.hpp). Each step is written in the
// names of the layouts it goes from and to, as they were: a step is history and never follows a
// later rename (that is the later step's job).
#include "io/checkpoint_upgrade.hpp"

#include <fmt/format.h>

#include <initializer_list>
#include <iterator>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "io/checkpoint_file.hpp"
#include "io/hdf5_handles.hpp"

namespace tidalcrust {

namespace {

constexpr double not_recorded = std::numeric_limits<double>::quiet_NaN();

bool has_attribute(hid_t loc, const char* name) { return H5Aexists(loc, name) > 0; }

/// Replaces /checkpoint@format_version by `version`.
void set_format_version(hid_t root, std::int64_t version) {
  h5::Group g = h5::open_group(root, "/checkpoint");
  if (has_attribute(g.get(), "format_version"))
    h5::check(H5Adelete(g.get(), "format_version"), "cannot replace /checkpoint@format_version");
  h5::write_attribute<std::int64_t>(g.get(), "format_version", version);
}

/// Rows of the column group `group` (its `time` column); nothing when the group or the column is
/// missing (the reader then names what is missing).
std::optional<hsize_t> rows_of_columns(hid_t root, const std::string& group) {
  const std::string time = group + "/time";
  if (!h5::exists(root, group) || !h5::exists(root, time)) return std::nullopt;
  const auto dims = h5::read_dataset<double>(root, time).dims;
  if (dims.size() != 1) return std::nullopt;
  return dims[0];
}

/// What format 4 gained after it was first written without a version bump, each addition as a
/// whole: the energy budget (2026-11-29, commit 82ecfd1: eight timeseries columns, the failure
/// log's released_energy, three fields of an encounter's record) and the local failure rule's
/// record fields (commit 57faf41). A file lacking every object of an addition was written before
/// it and gets the value it stands for: NaN where the quantity was not recorded, the paper rule's
/// own values for the rule fields (it was the only rule then). A file lacking only some of them is
/// damaged, not old: nothing is added and the reader names what is missing (main's 09985b6: every
/// budget column of a format-4 file is required). With `add` false only tells whether an addition
/// is missing as a whole; with `add` true also adds it (`root` writable).
bool complete_format_4(hid_t root, bool add) {
  const std::vector<const char*> timeseries = {"internal_kinetic_energy", "spring_energy",      "hinge_energy",
                                               "self_gravity_energy",     "perturber_energy",   "damping_dissipated",
                                               "failure_released",        "hinge_residual_work"};
  const std::vector<const char*> ledger = {"damping_dissipated", "failure_released", "hinge_residual_work"};
  const std::vector<const char*> rule = {"failure_rule", "relaxation_steps", "exclusion_distance"};

  // An encounter's record, if this is one (only an encounter's record has these fields).
  std::optional<h5::Group> record;
  if (h5::exists(root, "/checkpoint/record")) {
    h5::Group g = h5::open_group(root, "/checkpoint");
    if (has_attribute(g.get(), "stage") && h5::read_string_attribute(g.get(), "stage") == "encounter")
      record = h5::open_group(root, "/checkpoint/record");
  }
  const auto series_rows = rows_of_columns(root, "/checkpoint/timeseries");
  const auto failure_rows = rows_of_columns(root, "/checkpoint/failures");

  // How many objects of the energy budget the file has.
  int budget_present = 0;
  if (series_rows)
    for (const char* name : timeseries) budget_present += h5::exists(root, fmt::format("/checkpoint/timeseries/{}", name));
  if (failure_rows) budget_present += h5::exists(root, "/checkpoint/failures/released_energy");
  if (record)
    for (const char* name : ledger) budget_present += has_attribute(record->get(), name);
  const bool budget_missing = budget_present == 0 && (series_rows || failure_rows || record);

  int rule_present = 0;
  if (record)
    for (const char* name : rule) rule_present += has_attribute(record->get(), name);
  const bool rule_missing = record && rule_present == 0;

  if (add && budget_missing) {
    if (series_rows)
      for (const char* name : timeseries)
        h5::write_dataset(root, fmt::format("/checkpoint/timeseries/{}", name),
                          std::vector<double>(*series_rows, not_recorded), {*series_rows});
    if (failure_rows)
      h5::write_dataset(root, "/checkpoint/failures/released_energy", std::vector<double>(*failure_rows, not_recorded),
                        {*failure_rows});
    if (record)
      for (const char* name : ledger) h5::write_attribute<double>(record->get(), name, not_recorded);
  }
  if (add && rule_missing) {
    h5::write_string_attribute(record->get(), "failure_rule", "paper");
    h5::write_attribute<std::int64_t>(record->get(), "relaxation_steps", 0);
    h5::write_attribute<double>(record->get(), "exclusion_distance", 0.0);
  }
  return budget_missing || rule_missing;
}

/// 3 -> 4 (2026-11-29, commit f6f5a86, valid H5MD 1.1): the failure log and the timeseries moved
/// from /observables to /checkpoint and /observables went away. The H5MD metadata format 4 added
/// (units, particles_group references, labels, an extensible time dimension) is not read back,
/// so it is not made up here.
void layout_3_to_4(hid_t root) {
  for (const char* name : {"failures", "timeseries"}) {
    const std::string from = fmt::format("/observables/{}", name), to = fmt::format("/checkpoint/{}", name);
    if (!h5::exists(root, from)) continue;  // the reader names the missing group
    h5::check(H5Lmove(root, from.c_str(), root, to.c_str(), H5P_DEFAULT, H5P_DEFAULT),
              fmt::format("cannot move {} to {}", from, to));
  }
  if (h5::exists(root, "/observables")) h5::check(H5Ldelete(root, "/observables", H5P_DEFAULT), "cannot remove /observables");
}

/// True when the file holds an encounter's record (/checkpoint@stage = "encounter").
bool is_encounter_record(hid_t root) {
  if (!h5::exists(root, "/checkpoint/record")) return false;
  h5::Group g = h5::open_group(root, "/checkpoint");
  return has_attribute(g.get(), "stage") && h5::read_string_attribute(g.get(), "stage") == "encounter";
}

/// Adds the double attributes `names` = 0 to an encounter's record where it lacks them (the
/// failure rules before them had no such parameter).
void add_zero_encounter_record_attributes(hid_t root, std::initializer_list<const char*> names) {
  if (!is_encounter_record(root)) return;
  h5::Group record = h5::open_group(root, "/checkpoint/record");
  for (const char* name : names)
    if (!has_attribute(record.get(), name)) h5::write_attribute<double>(record.get(), name, 0.0);
}

/// 4 -> 5 (2026-12-06, the shadow failure rule): an encounter's record gains `shadow_distance`
/// (R), 0 for the rules before it, which have no stress shadow.
void layout_4_to_5(hid_t root) { add_zero_encounter_record_attributes(root, {"shadow_distance"}); }

/// 5 -> 6 (2026-12-06, the griffith failure rule): an encounter's record gains `flaw_length` (R)
/// and `growth_strain_factor`, 0 for the rules before it, which open no flaws.
void layout_5_to_6(hid_t root) { add_zero_encounter_record_attributes(root, {"flaw_length", "growth_strain_factor"}); }

/// 6 -> 7 (2026-12-07, encounter histories and orbit orientations, issue 25): an encounter's record
/// gains `after` ("": it began from the relaxed body, as every encounter before it did) and the
/// orbit's `inclination`, `ascending_node` and `argument_of_pericenter` (deg), 0, 0 and 90 for the
/// one orbit encounters had before: pericenter on +y, angular momentum along +z.
void layout_6_to_7(hid_t root) {
  if (!is_encounter_record(root)) return;
  h5::Group record = h5::open_group(root, "/checkpoint/record");
  if (!has_attribute(record.get(), "after")) h5::write_string_attribute(record.get(), "after", "");
  for (auto [name, value] : {std::pair{"inclination", 0.0}, {"ascending_node", 0.0}, {"argument_of_pericenter", 90.0}})
    if (!has_attribute(record.get(), name)) h5::write_attribute<double>(record.get(), name, value);
}

/// 7 -> 8 (2026-12-08, a crust that varies, issue 25): the springs gain `strength_factor` (a shell
/// spring fails beyond eps_S times it), 1 for every spring: every crust before it was uniform.
void layout_7_to_8(hid_t root) {
  const char* springs = "/connectivity/springs";
  const char* factor = "/checkpoint/springs/strength_factor";
  if (!h5::exists(root, springs) || h5::exists(root, factor)) return;  // the reader names a missing one
  const auto dims = h5::read_dataset<std::int32_t>(root, springs).dims;
  if (dims.empty()) return;
  h5::write_dataset(root, factor, std::vector<double>(dims[0], 1.0), {dims[0]});
}

/// 8 -> 9 (2026-12-08, a Maxwell liquid, issue 26): a liquid layer gains `maxwell_time` = 0 (its
/// springs stayed elastic; no `support`: none was set).
void layout_8_to_9(hid_t root) {
  const char* liquid = "/checkpoint/liquid";
  if (!h5::exists(root, liquid)) return;
  h5::Group group = h5::open_group(root, liquid);
  if (!has_attribute(group.get(), "maxwell_time")) h5::write_attribute<double>(group.get(), "maxwell_time", 0.0);
}

/// One upgrade step, from format `from` to `from + 1`.
struct UpgradeStep {
  std::int64_t from;
  void (*layout)(hid_t root);                ///< on the file's objects before they are read; nullptr: unchanged
  void (*meaning)(Checkpoint& checkpoint);   ///< on the checkpoint read; nullptr: nothing to redo
};

/// Every step, in order; the last one reaches checkpoint_format_version. A new format adds its
/// step here (e.g. a fingerprint scheme: {4, nullptr, recompute_fingerprint}).
constexpr UpgradeStep upgrade_steps[] = {
    {3, layout_3_to_4, nullptr},
    {4, layout_4_to_5, nullptr},
    {5, layout_5_to_6, nullptr},
    {6, layout_6_to_7, nullptr},
    {7, layout_7_to_8, nullptr},
    {8, layout_8_to_9, nullptr},
};
constexpr bool steps_are_consecutive() {
  for (std::size_t i = 0; i < std::size(upgrade_steps); ++i)
    if (upgrade_steps[i].from != oldest_readable_format + static_cast<std::int64_t>(i)) return false;
  return true;
}
static_assert(steps_are_consecutive(), "upgrade_steps[i] goes from format oldest_readable_format + i");
static_assert(oldest_readable_format + static_cast<std::int64_t>(std::size(upgrade_steps)) ==
                  checkpoint_format_version,
              "one upgrade step per format version from the oldest readable one to the current one");

}  // namespace

bool needs_layout_upgrade(hid_t root, std::int64_t version) {
  return version < checkpoint_format_version || (version == 4 && complete_format_4(root, false));
}

void upgrade_layout(hid_t root, std::int64_t version) {
  for (std::int64_t v = version;; ++v) {
    // Completed while the objects are at format 4, before any later step renames what it adds.
    if (v == 4) complete_format_4(root, true);
    if (v == checkpoint_format_version) break;
    const UpgradeStep& step = upgrade_steps[v - oldest_readable_format];
    if (step.layout) step.layout(root);
    set_format_version(root, v + 1);
  }
}

void upgrade_meaning(Checkpoint& checkpoint, std::int64_t version) {
  for (const UpgradeStep& step : upgrade_steps)
    if (step.from >= version && step.meaning) step.meaning(checkpoint);
}

}  // namespace tidalcrust
