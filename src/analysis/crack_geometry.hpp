#pragma once
// Crack geometry of a fracture set, what a geologist compares with a moon (docs/crack-geometry.md):
// small circles fitted to the long cracks (pole, angular radius, arc covered, misfit), the rose of
// crack azimuths about the subsatellite point and a concentricity measure. Everything is in the
// body's frame of the maps (physics/orbital_frame.hpp: for the paper's orbit the subsatellite point
// is +y, longitude +90, the orbital plane latitude 0; an encounter of another orientation gives
// its own subsatellite direction), on the unit sphere (positions are used by direction only).
//
// The small-circle fit is the least-squares fit of Gray, Geiser & Geiser (1980, "On the
// least-squares fit of small and great circles to spherically projected orientation data",
// Mathematical Geology 12, 173-184; also Mulchrone, Pastor-Galan & Gutierrez-Alonso 2013,
// Computers & Geosciences 54, 203-210): it minimises the sum of squared angular distances of the
// points from the circle, sum_i (angle(pole, x_i) - radius)^2, here by Gauss-Newton from the
// algebraic plane fit n.x = c of the points (pole n, radius acos c; the eigenvector method of GMT's
// fitcircle, with the points' mean removed so that the plane need not pass through the centre).
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "base/vec3.hpp"
#include "io/json.hpp"
#include "physics/orbital_frame.hpp"

namespace tidalcrust {

/// A small circle fitted to points on the unit sphere. All angles in degrees.
struct SmallCircleFit {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  Vec3 pole = Vec3::Zero();             ///< unit vector to the circle's centre; the centre of the smaller cap
  double pole_longitude_deg = nan;      ///< (-180, 180], subsatellite point at +90
  double pole_latitude_deg = nan;       ///< [-90, 90], orbital plane at 0
  double radius_deg = nan;              ///< angular radius, [0, 90] (90: a great circle)
  /// Azimuth about the pole that the points span: 360 deg minus the largest azimuth gap between
  /// two of them, [0, 360). A crack along three quarters of its circle covers 270.
  double arc_deg = nan;
  double arc_length = nan;              ///< that arc on the unit sphere, arc (rad) x sin(radius), R
  /// Unit vector on the circle where the covered arc begins; the arc runs from it through arc_deg
  /// counter-clockwise about the pole (right-handed: seen from outside, above the pole).
  Vec3 arc_start = Vec3::Zero();
  double rms_misfit_deg = nan;          ///< sqrt(mean_i (angle(pole, x_i) - radius)^2)
  double pole_from_subsatellite_deg = nan;  ///< angle between the pole and the subsatellite point, [0, 180]
  /// Angle between the pole's axis and the subsatellite axis, min(d, 180 - d) of the above, [0, 90]:
  /// 0 for a circle concentric about the subsatellite point or its antipode.
  double pole_axis_from_subsatellite_deg = nan;
  std::size_t points = 0;               ///< points fitted
  int iterations = 0;                   ///< Gauss-Newton steps taken
  bool finite() const;                  ///< every number above is finite
};

/// Largest number of Gauss-Newton steps of fit_small_circle; it stops earlier when a step moves
/// the pole and the radius by less than fit_step_tolerance (radians).
inline constexpr int max_fit_iterations = 100;
inline constexpr double fit_step_tolerance = 1e-13;

/// Least-squares small circle through `points` (any nonzero vectors, used by direction; order
/// fixes the result bit for bit): the algebraic plane fit as the start, then Gauss-Newton on
/// (pole, radius) with step halving whenever a step would raise the sum of squares, at most
/// max_fit_iterations steps. At least 3 points (asserted). Degenerate sets (all points on one
/// spot, or a short arc of a noisy line) give a circle without meaning, possibly not finite
/// (SmallCircleFit::finite): fit long cracks only (CrackGeometry).
SmallCircleFit fit_small_circle(const std::vector<Vec3>& points, const Vec3& subsatellite = subsatellite_direction);

/// The point at azimuth `angle_deg` along the fitted circle from fit.arc_start (counter-clockwise
/// about the pole): a unit vector. At 0 it is arc_start; at fit.arc_deg the other end of the arc.
Vec3 point_on_circle(const SmallCircleFit& fit, double angle_deg);

/// Orientation of the crack of a failed spring: the crack runs in the tangent plane at `position`
/// (R, relative to the centre of mass, map frame), perpendicular to the spring's direction
/// `spring` (any length; its radial part is dropped). Returned as the angle from the local
/// direction toward the subsatellite point (along the great circle through it), counter-clockwise
/// seen from outside the body, folded into [0, 180) deg: an axial quantity, 0 for a crack pointing
/// at the subsatellite point (radial), 90 for a crack concentric about it. NaN where undefined:
/// at the subsatellite point or its antipode, or for a purely radial spring.
double crack_azimuth_deg(const Vec3& position, const Vec3& spring, const Vec3& subsatellite = subsatellite_direction);

/// The rose of crack azimuths and the concentricity of a set of crack elements.
struct CrackOrientations {
  static constexpr double bin_width_deg = 10;
  static constexpr std::size_t bins = 18;  ///< bin k holds azimuths within 5 deg of 10 k (bin 0: [175, 180) and [0, 5))
  std::array<std::int64_t, bins> rose{};   ///< crack elements per bin
  std::size_t elements = 0;                ///< elements with a defined azimuth
  /// Mean over the elements of |cos| of the angle between the crack and the local concentric
  /// direction, i.e. mean |sin(azimuth)|: 1 for cracks all concentric about the subsatellite
  /// point, 0 for all radial, 2/pi = 0.6366 for azimuths uniform on [0, 180). NaN without elements.
  double concentricity = std::numeric_limits<double>::quiet_NaN();
  double rose_peak_deg = std::numeric_limits<double>::quiet_NaN();  ///< centre of the fullest bin (ties: lowest); NaN without elements
  /// The rose in four sectors of 45 deg, a rose coarse enough to compare between ensembles of a
  /// few members: sector k holds azimuths within 22.5 deg of 45 k (sector 0, radial: [157.5, 180)
  /// and [0, 22.5); sector 2, concentric: [67.5, 112.5)); sectors 1 and 3 are the two obliques.
  static constexpr double sector_width_deg = 45;
  static constexpr std::size_t sectors = 4;
  /// Share of the elements in each sector, summing to 1; NaN without elements.
  std::array<double, sectors> sector_share{std::numeric_limits<double>::quiet_NaN(),
                                           std::numeric_limits<double>::quiet_NaN(),
                                           std::numeric_limits<double>::quiet_NaN(),
                                           std::numeric_limits<double>::quiet_NaN()};
};

/// Expected concentricity of azimuths uniform on [0, 180): E|sin a| = 2/pi.
inline constexpr double random_concentricity = 0.63661977236758134308;

/// The rose and concentricity of these azimuths (deg, [0, 180); NaN entries are skipped).
CrackOrientations crack_orientations(const std::vector<double>& azimuths_deg);

/// A long crack (a cluster of fracture_analysis.hpp) with the small circle fitted to it.
struct CrackArc {
  std::size_t cluster = 0;  ///< index into FractureSummary::clusters (longest first)
  double length = 0;        ///< the cluster's dual-lattice length, R
  double extent = 0;        ///< its great-circle extent, R
  SmallCircleFit fit;       ///< fitted to the midpoints of its failed springs
};

/// The crack geometry of a fracture set (FractureSummary::geometry).
struct CrackGeometry {
  /// Which clusters get a circle: extent at least min_arc_extent (R = radians on the unit sphere,
  /// independent of the lattice spacing), at least min_arc_springs failed springs, the
  /// max_arcs longest of those.
  static constexpr double min_arc_extent = 0.5;
  static constexpr std::size_t min_arc_springs = 6;
  static constexpr std::size_t max_arcs = 10;
  static constexpr double pole_bin_width_deg = 10;
  static constexpr std::size_t pole_bins = 9;  ///< 0..90 deg of pole_axis_from_subsatellite_deg

