#pragma once
// Fracture statistics of a shell (paper section 3, Figures 6 and 8): which shell springs failed,
// where they lie in the orbital frame (orbital_frame.hpp), how they cluster into cracks and how
// long the cracks are. Cracks are drawn and measured on the dual lattice (section 2.6, Figure 4):
// a failed edge shows as a bar from the centroid of each of its two faces to the edge midpoint,
// so two failed edges of one triangle make a bent bar and three make a three-pronged fork.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/crack_geometry.hpp"
#include "io/json.hpp"
#include "model/body.hpp"
#include "model/checkpoint.hpp"
#include "physics/orbital_frame.hpp"
#include "model/state.hpp"
#include "base/vec3.hpp"

namespace tidalcrust {

struct FailedShellSpring {
  std::int32_t spring = 0;              ///< index into Body::springs
  Vec3 midpoint = Vec3::Zero();         ///< relative to the body's centre of mass, R
  double longitude_deg = 0;             ///< (-180, 180], subsatellite point at +90
  double latitude_deg = 0;              ///< [-90, 90], orbital plane at 0
  double angle_from_subsatellite_deg = 0;
  /// Orientation of its crack (perpendicular to the spring, tangent to the sphere) from the local
  /// direction toward the subsatellite point, [0, 180) deg (crack_azimuth_deg); NaN where undefined.
  double crack_azimuth_deg = 0;
};

/// Half of a dual-lattice bar: inside face `face`, from its centroid to the midpoint of the
/// failed edge `spring`. Positions relative to the body's centre of mass, R.
struct CrackBar {
  std::int32_t face = 0;
  std::int32_t spring = 0;
  Vec3 centroid = Vec3::Zero();
  Vec3 edge_midpoint = Vec3::Zero();
};

/// Failed springs connected through shared faces (two failed edges of one triangle touch).
struct CrackCluster {
  std::vector<std::int32_t> springs;  ///< ascending spring indices
  double length = 0;  ///< sum of its dual-lattice bar lengths, R
  double extent = 0;  ///< largest great-circle distance between two of its face centroids,
                      ///< measured on the unit sphere (radians = R)
};

struct FractureSummary {
  static constexpr double angle_bin_width_deg = 10;
  static constexpr std::size_t angle_bins = 18;  ///< 0..180 degrees

  std::size_t shell_springs = 0;
  std::vector<FailedShellSpring> failed;  ///< ascending spring index
  /// Failed shell springs left out because they failed before the encounter (FractureScope::earlier:
  /// an encounter of a history), ascending; the maps draw them apart.
  std::vector<std::int32_t> earlier_failed;
  /// The subsatellite direction the angles, azimuths and arc poles are measured from (a unit vector).
  Vec3 subsatellite = subsatellite_direction;
  std::vector<CrackBar> bars;             ///< by face, then edge
  std::vector<CrackBar> earlier_bars;     ///< the same for earlier_failed
  std::vector<CrackCluster> clusters;     ///< longest first (ties: lowest first spring)
  double fraction_shell = 0;        ///< failed / shell springs; NaN without shell springs
  double hemisphere_fraction = 0;   ///< share of failed springs with midpoint . (+y) > 0; NaN if none
  double mean_angle_from_subsatellite_deg = 0;  ///< NaN if none failed
  double median_angle_from_subsatellite_deg = 0;  ///< NaN if none failed (robust to a few far cracks)
  /// Length of the longest cluster, R (0 if none): the largest connected crack network (all its
  /// branches), not one crack; summary.json's largest_network_length (before issue 27:
  /// longest_crack).
  double longest_crack_length = 0;
  double longest_crack_extent = 0;  ///< its great-circle extent, R (0 if none): largest_network_extent
  /// Sum of the lengths of all clusters (= of all dual-lattice bars), R (0 if none). Unlike the
  /// failed count, it converges with resolution: a crack of given length crosses ~1/L_S bars.
  double total_crack_length = 0;
  /// Failed share of the shell AREA: each shell spring stands for a third of the area of each of
  /// its faces (the thirds sum to the whole shell), so a failed spring counts (A_f1 + A_f2)/3 of
  /// the total face area, both measured on the state's positions. Unlike fraction_shell (a share
  /// of springs, whose size shrinks as L_S^2) it converges with resolution. NaN without faces.
  double failed_area_fraction = 0;
  std::array<std::int64_t, angle_bins> angle_histogram{};  ///< failed springs per 10-degree bin
  /// Small circles fitted to the long clusters, the rose of crack azimuths and the concentricity
  /// (crack_geometry.hpp, docs/crack-geometry.md).
  CrackGeometry geometry;

