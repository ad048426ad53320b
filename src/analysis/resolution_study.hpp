#pragma once
// A resolution-convergence study (`tidalcrust compare --resolution`, issue 13): the same encounter
// of one material body run at several shell levels, one row per encounter checkpoint, coarsest
// first, with the fracture statistics that should converge as the lattice is refined (the failed
// AREA fraction, the total crack length, the hemisphere fraction and the median angle from the
// subsatellite point; the failed spring count does not: the number of springs grows as 4^L) and
// their relative change from the next coarser row. Units: G = M = R = 1.
#include <cstddef>
#include <string>
#include <vector>

#include "analysis/fracture_analysis.hpp"
#include "io/json.hpp"
#include "model/choices.hpp"
#include "model/encounter.hpp"

namespace tidalcrust {

/// The icosphere level L with shell_nodes = 10 4^L + 2 (README, Table 3 row), or -1 if there is none.
int shell_level_of(std::size_t shell_nodes);

struct ResolutionRow {
  std::string file;             ///< as given on the command line
  std::size_t shell_nodes = 0;  ///< N_S
  int shell_level = -1;         ///< from N_S = 10 4^L + 2; -1 if N_S is not of that form
  std::size_t particles = 0;    ///< interior + shell
  double dt = 0;                ///< the encounter's time step, t_grav
  std::string state_hash;
  FractureSummary fractures;    ///< analyze_fractures of the checkpoint (as analyze and compare)
  /// 100 (x - x_prev) / x_prev of failed_area_fraction, hemisphere_fraction and
  /// total_crack_length against the previous (coarser) row, percent; NaN for the first row and
  /// where x_prev is 0 or NaN. The crack length is the measure that can converge: the failed area
  /// is L_S / 2 times it by construction and halves with L_S (README, resolution convergence).
  double area_fraction_change_percent = 0;
  double hemisphere_fraction_change_percent = 0;
  double crack_length_change_percent = 0;
};

struct ResolutionStudy {
  Encounter encounter;                ///< name (of the first file), M2, q, V_q: shared by all rows
  double failure_strain = 0;          ///< eps_S, shared by all rows
  FailureRuleKind failure_rule = FailureRuleKind::paper;  ///< shared by all rows
  std::vector<ResolutionRow> rows;    ///< by shell node count ascending (ties: in the given order)
};

/// Reads the encounter checkpoints `files` (at least two) and tabulates them. InputError (one
/// line naming the file) when fewer than two files are given, a file cannot be read, is not a
/// finished encounter checkpoint (a mid-stage, snapshot or diagnostic checkpoint is not a result), has no
/// crust, or ran another encounter than the first file (perturber mass, pericenter, pericenter
/// speed, failure strain or failure rule differ). The bodies are not required to be the same:
/// that is the point of the study.
ResolutionStudy build_resolution_study(const std::vector<std::string>& files);

/// relative_change_percent(x, x_prev) = 100 (x - x_prev) / x_prev; NaN if x_prev is 0 or either is NaN.
double relative_change_percent(double x, double previous);

/// The study as JSON: encounter {name, perturber_mass, pericenter, pericenter_speed,
/// failure_strain, failure_rule} and rows [{file, shell_level (null if none), shell_nodes,
/// particles, dt, state_hash, failures (failure_summary_json, exactly what analyze's summary.json
/// holds), change_percent {failed_area_fraction, hemisphere_fraction, total_crack_length} (null where
/// undefined)}].
Json resolution_study_json(const ResolutionStudy& study);

/// CSV (io/csv.hpp): a header with units in brackets, then one row per checkpoint: file,
/// shell_level, shell_nodes, particles, dt, failed_springs, failed_area_fraction,
/// total_crack_length, largest_network_length, clusters, hemisphere_fraction, median_angle, the three
/// changes in percent (area, hemisphere, crack length), state_hash; undefined values are empty cells.
std::string resolution_study_csv(const ResolutionStudy& study);

}  // namespace tidalcrust
