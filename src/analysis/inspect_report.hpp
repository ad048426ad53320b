#pragma once
// What `tidalcrust inspect` shows about one checkpoint (README "Command line"), built
// once from a Checkpoint and rendered either as JSON or as an aligned text table. Other parts
// of the program extend it by adding sections (see add_failures_section).
#include <concepts>
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "model/checkpoint.hpp"
#include "model/moon_units.hpp"

namespace tidalcrust {

/// One value of the report: an integer, a number, a flag, a text or a list of numbers, with the
/// unit of a number (G = M = R = 1: "R", "t_grav", "sqrt(GM/R)", ...; "1" a pure number or
/// count, "step" a global step; "" for texts and flags).
struct ReportValue {
  enum class Kind { integer, number, flag, text, numbers };
  Kind kind = Kind::integer;
  std::string unit;
  std::int64_t integer = 0;
  double number = 0;
  bool flag = false;
  std::string text;
  std::vector<double> numbers;
  /// Of a [moon] workflow (docs/moon.md, "Output in SI"): the dimension of a number whose unit
  /// is a model unit (dimension_of_model_unit) and its value in that dimension's output unit.
  std::optional<Dimension> dimension;
  double si = 0;
};

/// An ordered list of named values; `name` is the JSON key of the nested object.
struct ReportSection {
  std::string name;
  std::vector<std::pair<std::string, ReportValue>> entries;

  ReportSection& add(std::string key, double value, std::string unit) {
    ReportValue v;
    v.kind = ReportValue::Kind::number;
    v.number = value;
    v.unit = std::move(unit);
    return put(std::move(key), std::move(v));
  }
  ReportSection& add(std::string key, std::string value) {
    ReportValue v;
    v.kind = ReportValue::Kind::text;
    v.text = std::move(value);
    return put(std::move(key), std::move(v));
  }
  ReportSection& add(std::string key, const char* value) { return add(std::move(key), std::string(value)); }
  ReportSection& add(std::string key, std::vector<double> values, std::string unit) {
    ReportValue v;
    v.kind = ReportValue::Kind::numbers;
    v.numbers = std::move(values);
    v.unit = std::move(unit);
    return put(std::move(key), std::move(v));
  }
  /// Any integer (counts, steps) is stored as int64.
  template <std::integral T>
    requires(!std::is_same_v<T, bool>)
  ReportSection& add(std::string key, T value, std::string unit) {
    ReportValue v;
    v.kind = ReportValue::Kind::integer;
    v.integer = static_cast<std::int64_t>(value);
    v.unit = std::move(unit);
    return put(std::move(key), std::move(v));
  }
  ReportSection& add(std::string key, bool value) {
    ReportValue v;
    v.kind = ReportValue::Kind::flag;
    v.flag = value;
    return put(std::move(key), std::move(v));
  }

 private:
  ReportSection& put(std::string key, ReportValue value) {
    entries.emplace_back(std::move(key), std::move(value));
    return *this;
  }
};

struct InspectReport {
  ReportSection top;                    ///< top-level keys (format_version, stage, ...)
  std::vector<ReportSection> sections;  ///< nested objects, in output order
  std::string fingerprint;              ///< the stage fingerprint's full text (JSON only)
  std::optional<MoonScale> moon;        ///< of a [moon] workflow: the SI beside the model values

  /// The section called `name`, appended if it does not exist yet.
  ReportSection& section(const std::string& name);
};

/// Builds the full report: top-level stage keys (with the fingerprint's short hash), the writer's
/// provenance (version, git commit, compiler, build flags), counts, derived (Table 3 quantities
/// with r_I from the stored configuration), conservation, the stage record (units from
/// visit_fields), and for encounters the perturber (with the time from pericenter), for relaxed
/// bodies the stability probe, plus add_failures_section. Every number carries its unit. Of a
/// [moon] workflow a section `moon` (its scale) comes first and every number in a model unit of
/// model_unit_name (R, M, t_grav, sqrt(GM/R), e_g, ...) gets its SI value (add_si_values).
/// `file` names the checkpoint in error messages (e.g. an unparsable stored configuration).
InspectReport build_inspect_report(const Checkpoint& checkpoint, const std::string& file);

/// Of a spinning body (docs/spin.md): a section `spin` with angular_velocity (configured),
/// frame, measured_angular_velocity (I^-1 L about the centre of mass) and the shell's flattening
/// with its equatorial and polar radii (shell_flattening in the body frame). Nothing otherwise.
void add_spin_section(const Checkpoint& checkpoint, InspectReport& report);

/// Hook for the fracture statistics of an encounter (`failures {count, fraction_shell, ...}`):
/// adds nothing yet; the analysis code fills it in.
void add_failures_section(const Checkpoint& checkpoint, InspectReport& report);

/// Sets the SI value of every number of `report` whose unit is a model unit, with the units of
/// `report.moon`; nothing without a moon.
void add_si_values(InspectReport& report);

/// One JSON object (io/json.hpp: doubles read back to the same bits, NaN is null): the values
/// as "key": value, and their units in one more object "units", laid out like the values
/// ("units": {"time": "t_grav", ..., "record": {"pericenter": "R", ...}}; keys without a unit are
/// left out). The fingerprint appears in full ("fingerprint") beside its short hash. Of a moon, an
/// object "si" last, laid out like the values, with each SI value under si_key(key) ("time_h",
/// "perturber": {"min_distance_km", ...}) and the units text.
std::string inspect_report_json(const InspectReport& report);

/// A line naming the units, then aligned "key  value unit" lines (the unit "1" of counts and
/// ratios left out; of a moon "value unit = SI-value SI-unit"), sections indented below their
/// names; the fingerprint as its short hash only (inspect --fingerprint prints the text).
std::string inspect_report_table(const InspectReport& report);

/// Short identity of a stage fingerprint: "xxh3:" and 16 hex digits of XXH3-64 of its text, or
/// "none" for an empty fingerprint (a checkpoint not written by `run`).
std::string fingerprint_hash(const std::string& fingerprint);

}  // namespace tidalcrust
