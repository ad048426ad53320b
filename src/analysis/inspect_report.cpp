#include "analysis/inspect_report.hpp"

#include "analysis/fracture_analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <numeric>

#include "model/config.hpp"
#include "physics/conservation.hpp"
#include "model/derived_quantities.hpp"
#include "io/json.hpp"
#include "io/state_hash.hpp"
#include "io/checkpoint_file.hpp"

namespace tidalcrust {

namespace {

std::vector<double> as_vector(const std::array<double, 3>& a) { return {a.begin(), a.end()}; }

ReportSection counts_section(const Checkpoint& c) {
  const Body& b = c.body;
  const std::int64_t failed =
      std::accumulate(c.state.springs.failed.begin(), c.state.springs.failed.end(), std::int64_t{0});
  ReportSection s{"counts", {}};
  s.add("interior", b.count_species(Species::interior))
      .add("shell", b.count_species(Species::shell))
      .add("springs_interior", b.count_springs(SpringKind::interior))
      .add("springs_shell", b.count_springs(SpringKind::shell))
      .add("springs_cross", b.count_springs(SpringKind::cross))
      .add("hinges", b.hinge_count())
      .add("faces", b.faces.size())
      .add("failed", failed);
  return s;
}

ReportSection derived_section(const Checkpoint& c, const std::string& file) {
  const Config config = parse_config(c.config_toml, file + ":/parameters/config");
  const DerivedQuantities q = derive_quantities(c.body, c.state, config.interior.radius);
  ReportSection s{"derived", {}};
  s.add("E_I", q.E_I).add("L_I", q.L_I).add("k_I", q.k_I).add("L_S", q.L_S).add("k_S", q.k_S).add("M_S", q.M_S);
  s.add("L_C", q.L_C).add("k_C", q.k_C).add("V_IP", q.V_IP).add("V_SP", q.V_SP).add("V_Co", q.V_Co);
  s.add("h_S", q.h_S).add("dt_max", q.dt_max);
  return s;
}

ReportSection conservation_section(const Checkpoint& c) {
  const Conservation totals = measure_conservation(c.body, c.state);
  ReportSection s{"conservation", {}};
  s.add("momentum", as_vector(totals.momentum))
      .add("angular_momentum", as_vector(totals.angular_momentum))
      .add("kinetic_energy", totals.kinetic_energy);
  return s;
}

/// Every field of the stage's record (model/stage_records.hpp), in stored order.
ReportSection record_section(const Checkpoint& c) {
  ReportSection s{"record", {}};
  auto add = [&s](const char* name, const auto& value, const char*, const char*) {
    using T = std::decay_t<decltype(value)>;
    if constexpr (std::is_same_v<T, std::vector<std::int64_t>>)
      s.add(name, std::vector<double>(value.begin(), value.end()));
    else
      s.add(name, value);
  };
  std::visit([&](const auto& record) { visit_fields(record, add); }, c.stage.record);
  return s;
}

std::string value_text(const ReportValue& v) {
  auto number = [](double x) { return fmt::format("{:.6g}", x); };
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
  const Json summary = failure_summary_json(analyze_fractures(c.body, c.state));
  for (const auto& [key, value] : summary.items()) {
    if (value.is_number_integer()) failures.add(key, value.get<std::int64_t>());
    else failures.add(key, value.get<double>());
  }
}

InspectReport build_inspect_report(const Checkpoint& c, const std::string& file) {
  InspectReport r;
  r.top.add("format_version", checkpoint_format_version)
      .add("stage", c.stage.name())
      .add("complete", c.stage.complete)
      .add("time", c.state.time)
      .add("step", c.state.step)
      .add("dt", c.stage.clock.dt)
      .add("state_hash", state_hash(c.state))
      .add("parent_hash", c.stage.parent_hash);
  if (!c.stage.diagnostic.empty()) r.top.add("diagnostic", c.stage.diagnostic);
  r.sections.push_back(counts_section(c));
  r.sections.push_back(derived_section(c, file));
  r.sections.push_back(conservation_section(c));
  r.sections.push_back(record_section(c));

  if (const auto* e = std::get_if<EncounterRecord>(&c.stage.record)) {
    ReportSection& p = r.section("perturber");
    if (c.state.perturber.present) p.add("mass", c.state.perturber.mass);
    p.add("min_distance", e->min_distance).add("speed_at_min", e->speed_at_min);
  }
  if (const auto* relax = std::get_if<RelaxRecord>(&c.stage.record); relax && relax->probe_runs > 0)
    r.section("stability").add("failures", relax->probe_failures).add("max_shell_strain", relax->probe_max_shell_strain);
  add_failures_section(c, r);
  return r;
}

std::string inspect_report_json(const InspectReport& r) {
  Json json = json_of(r.top);
  for (const auto& s : r.sections) json[s.name] = json_of(s);
  return json_text(json);
}

std::string inspect_report_table(const InspectReport& r) {
  std::size_t width = 0;
  for (const auto& [key, value] : r.top.entries) width = std::max(width, key.size());
  for (const auto& s : r.sections)
    for (const auto& [key, value] : s.entries) width = std::max(width, key.size() + 2);
  std::string out;
  for (const auto& [key, value] : r.top.entries) out += fmt::format("{:<{}}  {}\n", key, width, value_text(value));
  for (const auto& s : r.sections) {
    out += s.name + (s.entries.empty() ? "  (none)\n" : "\n");
    for (const auto& [key, value] : s.entries)
      out += fmt::format("  {:<{}}  {}\n", key, width - 2, value_text(value));
  }
  return out;
}

}  // namespace tidalcrust
