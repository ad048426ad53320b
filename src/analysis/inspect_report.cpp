#include "analysis/inspect_report.hpp"

#include "analysis/fracture_analysis.hpp"
#include "physics/spin_frame.hpp"
#include "analysis/si_output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <numeric>

#include <xxhash.h>

#include "model/config.hpp"
#include "forces/tree_gravity.hpp"
#include "physics/conservation.hpp"
#include "model/derived_quantities.hpp"
#include "integrate/stability_bound.hpp"
#include "io/json.hpp"
#include "io/state_hash.hpp"
#include "io/checkpoint_file.hpp"

namespace tidalcrust {

namespace {

constexpr const char* spring_constant_unit = "G M^2/R^3";
constexpr const char* pure_number = "1";  ///< the unit of counts and ratios (shown bare in the table)

std::vector<double> as_vector(const std::array<double, 3>& a) { return {a.begin(), a.end()}; }

ReportSection counts_section(const Checkpoint& c) {
  const Body& b = c.body;
  const std::int64_t failed =
      std::accumulate(c.state.springs.failed.begin(), c.state.springs.failed.end(), std::int64_t{0});
  ReportSection s{"counts", {}};
  s.add("interior", b.count_species(Species::interior), "1")
      .add("shell", b.count_species(Species::shell), "1")
      .add("springs_interior", b.count_springs(SpringKind::interior), "1")
      .add("springs_shell", b.count_springs(SpringKind::shell), "1")
      .add("springs_cross", b.count_springs(SpringKind::cross), "1")
      .add("hinges", b.hinge_count(), "1")
      .add("faces", b.faces.size(), "1")
      .add("failed", failed, "1");
  return s;
}

ReportSection derived_section(const Checkpoint& c, const std::string& file) {
  const Config config = parse_config(c.config_toml, file + ":/parameters/config");
  const DerivedQuantities q = derive_quantities(c.body, c.state, config.interior.radius);
  ReportSection s{"derived", {}};
  // Units as documented in model/derived_quantities.hpp (e_g = G M^2/R^4).
  s.add("E_I", q.E_I, "e_g").add("L_I", q.L_I, "R").add("k_I", q.k_I, spring_constant_unit);
  s.add("L_S", q.L_S, "R").add("k_S", q.k_S, spring_constant_unit).add("M_S", q.M_S, "M");
  s.add("L_C", q.L_C, "R").add("k_C", q.k_C, spring_constant_unit);
  s.add("V_IP", q.V_IP, "sqrt(GM/R)").add("V_SP", q.V_SP, "sqrt(GM/R)").add("V_Co", q.V_Co, "sqrt(GM/R)");
  s.add("h_S", q.h_S, "R").add("E_2D", q.E_2D, "e_g R").add("D_F", q.D_F, "e_g R^3").add("D_F_eq23", q.D_F_eq23, "e_g R^3").add("dt_max", q.dt_max, "t_grav");
  const StabilityBound bound = stability_bound(c.body, c.state);  // springs, hinges, node masses
  s.add("dt_safe", bound.safe_dt, "t_grav").add("dt_unstable", bound.unstable_dt, "t_grav");
  return s;
}

/// How the stage computed self-gravity (a tree gives other bits than the direct sum).
ReportSection gravity_section(const Checkpoint& c, const std::string& file) {
  const Config config = parse_config(c.config_toml, file + ":/parameters/config");
  ReportSection s{"gravity", {}};
  s.add("method", std::string(choice_name(config.gravity.method)));
  if (config.gravity.method == GravityMethod::tree)
    s.add("force_error", config.gravity.force_error, "1")
        .add("opening_angle", opening_angle_for(config.gravity.force_error), "1");
  return s;
}

ReportSection conservation_section(const Checkpoint& c) {
  const Conservation totals = measure_conservation(c.body, c.state);
  ReportSection s{"conservation", {}};
  s.add("momentum", as_vector(totals.momentum), "M sqrt(GM/R)")
      .add("angular_momentum", as_vector(totals.angular_momentum), "M R sqrt(GM/R)")
      .add("kinetic_energy", totals.kinetic_energy, "G M^2/R");
  return s;
}

/// Every field of the stage's record (model/stage_records.hpp), in stored order.
ReportSection record_section(const Checkpoint& c) {
  ReportSection s{"record", {}};
  auto add = [&s](const char* name, const auto& value, const char* unit, const char*) {
    using T = std::decay_t<decltype(value)>;
    if constexpr (std::is_same_v<T, std::vector<std::int64_t>>)
      s.add(name, std::vector<double>(value.begin(), value.end()), unit);
    else if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, std::string>)
      s.add(name, value);
    else if constexpr (std::is_same_v<T, std::optional<std::string>>)
      s.add(name, value.value_or("none"));  // `after` of an encounter begun from the relaxed body
    else if constexpr (Choice<T>)
      s.add(name, std::string(choice_name(value)));
    else
      s.add(name, value, unit);
  };
  std::visit([&](const auto& record) { visit_fields(record, add); }, c.stage.record);
  return s;
}

std::string value_text(const ReportValue& v) {
  auto number = [](double x) { return fmt::format("{:.6g}", x); };
  if (v.dimension) {
    ReportValue model = v;
    model.dimension.reset();
    return fmt::format("{} = {} {}", value_text(model), number(v.si), output_unit(*v.dimension).symbol);
  }
  if (!v.unit.empty() && v.unit != pure_number) {
    ReportValue bare = v;
    bare.unit.clear();
    return value_text(bare) + " " + v.unit;
  }
  switch (v.kind) {
    case ReportValue::Kind::integer: return fmt::format("{}", v.integer);
    case ReportValue::Kind::number: return number(v.number);
    case ReportValue::Kind::flag: return v.flag ? "true" : "false";
    case ReportValue::Kind::text: return v.text;
    case ReportValue::Kind::numbers: {
      std::string out = "[";
      for (std::size_t i = 0; i < v.numbers.size(); ++i) out += (i ? ", " : "") + number(v.numbers[i]);
      return out + "]";
    }
  }
  return {};
}

/// The units of a section's values, by key (values without a unit left out).
Json units_of(const ReportSection& s) {
  Json units = Json::object();
  for (const auto& [key, v] : s.entries)
    if (!v.unit.empty()) units[key] = v.unit;
  return units;
}

/// The SI values of a section's numbers, by si_key (numbers without one left out).
Json si_of(const ReportSection& s) {
  Json si = Json::object();
  for (const auto& [key, v] : s.entries)
    if (v.dimension) si[si_key(key, *v.dimension)] = v.si;
  return si;
}

Json json_of(const ReportSection& s) {
  Json json = Json::object();
  for (const auto& [key, v] : s.entries) {
    switch (v.kind) {
      case ReportValue::Kind::integer: json[key] = v.integer; break;
      case ReportValue::Kind::number: json[key] = v.number; break;
      case ReportValue::Kind::flag: json[key] = v.flag; break;
      case ReportValue::Kind::text: json[key] = v.text; break;
      case ReportValue::Kind::numbers: json[key] = v.numbers; break;
    }
  }
  return json;
}

}  // namespace