  std::size_t count() const { return failed.size(); }
  std::vector<double> angles_from_subsatellite_deg() const;
};

/// Which failed springs a FractureSummary counts and about which point.
struct FractureScope {
  /// The direction of the perturber at pericenter (unit vector): the encounter's orbit's
  /// (subsatellite_direction_of); +y for the paper's orbit.
  Vec3 subsatellite = subsatellite_direction;
  /// [springs] true for a spring that failed before the encounter (an encounter of a history):
  /// left out of every statistic, listed in FractureSummary::earlier_failed. Empty: none.
  std::vector<bool> earlier;
  /// The rotation that takes the state's positions (relative to the centre of mass) into the frame
  /// the summary is given in: for a spinning body (docs/spin.md) the body frame,
  /// Rz(Omega t)^T (physics/spin_frame.hpp); the identity otherwise. `subsatellite` is in that frame.
  Matrix3 to_body = Matrix3::Identity();
};

/// The scope of an encounter checkpoint: its orbit's subsatellite direction, and for an encounter
/// that came after another (EncounterRecord's encounter.after) the springs failed before it began:
/// failed in the state and absent from its failure log. The default scope for other stages.
/// A spinning body's encounter (spin.angular_velocity of the stored configuration) is seen in the
/// body frame (`in_body_frame`, the maps' frame): to_body = Rz(Omega t)^T at the state's time t,
/// and the subsatellite point is the pericenter direction turned back by the angle the body had
/// turned at pericenter, Rz(Omega t_q)^T; with `in_body_frame` false, in the inertial frame
/// (the hemisphere views, drawn with the perturber). InputError for a stored configuration that
/// does not parse.
FractureScope fracture_scope(const Checkpoint& c, bool in_body_frame = true);

/// The spin of a checkpoint's body, rad/t_grav: spin.angular_velocity of its stored configuration
/// (0 without one, a checkpoint made in memory). InputError naming `origin` for a stored text
/// that does not parse.
double stored_spin(const Checkpoint& c, const std::string& origin = "checkpoint");

/// Analyses the failed shell springs of `state` (State::springs.failed, shell kind only) within
/// `scope`. Throws InputError if the shell faces and springs, or the scope's flags, do not match.
FractureSummary analyze_fractures(const Body& body, const State& state, const FractureScope& scope = {});
/// analyze_fractures of a checkpoint within its fracture_scope: what every report of an encounter uses.
FractureSummary analyze_fractures(const Checkpoint& c);

/// The `failures` object of summary.json, compare --json and inspect: count, fraction_shell,
/// hemisphere_fraction, mean_angle_from_subsatellite_deg, median_angle_from_subsatellite_deg,
/// largest_network_length, largest_network_extent (R; the longest cluster, named longest_crack and
/// longest_crack_extent before issue 27), clusters (number of clusters), total_crack_length (R),
/// failed_area_fraction, then the crack geometry (docs/crack-geometry.md): concentricity (1),
/// crack_rose_peak_deg, fitted_arcs (number of CrackGeometry::arcs), median_arc_radius_deg,
/// median_arc_pole_axis_from_subsatellite_deg, and of the longest fitted arc longest_arc_radius_deg,
/// longest_arc_pole_axis_from_subsatellite_deg, longest_arc_span_deg (its arc_deg) and
/// longest_arc_misfit_deg (rms), in that order (new keys go at the end: readers of summary.json rely
/// on it); count, clusters and fitted_arcs are integers, undefined (NaN) values are written as null
/// (the crack-geometry keys hold null in the Json too, where no failure or no arc defines them).
Json failure_summary_json(const FractureSummary& summary);

/// The unit of a key of failure_summary_json: "R" for the crack lengths (largest_network_length,
/// largest_network_extent, total_crack_length), "deg" for the keys ending in _deg, "1" for the
/// counts and ratios.
std::string_view failure_summary_unit(std::string_view key);

/// cracks.json of `analyze` (docs/python.md, docs/crack-geometry.md), the one home of the crack
/// polylines the Python package turns into GeoJSON and shapefiles: `format` ("tidalcrust-cracks"),
/// `version` (1), `frame` and `units` (text), `state_hash` (given), `crack_count`, and `cracks`,
/// one object per cluster in the order of FractureSummary::clusters (longest first): `crack` (its
/// index), `springs` (ascending spring indices), `length` and `extent` (R), and `polylines`, one
/// per failed spring in the order of `springs`: the spring's dual-lattice bar as
/// [[lon, lat], ...] in degrees of the maps' orbital frame (directions from the centre of mass;
/// longitude (-180, 180], subsatellite point at +90, orbital plane the equator): the centroid of
/// its first face, the spring's midpoint, the centroid of its second face (2 vertices for a
/// spring on one face only). A polyline is not cut at the antimeridian; readers do that. Then
/// `subsatellite` ([lon, lat] of the encounter's subsatellite point) and `earlier` (the springs
/// that failed before the encounter, an encounter of a history: `springs` and their `polylines`,
/// empty lists otherwise).
Json crack_polylines_json(const FractureSummary& summary, const std::string& state_hash);

}  // namespace tidalcrust
