#include "model/crust_field.hpp"

#include <fmt/format.h>
#include <xxhash.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <utility>

#include "base/errors.hpp"

namespace tidalcrust {
namespace {

constexpr double degrees_per_radian = 180.0 / std::numbers::pi;

bool is_blank(char ch) { return ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r'; }

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_blank(s.back())) s.remove_suffix(1);
  return s;
}

/// A finite number filling all of `text` (after trimming), or nothing.
std::optional<double> number_of(std::string_view text) {
  const std::string s(trimmed(text));
  if (s.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size() || errno == ERANGE || !std::isfinite(v)) return std::nullopt;
  return v;
}

/// The "name = number" items of `text`, separated by commas or blanks (blanks around '=' allowed),
/// in order; InputError naming the malformed item and showing `example`.
std::vector<std::pair<std::string, double>> assignments(std::string_view text, const std::string& where,
                                                        std::string_view example) {
  std::vector<std::pair<std::string, double>> out;
  std::size_t at = 0;
  const auto skip_separators = [&] {
    while (at < text.size() && (is_blank(text[at]) || text[at] == ',')) ++at;
  };
  const auto refuse = [&](std::string_view item, std::string_view why) {
    throw InputError(fmt::format("{}: '{}': {} (expected terms like \"{}\")", where, trimmed(item), why, example));
  };
  for (skip_separators(); at < text.size(); skip_separators()) {
    const std::size_t start = at;
    while (at < text.size() && (std::isalnum(static_cast<unsigned char>(text[at])) || text[at] == '_')) ++at;
    const std::string name(text.substr(start, at - start));
    while (at < text.size() && is_blank(text[at])) ++at;
    if (name.empty() || at >= text.size() || text[at] != '=') {
      std::size_t end = text.find_first_of(",;", start);
      refuse(text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start),
             "not a name = number");
    }
    ++at;
    while (at < text.size() && is_blank(text[at])) ++at;
    const std::size_t value_start = at;
    while (at < text.size() && !is_blank(text[at]) && text[at] != ',') ++at;
    const auto value = number_of(text.substr(value_start, at - value_start));
    if (!value) refuse(text.substr(start, at - start), "the value is not a finite number");
    out.emplace_back(name, *value);
  }
  return out;
}

/// P~_lm(cos theta) cos(m phi) and sin(m phi) of a unit direction, Schmidt semi-normalised, by the
/// standard recursions in x = cos theta and s = sin theta, and (x + i y)^m / rho^m for the azimuth:
/// no trigonometric function.
std::pair<double, double> harmonic_at(int l, int m, const Vec3& u) {
  const double x = u.z();
  const double rho = std::hypot(u.x(), u.y());
  const double s = rho;  // sin theta of a unit vector
  // P_mm = (2m - 1)!! s^m, then upward in l (no Condon-Shortley phase).
  double p_mm = 1;
  for (int k = 1; k <= m; ++k) p_mm *= (2 * k - 1) * s;
  double p_prev = 0, p = p_mm;
  for (int k = m + 1; k <= l; ++k) {
    const double next = ((2 * k - 1) * x * p - (k + m - 1) * p_prev) / (k - m);
    p_prev = p;
    p = next;
  }
  // sqrt((2 - delta_m0) (l - m)! / (l + m)!)
  double ratio = 1;
  for (int k = l - m + 1; k <= l + m; ++k) ratio /= k;
  const double norm = std::sqrt((m == 0 ? 1.0 : 2.0) * ratio);
  double c = 1, sn = 0;  // cos(m phi), sin(m phi)
  if (m > 0 && rho > 0) {
    const double cp = u.x() / rho, sp = u.y() / rho;
    for (int k = 0; k < m; ++k) {
      const double c2 = c * cp - sn * sp;
      sn = sn * cp + c * sp;
      c = c2;
    }
  } else if (m > 0) {
    c = 0;  // at a pole every m > 0 term vanishes (s^m = 0) whatever phi is
  }
  return {norm * p * c, norm * p * sn};
}

}  // namespace

Vec3 direction_at(double lon_deg, double lat_deg) {
  const double lon = lon_deg / degrees_per_radian, lat = lat_deg / degrees_per_radian;
  return {std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat)};
}

