#pragma once
// The table of a workflow's encounters (`tidalcrust report`): one row per encounter of the
// workflow, finished or not, with its inputs, the impulse strain estimate of the paper's eq. 5 and,
// for a finished encounter, its fracture statistics (fracture_analysis.hpp), the energy it put
// into the body (energy_budget.hpp) and its state_hash; plus where each (M2, eps_S, V_q) line of
// the grid switches from crack to no crack, next to where eq. 5 puts the switch. Units:
// G = M = R = 1 (masses in M, distances in R, speeds in sqrt(GM/R), energies in G M^2/R).
#include <array>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "analysis/crack_geometry.hpp"
#include "analysis/ensemble_statistics.hpp"
#include "io/json.hpp"
#include "model/config.hpp"
#include "model/moon_units.hpp"

namespace tidalcrust {

/// Where an encounter of the workflow stands in its output folder.
enum class SweepStatus {
  finished,    ///< encounter.h5 complete, of this workflow's values and relaxed body
  unfinished,  ///< only a mid-stage checkpoint (interrupted, or running now)
  missing,     ///< nothing yet
  stale,       ///< encounter.h5 of other values or another relaxed body (rerun to refresh)
  unreadable,  ///< encounter.h5 that cannot be read (the note says why)
};
const char* status_name(SweepStatus status);

struct SweepRow {
  Encounter encounter;          ///< as the workflow defines it (name, M2, q, V_q)
  double failure_strain = 0;    ///< eps_S it runs with (its own, else shell.failure_strain)
  double strain_estimate = 0;   ///< eq. 5 with E = E_I of the relaxed body
  SweepStatus status = SweepStatus::missing;
  std::string note;             ///< e.g. "stopped at step 1200 of 5001", an error, a staleness reason
  // Finished encounters only (NaN / 0 / empty otherwise):
  std::size_t failures = 0;                     ///< failed shell springs
  double failed_fraction = 0;                   ///< of the shell springs
  double hemisphere_fraction = 0;               ///< of the failures on the subsatellite hemisphere; NaN if none
  double median_angle_deg = 0;                  ///< from the subsatellite point; NaN if none
  double largest_network_length = 0;            ///< dual-lattice length of the largest connected crack network, R
  double energy_deposited = 0;                  ///< internal energy after minus before, G M^2/R
  double energy_dissipated = 0;                 ///< to damping and failures, G M^2/R
  std::string state_hash;
  // Crack geometry (FractureSummary::geometry, docs/crack-geometry.md); finished encounters only:
  double concentricity = 0;                     ///< mean |sin| of the crack azimuths; NaN if none failed
  std::size_t fitted_arcs = 0;                  ///< long cracks with a fitted small circle
  double median_arc_radius_deg = 0;             ///< median angular radius of those circles; NaN if none
  double median_arc_pole_axis_deg = 0;          ///< median angle of their poles' axes from the subsatellite axis; NaN if none
  /// Share of the crack azimuths in the rose's sectors about 0, 45, 90, 135 deg (CrackOrientations);
  /// NaN if none failed.
  std::array<double, CrackOrientations::sectors> rose_sector_share{};
  double total_crack_length = 0;                ///< dual-lattice length of every crack, R
  std::size_t cracks = 0;                       ///< connected crack networks (clusters)
  bool cracked() const { return status == SweepStatus::finished && failures > 0; }
};

/// One line of the grid (fixed M2, eps_S and V_q) along q: where the finished encounters switch
/// from crack to no crack, and where eq. 5 puts strain = eps_S.
struct CrackBoundary {
  double perturber_mass = 0;
  double failure_strain = 0;
  double pericenter_speed = 0;
  double largest_cracked_q = 0;   ///< largest q with a crack; NaN if none cracked
  double smallest_intact_q = 0;   ///< smallest q above it without a crack; NaN if none
  double eq5_q = 0;               ///< q where eq. 5 gives strain = eps_S: sqrt(M2 / (E^(1/2) V_q eps_S))
  // An [ensemble] workflow's lines are its encounters before the expansion (unperturbed q), a
  // point "cracked" when any member cracked; and the probability of cracking gives (NaN otherwise):
  double half_probability_q = 0;  ///< q where the share of cracked members falls through 1/2 (linear between points)
  /// The boundary's 95% range: the largest q below it whose Wilson interval lies above 1/2 (a crack
  /// more likely than not beyond the noise) and the smallest q above that whose interval lies below 1/2.
  double half_probability_q_low = 0;
  double half_probability_q_high = 0;
};

/// One statistic of the ensemble table: its name (as in the CSV and JSON), unit and value of a
/// finished row. The list (ensemble_statistic_names) is the one home of what an ensemble reports.
struct EnsembleStatistic {
  const char* name;
  const char* unit;
  double (*value)(const SweepRow& row);
};
/// The statistics summarised over an ensemble's members, in table order.
std::span<const EnsembleStatistic> ensemble_statistics();

/// One encounter of an [ensemble] workflow over its members (docs/ensembles.md).
struct EnsembleRow {
  Encounter encounter;            ///< before the expansion: its name and unperturbed q
  double failure_strain = 0;      ///< eps_S its members run with
  double strain_estimate = 0;     ///< eq. 5 at the unperturbed q
  std::size_t members = 0;
  std::size_t finished = 0;       ///< members finished; the statistics are over these
  ProportionInterval cracked;     ///< finished members with at least one failure (Wilson interval)
  /// One per ensemble_statistics(), in order: summarize_about_trend over the finished members
  /// against their pericenter offsets (the value at the unperturbed q, the scatter about the trend).
  std::vector<SampleSummary> statistics;
};

struct SweepReport {
  std::string workflow;                  ///< the workflow's name
  std::filesystem::path folder;          ///< where its encounters are (root, or root/dt<factor>)
  double dt_factor = 1.0;
  double youngs_modulus = 0;             ///< E_I of the relaxed body (eq. 15), e_g: the E of eq. 5
  std::vector<SweepRow> rows;            ///< the workflow's encounters, in its order
  std::vector<CrackBoundary> boundaries; ///< by M2, eps_S, V_q (ascending)
  std::vector<EnsembleRow> ensembles;    ///< per encounter before the expansion; empty without [ensemble]
  EnsembleVariation ensemble_vary = EnsembleVariation::pericenter;  ///< what differs between the members
  /// Of a [moon] workflow: the moon whose SI units the tables give beside the model's (docs/moon.md).
  std::optional<MoonScale> moon;
  std::size_t count(SweepStatus status) const;
};

/// The configuration an encounter of the workflow was computed with, as its body chain left it
/// (stages/workflow.hpp, body_chain_config: the relax's time step of that body, its seed); called
/// with nullptr for the workflow's own body.
using BodyChainConfig = std::function<Config(const Encounter*)>;

/// The report of the encounters of `config` (validated) below `root` (the --out of run; with
/// dt_factor != 1 the encounters of root/dt<factor>/), read from their checkpoints, each judged
/// against the relaxed body it branches from (body_folder: root/body, or root/body-seed<N> for a
/// member on a body of its own) and the configuration `prepared` gives for it. InputError when
/// root/body/relax.h5 is missing or unfinished (nothing has been run: the message says which
/// command runs it) or cannot be read; an encounter that cannot be read is a row marked
/// unreadable, one whose own body is not relaxed yet a row marked missing or stale.
SweepReport build_sweep_report(const Config& config, const std::filesystem::path& root, double dt_factor,
                               const BodyChainConfig& prepared);

/// The report of `report`'s ensemble rows as rows of their own, for the phase diagram of crack
/// probability: a row per encounter before the expansion (unperturbed q), finished when a member
/// finished, with failures = the members that cracked and failed_fraction = their share.
SweepReport crack_probability_report(const SweepReport& report);

/// The strain of eq. 5, (e_g/E)^(1/2) (R/q)^2 (M2/M) (v_c/V_q), for E in e_g.
double eq5_strain(const Encounter& encounter, double youngs_in_e_g);

/// The ensemble table as CSV: per encounter (before the expansion) its inputs, members finished,
/// the cracked share with its interval, then per statistic mean, sd, low, high (95%, Student t;
/// summarize_about_trend). Of a [moon] workflow, last, M2, q, V_q and the mean, sd, low, high of
/// each statistic in a model unit again in SI ("total_crack_length_mean [km]", ...).
std::string ensemble_report_csv(const SweepReport& report);
/// The same as JSON, with the method of each interval stated.
Json ensemble_report_json(const SweepReport& report);

/// One ensemble of an ensembles.json, read back.
struct StoredEnsemble {
  std::string name;
  std::size_t finished = 0;
  std::vector<SampleSummary> statistics;  ///< in ensemble_statistics() order; count 0 where the file has none
};
/// The ensembles of `file` (an ensembles.json that ensemble_report_json wrote). InputError naming
/// the file when it cannot be read or is not an ensemble table.
std::vector<StoredEnsemble> read_ensemble_report(const std::filesystem::path& file);

/// CSV, one header row with the unit of each column in brackets, then one row per encounter;
/// cells of values an encounter does not have (not finished, NaN) are empty. The crack-geometry
/// columns (concentricity, fitted_arcs, median_arc_radius, median_arc_pole_axis) come after
/// the note: readers rely on the order of the others. Of a [moon] workflow the SI columns follow
/// last (sweep_si_columns: "M2 [kg]", "q [km]", "V_q [km/s]", crack lengths in km, energies in J).
std::string sweep_report_csv(const SweepReport& report);

/// The report as JSON: workflow, folder, dt_factor, youngs_modulus_E_I, counts per status, the
/// encounters (one object per row, NaN as null; the crack-geometry keys last) and the crack
/// boundaries. Of a [moon] workflow each encounter and boundary has an object "si" last (the
/// same values in SI, keys si_key(...): "pericenter_km", ...), and the report one "si" with the
/// units text and the moon.
Json sweep_report_json(const SweepReport& report);

/// A column of the sweep table that a [moon] workflow also gives in SI: its CSV name, its JSON
/// key, its dimension and its model value of a row.
struct SweepSiColumn {
  const char* csv_name;
  const char* json_key;
  Dimension dimension;
  double (*value)(const SweepRow& row);
};
/// The SI columns, in table order.
std::span<const SweepSiColumn> sweep_si_columns();

}  // namespace tidalcrust
