#pragma once
// Stage 5 (paper section 3): analysis of one encounter checkpoint into a folder: summary.json (its
// crack_geometry object last: docs/crack-geometry.md), cracks.json and figure_data.json, then
// the figures (fracture map, crack geometry, hemisphere views, orbit, failures over time,
// conservation, body shape, axis ratios; PNG + SVG) drawn from them by the Python package.
#include <filesystem>
#include <string>
#include <vector>

#include "model/checkpoint.hpp"
#include "analysis/fracture_analysis.hpp"

namespace tidalcrust {

/// Writes cracks.json, figure_data.json and summary.json (last, each atomically) of `checkpoint`,
/// read from `from` (snapshots ENC.snap-<step>.h5 beside it form the hemisphere row; one that
/// cannot be read is skipped with a line on stderr and listed in summary.json's
/// "skipped_snapshots"), then removes the figures of an earlier analysis and draws them anew
/// (draw_figures, figures/figure_script.hpp); with `with_figures` false it only removes them and lists
/// none in summary.json (`[analysis] figures`). Returns the figure files drawn.
/// InputError for a checkpoint that is not an encounter, and (after the files) for a figure
/// process that cannot run or fails.
std::vector<std::filesystem::path> analyze_encounter(const std::filesystem::path& from, const Checkpoint& checkpoint,
                                                     const std::filesystem::path& out, bool with_figures = true);

/// True if out/summary.json was written for exactly this state (same state_hash) by an analysis
/// that writes everything this one does (it has the failure_trend object, summary.json's newest;
/// cracks.json and figure_data.json beside it) with every snapshot read (its "skipped_snapshots"
/// list empty; a summary without the list, written before it existed, counts as not finished)
/// and every figure it lists drawn; with `with_figures`, also one that lists figures (an analysis
/// made without them is redone when they are wanted).
bool analysis_is_current(const std::filesystem::path& out, const Checkpoint& checkpoint, bool with_figures = true);

/// The warning line of an encounter that ended while its crust was still failing
/// (analysis/failure_trend.hpp), "" otherwise; summary.json holds the numbers ("failure_trend").
std::string failure_trend_line(const std::string& name, const Checkpoint& encounter);

/// One line: failures, fraction, hemisphere fraction, mean angle, cracks, largest crack network.
std::string fracture_summary_line(const std::string& name, const FractureSummary& fractures);

}  // namespace tidalcrust