std::vector<Harmonic> parse_harmonics(std::string_view text, const std::string& where) {
  constexpr std::string_view example = "c10 = 0.5, s11 = -0.1";
  std::vector<Harmonic> out;
  for (const auto& [name, value] : assignments(text, where, example)) {
    const bool shape = name.size() == 3 && (name[0] == 'c' || name[0] == 's') && std::isdigit(static_cast<unsigned char>(name[1])) &&
                       std::isdigit(static_cast<unsigned char>(name[2]));
    const auto refuse = [&](std::string_view why) {
      throw InputError(fmt::format("{}: '{} = {}': {} (expected terms c<l><m> or s<l><m> = number, degree l = 1-{}, "
                                   "order m = 0-l, as \"{}\")",
                                   where, name, value, why, max_harmonic_degree, example));
    };
    if (!shape) refuse("not a term c<l><m> or s<l><m>");
    Harmonic h{name[1] - '0', name[2] - '0', name[0] == 's', value};
    if (h.degree < 1) refuse("degree 0 is the mean, set by the crust's own keys");
    if (h.order > h.degree) refuse("order above degree");
    if (h.sine && h.order == 0) refuse("s<l>0 is zero everywhere");
    for (const Harmonic& other : out)
      if (other.degree == h.degree && other.order == h.order && other.sine == h.sine) refuse("given twice");
    out.push_back(h);
  }
  return out;
}

std::vector<WeakLine> parse_weak_lines(std::string_view text, const std::string& where) {
  constexpr std::string_view example = "pole_lon = 0, pole_lat = 0, radius = 90, half_width = 4, factor = 0.5";
  std::vector<WeakLine> out;
  for (std::size_t at = 0; at <= text.size();) {
    const std::size_t end = std::min(text.find(';', at), text.size());
    const std::string_view one = text.substr(at, end - at);
    at = end + 1;
    if (trimmed(one).empty()) continue;
    const std::string line_where = fmt::format("{}: weak line {}", where, out.size() + 1);
    std::map<std::string, double> given;
    for (const auto& [name, value] : assignments(one, line_where, example)) {
      if (name != "pole_lon" && name != "pole_lat" && name != "radius" && name != "half_width" && name != "factor")
        throw InputError(fmt::format("{}: unknown field '{}' (known: pole_lon, pole_lat, radius, half_width, factor)",
                                     line_where, name));
      if (!given.emplace(name, value).second)
        throw InputError(fmt::format("{}: field '{}' given twice", line_where, name));
    }
    for (const char* needed : {"pole_lon", "pole_lat", "half_width", "factor"})
      if (!given.contains(needed))
        throw InputError(fmt::format("{}: field '{}' missing (as \"{}\")", line_where, needed, example));
    WeakLine line{given["pole_lon"], given["pole_lat"], given.contains("radius") ? given["radius"] : 90.0,
                  given["half_width"], given["factor"]};
    const auto check = [&](const char* name, double v, bool ok, const char* range) {
      if (!ok) throw InputError(fmt::format("{}: {} = {} must be {}", line_where, name, v, range));
    };
    check("pole_lat", line.pole_lat_deg, line.pole_lat_deg >= -90 && line.pole_lat_deg <= 90, "in [-90, 90] deg");
    check("pole_lon", line.pole_lon_deg, line.pole_lon_deg >= -360 && line.pole_lon_deg <= 360, "in [-360, 360] deg");
    check("radius", line.radius_deg, line.radius_deg > 0 && line.radius_deg < 180, "in (0, 180) deg (90: a great circle)");
    check("half_width", line.half_width_deg, line.half_width_deg > 0 && line.half_width_deg <= 90, "in (0, 90] deg");
    check("factor", line.factor, line.factor > 0 && line.factor < 1, "in (0, 1): a weak line lowers the strength");
    out.push_back(line);
  }
  return out;
}

double harmonic_sum(const std::vector<Harmonic>& terms, const Vec3& direction) {
  const Vec3 u = direction.normalized();
  double sum = 0;
  for (const Harmonic& h : terms) {
    const auto [c, s] = harmonic_at(h.degree, h.order, u);
    sum += h.coefficient * (h.sine ? s : c);
  }
  return sum;
}

