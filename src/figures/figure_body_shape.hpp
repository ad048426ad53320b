#pragma once
// Figure 5 (fig:mush) of the paper: the body's shape during an encounter, for the interior-only
// run N (and any body): slices of the body in the orbital plane at several times, and its
// principal axis ratios over time (analysis/body_shape.hpp). Each written as PNG and SVG.
#include <filesystem>
#include <string>
#include <vector>

#include "analysis/body_shape.hpp"
#include "figures/plot_axes.hpp"
#include "model/checkpoint.hpp"

namespace tidalcrust {

/// Half thickness of the slice about the orbital plane that write_body_slices draws, R.
inline constexpr double body_slice_half_width = 0.12;

/// One panel per checkpoint (all of one body, in the given order), looking down on the orbital
/// plane (+x right, +y up, positions relative to the centre of mass): the outline of the whole
/// body projected onto the plane (its convex hull, grey), the springs with both ends within
/// body_slice_half_width of the plane (pink, as the paper draws them) and those particles (dark
/// dots); the perturber's direction as a magenta arrow at the rim when present. Panels are
/// labelled with t - t_peri and b/a. InputError when `snapshots` is empty.
std::vector<std::filesystem::path> write_body_slices(const std::vector<const Checkpoint*>& snapshots,
                                                     double pericenter_time, const std::filesystem::path& stem,
                                                     const std::string& title);
/// Where panel `index` of write_body_slices (of `panel_count`) puts x, y (R), in points.
PlotAxes body_slice_panel_axes(std::size_t index, std::size_t panel_count);

/// Principal axis ratios b/a (solid) and c/a (dashed) against t - t_peri, one marker per time:
/// time_from_pericenter [k] in t_grav and the axes at those times [k].
std::vector<std::filesystem::path> write_axis_ratios(const std::vector<double>& time_from_pericenter,
                                                     const std::vector<PrincipalAxes>& axes,
                                                     const std::filesystem::path& stem, const std::string& title);
/// Where write_axis_ratios with these times and axes puts t - t_peri and the ratio, in points.
PlotAxes axis_ratio_axes(const std::vector<double>& time_from_pericenter, const std::vector<PrincipalAxes>& axes);

}  // namespace tidalcrust
