#include "analysis/crust_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "base/vec3.hpp"
#include "model/center_of_mass.hpp"
#include "physics/orbital_frame.hpp"

namespace tidalcrust {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
/// Factors this close to 1 are 1: the mean node mass is a sum divided by a count.
constexpr double unit_tolerance = 1e-9;

bool is_shell_spring(const Body& body, std::size_t s) {
  return body.spring_kind[s] == static_cast<std::uint8_t>(SpringKind::shell);
}

double share(std::size_t part, std::size_t whole) {
  return whole > 0 ? static_cast<double>(part) / static_cast<double>(whole) : nan;
}

Json number_or_null(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

}  // namespace

std::vector<double> shell_thickness_factors(const Body& body) {
  double sum = 0;
  std::size_t nodes = 0;
  std::optional<double> common;  // the one shell node mass of a uniform crust
  bool uniform = true;
  for (std::size_t i = 0; i < body.particle_count(); ++i)
    if (body.species[i] == static_cast<std::uint8_t>(Species::shell)) {
      sum += body.mass[i], ++nodes;
      if (!common) common = body.mass[i];
      uniform = uniform && body.mass[i] == *common;
    }
  std::vector<double> t(body.particle_count(), 0.0);
  if (nodes == 0) return t;
  // A uniform crust's factors are exactly 1 (sum / count need not give its node mass back).
  const double mean = uniform ? *common : sum / static_cast<double>(nodes);
  for (std::size_t i = 0; i < body.particle_count(); ++i)
    if (body.species[i] == static_cast<std::uint8_t>(Species::shell)) t[i] = body.mass[i] / mean;
  return t;
}

CrustStatistics crust_statistics(const Body& body, const FractureSummary& fractures) {
  CrustStatistics out;
  const std::vector<double> t = shell_thickness_factors(body);
  bool first = true;
  for (std::size_t i = 0; i < body.particle_count(); ++i)
    if (body.species[i] == static_cast<std::uint8_t>(Species::shell)) {
      out.thickness_factor_min = first ? t[i] : std::min(out.thickness_factor_min, t[i]);
      out.thickness_factor_max = first ? t[i] : std::max(out.thickness_factor_max, t[i]);
      first = false;
    }
  const auto spring_thickness = [&](std::size_t s) {
    return 0.5 * (t[static_cast<std::size_t>(body.springs[s][0])] + t[static_cast<std::size_t>(body.springs[s][1])]);
  };
  const auto weak = [&](std::size_t s) { return body.failure_strain_factor(s) < 1 - unit_tolerance; };
  const auto thin = [&](std::size_t s) { return spring_thickness(s) < 1 - unit_tolerance; };
  std::size_t shell = 0;
  first = true;
  for (std::size_t s = 0; s < body.spring_count(); ++s) {
    if (!is_shell_spring(body, s)) continue;
    ++shell;
    const double f = body.failure_strain_factor(s);
    out.strength_factor_min = first ? f : std::min(out.strength_factor_min, f);
    out.strength_factor_max = first ? f : std::max(out.strength_factor_max, f);
    first = false;
    out.weak.springs += weak(s);
    out.thin.springs += thin(s);
  }
  for (const FailedShellSpring& f : fractures.failed) {
    out.weak.failures += weak(static_cast<std::size_t>(f.spring));
    out.thin.failures += thin(static_cast<std::size_t>(f.spring));
  }
  for (CrustPartShares* part : {&out.weak, &out.thin}) {
    part->spring_share = share(part->springs, shell);
    part->failure_share = share(part->failures, fractures.failed.size());
    part->capture_ratio = part->springs > 0 ? part->failure_share / part->spring_share : nan;
  }
  const auto differs = [](double v) { return std::abs(v - 1) > unit_tolerance; };
  out.varies = differs(out.thickness_factor_min) || differs(out.thickness_factor_max) ||
               differs(out.strength_factor_min) || differs(out.strength_factor_max);
  return out;
}

Json crust_statistics_json(const CrustStatistics& c) {
  const auto part = [](const CrustPartShares& p) {
    return Json{{"springs", p.springs},
                {"failures", p.failures},
                {"spring_share", number_or_null(p.spring_share)},
                {"failure_share", number_or_null(p.failure_share)},
                {"capture_ratio", number_or_null(p.capture_ratio)}};
  };
  return {{"varies", c.varies},
          {"thickness_factor_min", c.thickness_factor_min},
          {"thickness_factor_max", c.thickness_factor_max},
          {"strength_factor_min", c.strength_factor_min},
          {"strength_factor_max", c.strength_factor_max},
          {"weak", part(c.weak)},
          {"thin", part(c.thin)},
          {"note", "weak: shell springs of strength factor < 1 (within a weak line's half-width); thin: shell springs "
                   "whose nodes' mean thickness factor is < 1; capture_ratio = failure_share / spring_share "
                   "(docs/crust.md)"}};
}

Json crust_field_json(const Body& body, const State& state) {
  const Vec3 center = body_center_of_mass(body, state);
  const auto at = [&](std::size_t i) { return Vec3(vec3_at(state.position, i) - center); };
  const auto rounded = [](double v) { return std::round(v * 1e4) / 1e4; };
  const std::vector<double> t = shell_thickness_factors(body);
  Json thickness = {{"lon", Json::array()}, {"lat", Json::array()}, {"factor", Json::array()}};
  Json strength = thickness;
  const auto add = [&](Json& list, const Vec3& p, double factor) {
    list["lon"].push_back(rounded(longitude_deg(p)));
    list["lat"].push_back(rounded(latitude_deg(p)));
    list["factor"].push_back(factor);
  };
  const bool thickness_varies = std::any_of(t.begin(), t.end(), [](double v) { return v != 0 && std::abs(v - 1) > unit_tolerance; });
  bool strength_varies = false;
  for (std::size_t s = 0; s < body.spring_count(); ++s)
    strength_varies = strength_varies || (is_shell_spring(body, s) && std::abs(body.failure_strain_factor(s) - 1) > unit_tolerance);
  if (thickness_varies)
    for (std::size_t i = 0; i < body.particle_count(); ++i)
      if (body.species[i] == static_cast<std::uint8_t>(Species::shell)) add(thickness, at(i), t[i]);
  if (strength_varies)
    for (std::size_t s = 0; s < body.spring_count(); ++s)
      if (is_shell_spring(body, s))
        add(strength, 0.5 * (at(static_cast<std::size_t>(body.springs[s][0])) + at(static_cast<std::size_t>(body.springs[s][1]))),
            body.failure_strain_factor(s));
  return {{"thickness", thickness}, {"strength", strength}};
}

}  // namespace tidalcrust