bool WeakLine::contains(const Vec3& direction) const {
  const double cosine = std::clamp(direction.normalized().dot(direction_at(pole_lon_deg, pole_lat_deg)), -1.0, 1.0);
  return std::abs(std::acos(cosine) * degrees_per_radian - radius_deg) <= half_width_deg;
}

double CrustMap::interpolate(const std::vector<double>& values, const Vec3& direction) const {
  const Vec3 u = direction.normalized();
  double lon = std::atan2(u.y(), u.x()) * degrees_per_radian;
  if (lon < 0) lon += 360;
  const double lat = std::asin(std::clamp(u.z(), -1.0, 1.0)) * degrees_per_radian;
  const std::size_t nlon = lon_deg.size(), nlat = lat_deg.size();
  // Longitude: the cell [lon_i, lon_i+1], the last one wrapping to lon_0 + 360.
  std::size_t i = static_cast<std::size_t>(std::upper_bound(lon_deg.begin(), lon_deg.end(), lon) - lon_deg.begin());
  i = i == 0 ? nlon - 1 : i - 1;  // lon below the first: the wrapped cell from the last
  const std::size_t i1 = (i + 1) % nlon;
  double span = (i1 == 0 ? lon_deg[0] + 360 : lon_deg[i1]) - lon_deg[i];
  double from = lon - lon_deg[i];
  if (from < 0) from += 360;
  const double wx = nlon == 1 ? 0 : from / span;
  // Latitude: clamped to the table.
  std::size_t j = 0;
  double wy = 0;
  if (lat <= lat_deg.front()) {
    j = 0;
  } else if (lat >= lat_deg.back()) {
    j = nlat - 1;
  } else {
    j = static_cast<std::size_t>(std::upper_bound(lat_deg.begin(), lat_deg.end(), lat) - lat_deg.begin()) - 1;
    wy = (lat - lat_deg[j]) / (lat_deg[j + 1] - lat_deg[j]);
  }
  const std::size_t j1 = std::min(j + 1, nlat - 1);
  const auto at = [&](std::size_t row, std::size_t col) { return values[row * nlon + col]; };
  return (1 - wy) * ((1 - wx) * at(j, i) + wx * at(j, i1)) + wy * ((1 - wx) * at(j1, i) + wx * at(j1, i1));
}

