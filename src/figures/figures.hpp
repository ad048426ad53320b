#pragma once
// The paper-style figures of an encounter (paper section 3), each written as <stem>.png and
// <stem>.svg (figure_output.hpp). All positions are taken relative to the body's centre of
// mass in the map frame of orbital_frame.hpp (orbital plane = equator, subsatellite point +y).
#include <filesystem>
#include <string>
#include <vector>

#include "model/checkpoint.hpp"
#include "analysis/fracture_analysis.hpp"
#include "analysis/sweep_report.hpp"
#include "figures/plot_axes.hpp"

namespace tidalcrust {

using FigureFiles = std::vector<std::filesystem::path>;

/// Figure 8 (fig:lat): cylindrical map, longitude -180..180 deg, latitude -90..90 deg, cracks as
/// dual-lattice bars (Figure 4; drawn as map_segment_pieces), subsatellite
/// point (+90, 0) marked by a yellow ring.
FigureFiles write_fracture_map(const FractureSummary& fractures, const std::filesystem::path& stem,
                               const std::string& title);
/// One line drawn on the fracture map: longitudes in [-180, 180] and latitudes, degrees.
struct MapPolyline {
  std::vector<double> longitude_deg, latitude_deg;
};
/// The map image of the straight segment from -> to (R, relative to the centre of mass, map
/// frame), as the pieces to draw: sampled so that no step spans more than 3 degrees of longitude
/// or latitude (a segment near a pole bends as the projection does), split in two where it
/// crosses the +-180 degree seam (both pieces end on the seam at the same latitude), and broken
/// where it passes over a pole (where the projection stretches one point into the map's whole top
/// or bottom edge). No piece crosses the map.
std::vector<MapPolyline> map_segment_pieces(const Vec3& from, const Vec3& to);
/// Where write_fracture_map puts longitude (x, degrees) and latitude (y, degrees), in points.
PlotAxes fracture_map_axes();
/// Draws one fracture map into `axes` (longitude -180..180, latitude -90..90): ice, graticule,
/// crack bars, subsatellite ring, frame with ticks and axis labels. Every fracture map is drawn
/// by it: write_fracture_map's and each panel of write_fracture_map_row.
void draw_fracture_map(cairo_t* cr, const PlotAxes& axes, const FractureSummary& fractures);
/// Fracture maps side by side (`compare --resolution`: one panel per shell level, coarsest
/// first), each drawn by draw_fracture_map at half the size of write_fracture_map's and titled
/// with `panel_titles[i]`; `title` (two lines, as draw_title) above the row. InputError naming the
/// stem if there is no panel or the titles do not match the panels (and as write_figure).
FigureFiles write_fracture_map_row(const std::vector<const FractureSummary*>& panels,
                                   const std::vector<std::string>& panel_titles, const std::filesystem::path& stem,
                                   const std::string& title);
/// Where write_fracture_map_row puts longitude and latitude of panel `index`, in points (the
/// panels are 320 x 160 points; the figure is as wide as its panels need).
PlotAxes fracture_map_row_axes(std::size_t index);

/// The crack geometry (docs/crack-geometry.md), one figure: left the fracture map
/// (draw_fracture_map) with the small circles fitted to the long cracks (FractureSummary::geometry;
/// the arc each crack covers thick in arc_color, the rest of its circle dashed) and their poles
/// as numbered dots; right the rose of crack azimuths (CrackOrientations: 18 axial bins, each
/// drawn at a and a + 180 deg, equal-area petals of radius ~ sqrt(count), 0 = toward the
/// subsatellite point up, counter-clockwise as seen from outside; dashed: the uniform level),
/// below it the concentricity and a line per fitted arc (pole, its angle from the subsatellite
/// axis, radius, arc, misfit).
FigureFiles write_crack_geometry(const FractureSummary& fractures, const std::filesystem::path& stem,
                                 const std::string& title);
/// Where write_crack_geometry puts longitude (x) and latitude (y) of its map, degrees, in points.
PlotAxes crack_geometry_map_axes();
/// Where write_crack_geometry draws its rose: centre and the radius of the fullest bin, points.
struct CrackRoseLayout {
  double center_x = 0, center_y = 0, radius = 0;
};
CrackRoseLayout crack_rose_layout();

/// Figure 6 (fig:T5): one panel per checkpoint (all of one body, in the given order), each an
/// orthographic view of the hemisphere centred on the subsatellite point. The viewer sits on the
/// +y axis in the orbital plane, looking toward -y, north (+z) up, so +x points left and the
/// perturber crosses from left to right (the paper's viewer at -y sees a frame turned by pi about
/// x, where it moves right to left). Lambert-shaded triangles, crack bars in black, the perturber
/// as a translucent magenta disc of radius M2^(1/3) R (same density as the body), hidden by the
/// body when behind it, under the cracks when in front (hemisphere_panel_layers). Panels are
/// labelled with t - t_peri in t_grav.
FigureFiles write_hemisphere_views(const std::vector<const Checkpoint*>& snapshots, double pericenter_time,
                                   const std::filesystem::path& stem, const std::string& title);
/// What a hemisphere panel draws, in the order returned by hemisphere_panel_layers.
enum class HemisphereLayer { faces, cracks, perturber_fill, perturber_outline };
/// Drawing order of one hemisphere panel: faces then cracks; a perturber behind the body first
/// (the faces cover it); a perturber in front as a translucent fill between the faces and the
/// cracks, and its outline last, so that the disc never hides a crack.
std::vector<HemisphereLayer> hemisphere_panel_layers(bool perturber_present, bool perturber_in_front);
/// Where panel `index` of write_hemisphere_views (of `panel_count`) puts screen coordinates
/// (x = -x_body, y = z_body, R relative to the centre of mass), in points.
PlotAxes hemisphere_panel_axes(std::size_t index, std::size_t panel_count);

/// Figure 7 (fig:orbit): perturber track relative to the body centre in the orbital plane over
/// the stage, the body as a black disc of radius R, red diamonds every 0.1 t_grav, open circles
/// of radius M2^(1/3) R at `snapshot_times`, a red arrow for the direction of motion at the
/// closest approach, and the stored perturber position of the checkpoint. The track is the
/// simulated one (recorded_track.hpp: the timeseries samples' perturber_offset, with the body's
/// recoil and tidal effects), with the analytic two-body orbit (two_body_orbit.hpp) as a thin grey
/// dashed reference; a checkpoint without such samples gets the analytic track alone.
FigureFiles write_orbit_plot(const Checkpoint& checkpoint, const EncounterRecord& record,
                             const std::vector<double>& snapshot_times, const std::filesystem::path& stem,
                             const std::string& title);
/// Where write_orbit_plot with the same arguments puts x, y (R relative to the centre of mass),
/// in points.
PlotAxes orbit_plot_axes(const Checkpoint& checkpoint, const EncounterRecord& record,
                         const std::vector<double>& snapshot_times);

/// Failed shell springs against t - t_peri (failure events; timeseries counts if there are none).
FigureFiles write_failure_history(const Checkpoint& checkpoint, double pericenter_time,
                                  const std::filesystem::path& stem, const std::string& title);

/// Conservation diagnostics against t - t_peri from the timeseries: (K - K0)/K0 of the kinetic
/// energy, |P - P0| and |L - L0| (body + perturber, about the origin).
FigureFiles write_conservation_plot(const Checkpoint& checkpoint, double pericenter_time,
                                    const std::filesystem::path& stem, const std::string& title);

/// Phase diagram of a sweep (`tidalcrust report`): the encounters of `report` with this M2 and
/// eps_S over pericenter q (x, R) and pericenter speed V_q (y, sqrt(GM/R)); filled circles
/// coloured by the failed fraction of the shell springs where the crust cracked (colour bar at the
/// right), open circles where it did not, grey crosses for encounters not finished; the paper's
/// eq. 5 strain = eps_S line (V_q = M2 / (E^(1/2) q^2 eps_S), E = report.youngs_modulus) in
/// eq5_line_color, and the crack/no-crack boundary (grid-cell edges between a cracked and an
/// intact finished neighbour) dashed in boundary_color. InputError if no encounter matches.
/// With `crack_probability` (rows of crack_probability_report) every point is filled in the
/// colour of its share of cracked members on [0, 1], and the boundary runs where it falls
/// through 1/2.
FigureFiles write_phase_diagram(const SweepReport& report, double perturber_mass, double failure_strain,
                                const std::filesystem::path& stem, bool crack_probability = false);
/// Where write_phase_diagram puts q (x) and V_q (y) for these encounters (one M2 and eps_S) and
/// E = youngs_modulus (e_g), in points: their range, widened to where eq. 5 crosses strain =
/// eps_S over their speeds (at most to 4x their largest q).
PlotAxes phase_diagram_axes(const std::vector<const SweepRow*>& rows, double youngs_modulus);

}  // namespace tidalcrust