ReportSection& InspectReport::section(const std::string& name) {
  for (auto& s : sections)
    if (s.name == name) return s;
  sections.push_back({name, {}});
  return sections.back();
}

void add_failures_section(const Checkpoint& c, InspectReport& r) {
  if (!std::holds_alternative<EncounterRecord>(c.stage.record)) return;
  ReportSection& failures = r.section("failures");
  const Json summary = failure_summary_json(analyze_fractures(c));
  for (const auto& [key, value] : summary.items()) {
    const std::string unit(failure_summary_unit(key));
    if (value.is_number_integer()) failures.add(key, value.get<std::int64_t>(), unit);
    else failures.add(key, value.is_null() ? std::numeric_limits<double>::quiet_NaN() : value.get<double>(), unit);
  }
}

std::string fingerprint_hash(const std::string& fingerprint) {
  if (fingerprint.empty()) return "none";
  return fmt::format("xxh3:{:016x}", XXH3_64bits(fingerprint.data(), fingerprint.size()));
}

void add_si_values(InspectReport& r) {
  if (!r.moon) return;
  const auto convert = [&](ReportSection& s) {
    for (auto& [key, v] : s.entries)
      if (const auto dimension = dimension_of_model_unit(v.unit); dimension && v.kind == ReportValue::Kind::number) {
        v.dimension = dimension;
        v.si = model_to_output(r.moon->units, *dimension, v.number);
      }
  };
  convert(r.top);
  for (auto& s : r.sections) convert(s);
}