CrustMap read_crust_map(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{}: cannot open crust.map_file: {}", name, std::strerror(errno)));
  static const std::array<std::string_view, 4> columns = {"lon", "lat", "thickness_factor", "strength_factor"};
  std::array<int, 4> column_of{-1, -1, -1, -1};
  std::map<std::pair<double, double>, std::pair<double, double>> rows;  // (lat, lon) -> factors
  std::string line;
  int number = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++number;
    const std::string_view text = trimmed(line);
    if (text.empty() || text.front() == '#') continue;
    std::vector<std::string_view> cells;
    for (std::size_t at = 0; at <= text.size();) {
      const std::size_t end = std::min(text.find(',', at), text.size());
      cells.push_back(trimmed(text.substr(at, end - at)));
      at = end + 1;
    }
    const auto where = [&] { return fmt::format("{}:{}", name, number); };
    if (!header) {
      for (std::size_t c = 0; c < cells.size(); ++c)
        for (std::size_t k = 0; k < columns.size(); ++k)
          if (cells[c] == columns[k]) column_of[k] = static_cast<int>(c);
      for (std::size_t k = 0; k < columns.size(); ++k)
        if (column_of[k] < 0)
          throw InputError(fmt::format("{}: the header lacks the column '{}' (expected lon,lat,thickness_factor,"
                                       "strength_factor)",
                                       where(), columns[k]));
      header = true;
      continue;
    }
    const auto last_column = static_cast<std::size_t>(*std::max_element(column_of.begin(), column_of.end()));
    if (cells.size() <= last_column)
      throw InputError(fmt::format("{}: {} cells, fewer than the header's columns", where(), cells.size()));
    std::array<double, 4> v{};
    for (std::size_t k = 0; k < columns.size(); ++k) {
      const auto value = number_of(cells[static_cast<std::size_t>(column_of[k])]);
      if (!value)
        throw InputError(fmt::format("{}: {} '{}' is not a finite number", where(), columns[k],
                                     cells[static_cast<std::size_t>(column_of[k])]));
      v[k] = *value;
    }
    double lon = v[0];
    if (!(lon >= -180 && lon <= 360)) throw InputError(fmt::format("{}: lon = {} must be in [-180, 360]", where(), lon));
    if (!(v[1] >= -90 && v[1] <= 90)) throw InputError(fmt::format("{}: lat = {} must be in [-90, 90]", where(), v[1]));
    for (std::size_t k = 2; k < 4; ++k)
      if (!(v[k] > 0)) throw InputError(fmt::format("{}: {} = {} must be > 0", where(), columns[k], v[k]));
    if (lon < 0) lon += 360;
    if (lon >= 360) lon -= 360;
    if (!rows.emplace(std::pair{v[1], lon}, std::pair{v[2], v[3]}).second)
      throw InputError(fmt::format("{}: the point lon = {}, lat = {} is given twice", where(), v[0], v[1]));
  }
  if (in.bad()) throw InputError(fmt::format("{}: cannot read crust.map_file: {}", name, std::strerror(errno)));
  if (!header) throw InputError(fmt::format("{}: no header line lon,lat,thickness_factor,strength_factor", name));
  CrustMap map;
  for (const auto& [point, unused] : rows) {
    if (map.lat_deg.empty() || map.lat_deg.back() != point.first) map.lat_deg.push_back(point.first);
    if (std::find(map.lon_deg.begin(), map.lon_deg.end(), point.second) == map.lon_deg.end())
      map.lon_deg.push_back(point.second);
  }
  std::sort(map.lon_deg.begin(), map.lon_deg.end());
  if (map.lat_deg.size() < 2 || map.lon_deg.size() < 2 || rows.size() != map.lat_deg.size() * map.lon_deg.size())
    throw InputError(fmt::format("{}: {} points, not a regular grid of at least 2 longitudes x 2 latitudes ({} "
                                 "longitudes x {} latitudes would need {})",
                                 name, rows.size(), map.lon_deg.size(), map.lat_deg.size(),
                                 map.lon_deg.size() * map.lat_deg.size()));
  for (const double lat : map.lat_deg)
    for (const double lon : map.lon_deg) {
      const auto& [t, s] = rows.at({lat, lon});
      map.thickness.push_back(t);
      map.strength.push_back(s);
    }
  return map;
}

std::string crust_map_digest(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream bytes;
  if (in) bytes << in.rdbuf();
  if (!in || in.bad())
    throw InputError(fmt::format("{}: cannot read crust.map_file: {}", file.string(), std::strerror(errno)));
  const std::string text = bytes.str();
  return fmt::format("{:016x}", XXH3_64bits(text.data(), text.size()));
}

double CrustField::thickness_factor(const Vec3& direction) const {
  double t = 1 + harmonic_sum(thickness_harmonics, direction);
  if (has_map) t *= map.thickness_at(direction);
  return t;
}

double CrustField::strength_factor(const Vec3& direction) const {
  double f = 1 + harmonic_sum(strength_harmonics, direction);
  if (has_map) f *= map.strength_at(direction);
  double line = 1;
  for (const WeakLine& w : weak_lines)
    if (w.contains(direction)) line = std::min(line, w.factor);
  return f * line;
}

CrustField make_crust_field(const CrustConfig& crust, const std::string& where) {
  CrustField field;
  if (crust.thickness_harmonics)
    field.thickness_harmonics = parse_harmonics(*crust.thickness_harmonics, where + ".thickness_harmonics");
  if (crust.strength_harmonics)
    field.strength_harmonics = parse_harmonics(*crust.strength_harmonics, where + ".strength_harmonics");
  if (crust.weak_lines) field.weak_lines = parse_weak_lines(*crust.weak_lines, where + ".weak_lines");
  if (crust.map_file) {
    const std::string digest = crust_map_digest(*crust.map_file);
    if (crust.map_digest && *crust.map_digest != digest)
      throw InputError(fmt::format("{}: crust.map_file has changed since the workflow was read (digest {}, recorded {}); "
                                   "run the workflow again",
                                   *crust.map_file, digest, *crust.map_digest));
    field.map = read_crust_map(*crust.map_file);
    field.has_map = true;
  }
  return field;
}

}  // namespace tidalcrust