  std::vector<CrackArc> arcs;          ///< longest first
  CrackOrientations orientations;      ///< of every failed shell spring
  std::array<std::int64_t, pole_bins> pole_axis_histogram{};  ///< arcs per 10 deg of pole axis angle
  /// Median over the arcs of pole_axis_from_subsatellite_deg; NaN without arcs.
  double median_pole_axis_from_subsatellite_deg = std::numeric_limits<double>::quiet_NaN();
  /// Median over the arcs of radius_deg; NaN without arcs.
  double median_arc_radius_deg = std::numeric_limits<double>::quiet_NaN();
};

/// The arcs of `clusters` (given longest first, each by the unit-sphere directions of its failed
/// springs' midpoints, its length and extent in R) and the orientations of `azimuths_deg` (one
/// per failed spring, crack_azimuth_deg).
CrackGeometry crack_geometry(const std::vector<std::vector<Vec3>>& cluster_points,
                             const std::vector<double>& cluster_lengths, const std::vector<double>& cluster_extents,
                             const std::vector<double>& azimuths_deg,
                             const Vec3& subsatellite = subsatellite_direction);

/// The `crack_geometry` object of summary.json: units, the arc selection (min_extent R,
/// min_springs, max_arcs), the arcs (cluster index, springs, length and extent in R, pole as a unit
/// vector and as longitude/latitude, radius_deg, arc_deg, arc_length in R, rms_misfit_deg,
/// pole_from_subsatellite_deg, pole_axis_from_subsatellite_deg, iterations), the pole axis
/// histogram with its median, the rose (bin width, bin centres, counts, peak, elements) and the
/// concentricity with its random expectation 2/pi. NaN is written as null.
Json crack_geometry_json(const CrackGeometry& geometry);

}  // namespace tidalcrust
