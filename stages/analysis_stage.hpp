#pragma once
// Stage 5 (paper section 3): analysis of one encounter checkpoint into a folder of figures
// (fracture map, crack geometry, hemisphere views, orbit, failures over time, conservation; PNG +
// SVG) and summary.json (its crack_geometry object last: docs/crack-geometry.md).
#include <filesystem>
#include <string>
#include <vector>

#include "model/checkpoint.hpp"
#include "analysis/fracture_analysis.hpp"

namespace tidalcrust {

/// Writes the figures and summary.json (last, atomically) of `checkpoint`, read from `from`
/// (snapshots ENC.snap-<step>.h5 beside it form the hemisphere row; one that cannot be read is
/// skipped with a line on stderr and listed in summary.json's "skipped_snapshots"). Returns the
/// figure files.
/// InputError for a checkpoint that is not an encounter.
std::vector<std::filesystem::path> analyze_encounter(const std::filesystem::path& from, const Checkpoint& checkpoint,
                                                     const std::filesystem::path& out);

/// True if out/summary.json was written for exactly this state (same state_hash) by an analysis
/// that writes everything this one does (it has the failure_trend object, summary.json's newest)
/// with every snapshot read (its "skipped_snapshots" list empty; a summary without the list,
/// written before it existed, counts as not finished).
bool analysis_is_current(const std::filesystem::path& out, const Checkpoint& checkpoint);

/// The warning line of an encounter that ended while its crust was still failing
/// (analysis/failure_trend.hpp), "" otherwise; summary.json holds the numbers ("failure_trend").
std::string failure_trend_line(const std::string& name, const Checkpoint& encounter);

/// One line: failures, fraction, hemisphere fraction, mean angle, cracks, largest crack network.
std::string fracture_summary_line(const std::string& name, const FractureSummary& fractures);

}  // namespace tidalcrust
