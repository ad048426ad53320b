#include "analysis/crack_geometry.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>  // cross()

#include <algorithm>
#include <cmath>
#include <numbers>

#include "base/invariant.hpp"
#include "physics/orbital_frame.hpp"

namespace tidalcrust {

namespace {
constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double degrees = 180.0 / std::numbers::pi;

/// Two unit vectors completing `p` (unit) to a right-handed orthonormal basis (e1, e2, p),
/// chosen from the coordinate axis least aligned with p.
std::pair<Vec3, Vec3> tangent_basis(const Vec3& p) {
  const Vec3 a = std::abs(p.x()) <= std::abs(p.y()) && std::abs(p.x()) <= std::abs(p.z()) ? Vec3::UnitX()
                 : std::abs(p.y()) <= std::abs(p.z())                                      ? Vec3::UnitY()
                                                                                           : Vec3::UnitZ();
  const Vec3 e1 = p.cross(a).normalized();
  return {e1, p.cross(e1)};
}

double angle_between_unit(const Vec3& a, const Vec3& b) {
  // atan2 of |a x b| and a.b: accurate near 0 and pi, where acos is not.
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

double sum_of_squares(const std::vector<Vec3>& x, const Vec3& pole, double radius) {
  double sum = 0;
  for (const Vec3& xi : x) {
    const double r = angle_between_unit(pole, xi) - radius;
    sum += r * r;
  }
  return sum;
}

double median(std::vector<double> v) {
  if (v.empty()) return nan;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
}  // namespace

bool SmallCircleFit::finite() const {
  return pole.allFinite() && std::isfinite(pole_longitude_deg) && std::isfinite(pole_latitude_deg) &&
         std::isfinite(radius_deg) && std::isfinite(arc_deg) && std::isfinite(arc_length) &&
         std::isfinite(rms_misfit_deg) && std::isfinite(pole_from_subsatellite_deg) &&
         std::isfinite(pole_axis_from_subsatellite_deg);
}

SmallCircleFit fit_small_circle(const std::vector<Vec3>& points, const Vec3& subsatellite) {
  TIDALCRUST_ASSERT(points.size() >= 3, "a small circle is fitted to at least 3 points");
  std::vector<Vec3> x;
  x.reserve(points.size());
  for (const Vec3& p : points) {
    TIDALCRUST_ASSERT(p.norm() > 0, "small-circle points are nonzero vectors");
    x.push_back(p.normalized());
  }
  const double n = static_cast<double>(x.size());
  SmallCircleFit fit;
  fit.points = x.size();

  // Algebraic start: the plane n.x = c nearest the points in the least-squares sense, i.e. the
  // eigenvector of the smallest eigenvalue of the points' scatter matrix about their mean.
  Vec3 mean = Vec3::Zero();
  for (const Vec3& xi : x) mean += xi;
  mean /= n;
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Vec3& xi : x) scatter += (xi - mean) * (xi - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter);
  Vec3 pole = eigen.eigenvectors().col(0).normalized();
  if (pole.dot(mean) < 0) pole = -pole;
  double radius = std::acos(std::clamp(pole.dot(mean), -1.0, 1.0));
  if (!pole.allFinite()) return fit;

  // Gauss-Newton on (pole, radius): residual_i = angle(pole, x_i) - radius; the pole moves in its
  // tangent plane, p -> normalize(p + d1 e1 + d2 e2), and d angle_i / d dk = -(x_i . e_k) / sin angle_i.
  double cost = sum_of_squares(x, pole, radius);
  for (int iteration = 0; iteration < max_fit_iterations; ++iteration) {
    const auto [e1, e2] = tangent_basis(pole);
    Eigen::Matrix3d jtj = Eigen::Matrix3d::Zero();
    Eigen::Vector3d jtr = Eigen::Vector3d::Zero();
    for (const Vec3& xi : x) {
      const double angle = angle_between_unit(pole, xi);
      const double s = std::sin(angle);
      const Eigen::Vector3d row =
          s > 1e-12 ? Eigen::Vector3d(-xi.dot(e1) / s, -xi.dot(e2) / s, -1.0) : Eigen::Vector3d(0, 0, -1.0);
      jtj += row * row.transpose();
      jtr += row * (angle - radius);
    }
    Eigen::Vector3d step = jtj.ldlt().solve(-jtr);
    if (!step.allFinite()) break;
    fit.iterations = iteration + 1;
    // Halve a step that would raise the sum of squares (at most 30 times; then stop there).
    bool improved = false;
    for (int halving = 0; halving < 30; ++halving) {
      const Vec3 trial_pole = (pole + step[0] * e1 + step[1] * e2).normalized();
      const double trial_radius = radius + step[2];
      const double trial_cost = sum_of_squares(x, trial_pole, trial_radius);
      if (trial_cost <= cost) {
        pole = trial_pole;
        radius = trial_radius;
        cost = trial_cost;
        improved = true;
        break;
      }
      step *= 0.5;
    }
    if (!improved || step.norm() < fit_step_tolerance) break;
  }

  // The same circle about the antipode has radius pi - r: report the centre of the smaller cap.
  if (radius > std::numbers::pi / 2) {
    pole = -pole;
    radius = std::numbers::pi - radius;
  } else if (radius < 0) {  // not reached from the algebraic start, but a negative radius is the same circle
    radius = -radius;
  }
  fit.pole = pole;
  fit.pole_longitude_deg = longitude_deg(pole);
  fit.pole_latitude_deg = latitude_deg(pole);
  fit.radius_deg = radius * degrees;
  fit.rms_misfit_deg = std::sqrt(sum_of_squares(x, pole, radius) / n) * degrees;
  fit.pole_from_subsatellite_deg = angle_between_unit(pole, subsatellite) * degrees;
  fit.pole_axis_from_subsatellite_deg = std::min(fit.pole_from_subsatellite_deg, 180 - fit.pole_from_subsatellite_deg);

  // Arc covered: the azimuths of the points about the pole, 2 pi minus their largest gap.
  const auto [e1, e2] = tangent_basis(pole);
  std::vector<double> azimuth;
  azimuth.reserve(x.size());
  for (const Vec3& xi : x) azimuth.push_back(std::atan2(xi.dot(e2), xi.dot(e1)));
  std::sort(azimuth.begin(), azimuth.end());
  double largest_gap = azimuth.front() + 2 * std::numbers::pi - azimuth.back();
  for (std::size_t i = 1; i < azimuth.size(); ++i) largest_gap = std::max(largest_gap, azimuth[i] - azimuth[i - 1]);
  std::size_t first = 0;  // the point after the largest gap begins the arc
  for (std::size_t i = 1; i < azimuth.size(); ++i)
    if (azimuth[i] - azimuth[i - 1] == largest_gap) {
      first = i;
      break;
    }
  const double arc = 2 * std::numbers::pi - largest_gap;
  fit.arc_deg = arc * degrees;
  fit.arc_length = arc * std::sin(radius);
  fit.arc_start = std::cos(radius) * pole + std::sin(radius) * (std::cos(azimuth[first]) * e1 + std::sin(azimuth[first]) * e2);
  return fit;
}

Vec3 point_on_circle(const SmallCircleFit& fit, double angle_deg) {
  // Rodrigues' rotation of arc_start about the pole.
  const double a = angle_deg / degrees;
  const Vec3& k = fit.pole;
  const Vec3& v = fit.arc_start;
  return std::cos(a) * v + std::sin(a) * k.cross(v) + (1 - std::cos(a)) * k.dot(v) * k;
}

double crack_azimuth_deg(const Vec3& position, const Vec3& spring, const Vec3& subsatellite) {
  const double norm = position.norm();
  if (!(norm > 0)) return nan;
  const Vec3 up = position / norm;
  const Vec3 toward = subsatellite - subsatellite.dot(up) * up;  // tangent, toward the subsatellite point
  const Vec3 along = spring - spring.dot(up) * up;                                   // the spring, tangent
  if (toward.norm() < 1e-12 || along.norm() < 1e-12 * spring.norm() || !(spring.norm() > 0)) return nan;
  const Vec3 t = toward.normalized();
  const Vec3 crack = up.cross(along.normalized());  // tangent, perpendicular to the spring
  double a = std::atan2(crack.dot(up.cross(t)), crack.dot(t)) * degrees;  // (-180, 180]
  if (a < 0) a += 180;
  if (a >= 180) a -= 180;
  return a;
}

CrackOrientations crack_orientations(const std::vector<double>& azimuths_deg) {
  CrackOrientations o;
  double sum = 0;
  std::array<std::int64_t, CrackOrientations::sectors> in_sector{};
  for (const double a : azimuths_deg) {
    if (!std::isfinite(a)) continue;
    ++o.elements;
    sum += std::abs(std::sin(a / degrees));
    // Bins centred on 0, 10, ..., 170 deg; [175, 180) joins bin 0 (the same axis as [0, 5)); so
    // for the sectors centred on 0, 45, 90, 135 deg.
    const auto bin = static_cast<std::size_t>(std::floor((a + 0.5 * o.bin_width_deg) / o.bin_width_deg)) % o.bins;
    ++o.rose[bin];
    ++in_sector[static_cast<std::size_t>(std::floor((a + 0.5 * o.sector_width_deg) / o.sector_width_deg)) % o.sectors];
  }
  if (o.elements > 0) {
    o.concentricity = sum / static_cast<double>(o.elements);
    for (std::size_t k = 0; k < o.sectors; ++k)
      o.sector_share[k] = static_cast<double>(in_sector[k]) / static_cast<double>(o.elements);
    const auto peak = std::max_element(o.rose.begin(), o.rose.end());  // the first of equal maxima
    o.rose_peak_deg = static_cast<double>(peak - o.rose.begin()) * o.bin_width_deg;
  }
  return o;
}

CrackGeometry crack_geometry(const std::vector<std::vector<Vec3>>& cluster_points,
                             const std::vector<double>& cluster_lengths, const std::vector<double>& cluster_extents,
                             const std::vector<double>& azimuths_deg, const Vec3& subsatellite) {
  TIDALCRUST_ASSERT(cluster_lengths.size() == cluster_points.size() && cluster_extents.size() == cluster_points.size(),
                    "one length and one extent per cluster");
  CrackGeometry g;
  g.orientations = crack_orientations(azimuths_deg);
  std::vector<double> pole_axes, radii;
  for (std::size_t c = 0; c < cluster_points.size() && g.arcs.size() < g.max_arcs; ++c) {
    if (!(cluster_extents[c] >= g.min_arc_extent) || cluster_points[c].size() < g.min_arc_springs) continue;
    CrackArc arc{c, cluster_lengths[c], cluster_extents[c], fit_small_circle(cluster_points[c], subsatellite)};
    if (!arc.fit.finite()) continue;
    pole_axes.push_back(arc.fit.pole_axis_from_subsatellite_deg);
    radii.push_back(arc.fit.radius_deg);
    const auto bin = std::min(g.pole_bins - 1,
                              static_cast<std::size_t>(arc.fit.pole_axis_from_subsatellite_deg / g.pole_bin_width_deg));
    ++g.pole_axis_histogram[bin];
    g.arcs.push_back(arc);
  }
  g.median_pole_axis_from_subsatellite_deg = median(pole_axes);
  g.median_arc_radius_deg = median(radii);
  return g;
}

Json crack_geometry_json(const CrackGeometry& g) {
  Json arcs = Json::array();
  for (const CrackArc& a : g.arcs)
    arcs.push_back({{"cluster", a.cluster},
                    {"springs", a.fit.points},
                    {"length", a.length},
                    {"extent", a.extent},
                    {"pole", {a.fit.pole.x(), a.fit.pole.y(), a.fit.pole.z()}},
                    {"pole_longitude_deg", a.fit.pole_longitude_deg},
                    {"pole_latitude_deg", a.fit.pole_latitude_deg},
                    {"radius_deg", a.fit.radius_deg},
                    {"arc_deg", a.fit.arc_deg},
                    {"arc_length", a.fit.arc_length},
                    {"rms_misfit_deg", a.fit.rms_misfit_deg},
                    {"pole_from_subsatellite_deg", a.fit.pole_from_subsatellite_deg},
                    {"pole_axis_from_subsatellite_deg", a.fit.pole_axis_from_subsatellite_deg},
                    {"iterations", a.fit.iterations}});
  Json centres = Json::array();
  for (std::size_t k = 0; k < CrackOrientations::bins; ++k)
    centres.push_back(static_cast<double>(k) * CrackOrientations::bin_width_deg);
  const CrackOrientations& o = g.orientations;
  const auto number = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
  Json sector_centres = Json::array(), sector_share = Json::array();
  for (std::size_t k = 0; k < CrackOrientations::sectors; ++k) {
    sector_centres.push_back(static_cast<double>(k) * CrackOrientations::sector_width_deg);
    sector_share.push_back(number(o.sector_share[k]));
  }
  return {{"units", "angles in degrees, lengths in R; orbital frame: subsatellite point at longitude 90, latitude 0; "
                    "crack azimuths from the local direction toward the subsatellite point (docs/crack-geometry.md)"},
          {"arc_selection",
           {{"min_extent", CrackGeometry::min_arc_extent},
            {"min_springs", CrackGeometry::min_arc_springs},
            {"max_arcs", CrackGeometry::max_arcs}}},
          {"arcs", arcs},
          {"pole_axis_from_subsatellite",
           {{"bin_width_deg", CrackGeometry::pole_bin_width_deg},
            {"histogram", g.pole_axis_histogram},
            {"median_deg", number(g.median_pole_axis_from_subsatellite_deg)}}},
          {"median_arc_radius_deg", number(g.median_arc_radius_deg)},
          {"rose",
           {{"bin_width_deg", CrackOrientations::bin_width_deg},
            {"bin_centres_deg", centres},
            {"histogram", o.rose},
            {"peak_deg", number(o.rose_peak_deg)},
            {"elements", o.elements},
            {"sector_width_deg", CrackOrientations::sector_width_deg},
            {"sector_centres_deg", sector_centres},
            {"sector_share", sector_share}}},
          {"concentricity", number(o.concentricity)},
          {"concentricity_random", random_concentricity}};
}

}  // namespace tidalcrust