InspectReport build_inspect_report(const Checkpoint& c, const std::string& file) {
  InspectReport r;
  r.moon = stored_moon(c.config_toml, file + ":/parameters/config");
  // The format the file was written in (read_checkpoint upgrades an older one in memory).
  r.top.add("format_version", c.provenance.format_version > 0 ? c.provenance.format_version : checkpoint_format_version, "1")
      .add("stage", c.stage.name())
      .add("complete", c.stage.complete)
      .add("time", c.state.time, "t_grav")
      .add("step", c.state.step, "1")
      .add("dt", c.stage.clock.dt, "t_grav")
      .add("state_hash", state_hash(c.state))
      .add("parent_hash", c.stage.parent_hash)
      .add("fingerprint_hash", fingerprint_hash(c.stage.fingerprint));
  r.fingerprint = c.stage.fingerprint;
  if (!c.stage.diagnostic.empty()) r.top.add("diagnostic", c.stage.diagnostic);
  if (r.moon) {  // what one model unit is worth, in SI
    const ModelUnits& u = r.moon->units;
    const auto unit = [](Dimension d) { return std::string(output_unit(d).symbol); };
    r.section("moon")
        .add("name", r.moon->name)
        .add("radius", model_to_output(u, Dimension::length, 1), unit(Dimension::length))
        .add("mass", model_to_output(u, Dimension::mass, 1), unit(Dimension::mass))
        .add("mean_density", u.mean_density_kg_m3, unit(Dimension::density))
        .add("t_grav", u.time_s, "s")
        .add("v_c", model_to_output(u, Dimension::speed, 1), unit(Dimension::speed))
        .add("e_g", model_to_output(u, Dimension::pressure, 1), unit(Dimension::pressure))
        .add("G", gravitational_constant_si, "m^3 kg^-1 s^-2");
  }
  r.section("provenance")
      .add("version", c.provenance.version)
      .add("git_commit", c.provenance.git_commit)
      .add("compiler", c.provenance.compiler)
      .add("build_flags", c.provenance.build_flags)
      .add("gravity_kernel", c.stage.gravity_kernel.empty() ? "none recorded" : c.stage.gravity_kernel);
  if (!c.stage.gravity_kernel_changes.empty())
    r.sections.back().add("gravity_kernel_changes", c.stage.gravity_kernel_changes);
  r.sections.push_back(counts_section(c));
  r.sections.push_back(derived_section(c, file));
  r.sections.push_back(gravity_section(c, file));
  r.sections.push_back(conservation_section(c));
  r.sections.push_back(record_section(c));

  if (const auto* e = std::get_if<EncounterRecord>(&c.stage.record)) {
    ReportSection& p = r.section("perturber");
    if (c.state.perturber.present) p.add("mass", c.state.perturber.mass, "M");
    p.add("min_distance", e->min_distance, "R").add("speed_at_min", e->speed_at_min, "sqrt(GM/R)");
    p.add("time_from_pericenter", c.state.time - e->pericenter_time, "t_grav");
  }
  if (const auto* relax = std::get_if<RelaxRecord>(&c.stage.record); relax && relax->probe_runs > 0)
    r.section("stability")
        .add("failures", relax->probe_failures, "1")
        .add("max_shell_strain", relax->probe_max_shell_strain, "1");
  add_spin_section(c, r);
  add_failures_section(c, r);
  add_si_values(r);
  return r;
}

void add_spin_section(const Checkpoint& c, InspectReport& r) {
  const double spin = stored_spin(c, "inspect");
  if (spin == 0) return;
  // A mid-stage relax checkpoint is in the co-rotating frame, which is the body frame.
  const auto* relax = std::get_if<RelaxRecord>(&c.stage.record);
  const bool rotating = relax && !relax->relaxed;
  const Matrix3 to_body = rotating ? Matrix3(Matrix3::Identity()) : Matrix3(spin_rotation(spin, c.state.time).transpose());
  const ShellFlattening shape = shell_flattening(c.body, c.state, to_body);
  const Vec3 measured = body_angular_velocity(c.body, c.state);
  r.section("spin")
      .add("angular_velocity", spin, "1/t_grav")
      .add("frame", rotating ? "co-rotating (relaxing)" : "inertial, spinning")
      .add("measured_angular_velocity", std::vector<double>{measured.x(), measured.y(), measured.z()}, "1/t_grav")
      .add("flattening", shape.flattening, "1")
      .add("equatorial_radius", shape.equatorial_radius, "R")
      .add("polar_radius", shape.polar_radius, "R");
}

std::string inspect_report_json(const InspectReport& r) {
  Json json = json_of(r.top);
  json["fingerprint"] = r.fingerprint;
  Json units = units_of(r.top);
  for (const auto& s : r.sections) {
    json[s.name] = json_of(s);
    if (Json section_units = units_of(s); !section_units.empty()) units[s.name] = std::move(section_units);
  }
  json["units"] = std::move(units);
  if (r.moon) {
    Json si = si_of(r.top);
    si["units"] = si_units_text(*r.moon);
    for (const auto& s : r.sections)
      if (Json section = si_of(s); !section.empty()) si[s.name] = std::move(section);
    json["si"] = std::move(si);
  }
  return json_text(json);
}

std::string inspect_report_table(const InspectReport& r) {
  std::size_t width = 0;
  for (const auto& [key, value] : r.top.entries) width = std::max(width, key.size());
  for (const auto& s : r.sections)
    for (const auto& [key, value] : s.entries) width = std::max(width, key.size() + 2);
  std::string out = "units: G = M = R = 1 (README \"Units\"); a number without a unit is a count or a ratio\n";
  if (r.moon) out += "beside them (\" = \"): " + si_units_text(*r.moon) + "\n";
  for (const auto& [key, value] : r.top.entries) out += fmt::format("{:<{}}  {}\n", key, width, value_text(value));
  for (const auto& s : r.sections) {
    out += s.name + (s.entries.empty() ? "  (none)\n" : "\n");
    for (const auto& [key, value] : s.entries)
      out += fmt::format("  {:<{}}  {}\n", key, width - 2, value_text(value));
  }
  return out;
}

}  // namespace tidalcrust
