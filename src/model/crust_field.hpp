#pragma once
// A crust that varies over the surface (issue 25, docs/crust.md): the crust's thickness and its
// strength (failure strain) as factors of the configured mean h_S and eps_S, each a function of
// the direction from the body's centre, in the body frame of the maps (longitude from +x in the
// xy plane, latitude toward +z; the paper's orbit has its subsatellite point at lon +90, lat 0).
// Given by the [crust] keys (model/config.hpp): low-degree real spherical harmonics, a lat/lon
// table from a CSV file, and pre-existing weak lines (great or small circles of lowered strength).
// The one home of their grammar and their evaluation; the builder (bodies/build_body.cpp) samples
// them once, and the body keeps what it sampled.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/vec3.hpp"

namespace tidalcrust {

/// One term of a real spherical-harmonic expansion, Schmidt semi-normalised and without the
/// Condon-Shortley phase (geomagnetism's convention): Y = P~_lm(cos theta) cos(m phi) (cosine, "c")
/// or sin(m phi) ("s"), P~_lm = sqrt((2 - delta_m0) (l - m)! / (l + m)!) P_lm, so |Y| <= 1 and the
/// degree-1 terms are the Cartesian components of the direction: c10 = z, c11 = x, s11 = y.
struct Harmonic {
  int degree = 1;      ///< l, 1 .. max_harmonic_degree (degree 0 is the mean: h_S, eps_S)
  int order = 0;       ///< m, 0 .. l
  bool sine = false;   ///< sin(m phi) instead of cos(m phi); m >= 1
  double coefficient = 0;
  bool operator==(const Harmonic&) const = default;
};
inline constexpr int max_harmonic_degree = 9;

/// A pre-existing weak line: the small circle at angular radius `radius_deg` about the pole
/// (lon, lat) (90: a great circle), of half-width `half_width_deg`; within it the strength is
/// `factor` times the rest's.
struct WeakLine {
  double pole_lon_deg = 0;
  double pole_lat_deg = 90;
  double radius_deg = 90;
  double half_width_deg = 0;
  double factor = 1;
  bool operator==(const WeakLine&) const = default;
  /// True when `direction` (any length > 0) lies within the half-width of the circle.
  bool contains(const Vec3& direction) const;
};

/// A regular lat/lon table of thickness and strength factors (crust.map_file): every longitude of
/// `lon_deg` (ascending, in [0, 360)) with every latitude of `lat_deg` (ascending, in [-90, 90]);
/// values [lat][lon] row-major. Bilinear in (lon, lat), periodic in longitude, constant beyond the
/// first and last latitude.
struct CrustMap {
  std::vector<double> lon_deg;
  std::vector<double> lat_deg;
  std::vector<double> thickness;
  std::vector<double> strength;
  double thickness_at(const Vec3& direction) const { return interpolate(thickness, direction); }
  double strength_at(const Vec3& direction) const { return interpolate(strength, direction); }

 private:
  double interpolate(const std::vector<double>& values, const Vec3& direction) const;
};

/// The harmonics of `text` ("c10 = 0.5, s11 = -0.1": terms c<l><m> or s<l><m> = number, separated
/// by commas or blanks; "" gives none). `where` ("workflow.toml: crust.thickness_harmonics") starts
/// every error: an InputError (exit 2) naming the malformed term.
std::vector<Harmonic> parse_harmonics(std::string_view text, const std::string& where);
/// The weak lines of `text`: lines separated by ';', each "pole_lon = 0, pole_lat = 0, radius = 90,
/// half_width = 4, factor = 0.5" (radius optional, default 90; degrees; 0 < half_width <= 90,
/// 0 < radius < 180, 0 < factor < 1). InputError as parse_harmonics.
std::vector<WeakLine> parse_weak_lines(std::string_view text, const std::string& where);
/// sum_k coefficient_k Y_k(direction): the expansion at a direction (any length > 0).
double harmonic_sum(const std::vector<Harmonic>& terms, const Vec3& direction);

/// Reads crust.map_file: CSV with the header lon,lat,thickness_factor,strength_factor (any order;
/// '#' lines and blank lines skipped), a regular grid (CrustMap), factors finite and > 0. InputError
/// naming the file and the line for an unreadable file or a bad row.
CrustMap read_crust_map(const std::filesystem::path& file);
/// The digest that crust.map_digest records of a map file: XXH3-64 of its bytes, 16 hex digits.
/// InputError naming the file when it cannot be read.
std::string crust_map_digest(const std::filesystem::path& file);

/// The crust's variation, parsed from the [crust] keys: thickness factor t(x) = (1 + sum of the
/// thickness harmonics) * map thickness; strength factor f(x) = (1 + sum of the strength harmonics)
/// * map strength * the smallest factor of the weak lines containing x (1 outside every line).
struct CrustField {
  std::vector<Harmonic> thickness_harmonics;
  std::vector<Harmonic> strength_harmonics;
  std::vector<WeakLine> weak_lines;
  bool has_map = false;
  CrustMap map;

  /// True when neither factor varies (no key given): the body is built as before the keys.
  bool uniform() const {
    return thickness_harmonics.empty() && strength_harmonics.empty() && weak_lines.empty() && !has_map;
  }
  bool thickness_varies() const { return !thickness_harmonics.empty() || has_map; }
  double thickness_factor(const Vec3& direction) const;
  double strength_factor(const Vec3& direction) const;
};

/// The [crust] table of a workflow (docs/crust.md): every key optional; none given, the crust is
/// uniform and the body is built bit for bit as before the table.
struct CrustConfig {
  std::optional<std::string> thickness_harmonics;  ///< "c10 = 0.5, ...": t(x) = 1 + sum
  std::optional<std::string> strength_harmonics;   ///< the same for the failure strain's factor
  std::optional<std::string> weak_lines;           ///< "pole_lon = .., pole_lat = .., half_width = .., factor = ..; ..."
  std::optional<std::string> map_file;             ///< CSV lon,lat,thickness_factor,strength_factor
  /// crust_map_digest of map_file, filled when the workflow is read (resolve_crust): the fingerprint
  /// of the build holds the file's content, not its name.
  std::optional<std::string> map_digest;
  bool given() const { return thickness_harmonics || strength_harmonics || weak_lines || map_file; }
};

/// The field the [crust] keys describe; `where` starts every error ("workflow.toml: crust"). Reads
/// crust.map_file when given and refuses it (InputError, exit 2) when its digest is not map_digest
/// (changed since the workflow was read).
CrustField make_crust_field(const CrustConfig& crust, const std::string& where);

/// The unit vector at (lon, lat) in degrees, in the maps' body frame.
Vec3 direction_at(double lon_deg, double lat_deg);

}  // namespace tidalcrust
