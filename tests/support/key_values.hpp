#pragma once
// Other values to try for a configuration key (the key tests: StageFingerprint.EveryKey...,
// KeyReaders.*): a boolean flipped, a name renamed, a choice's other names (from its range "one
// of: a, b", the choice's table), a number shifted, scaled and a few fixed ones. Some may be out of
// the key's range; the tests skip the values that apply_override or validate refuse.
#include <fmt/format.h>

#include <optional>
#include <string>
#include <vector>

#include "model/config.hpp"
#include "model/moon_units.hpp"

namespace tidalcrust::test_support {

inline std::vector<std::string> other_key_values(const KeyInfo& key) {
  if (key.type == "boolean") return {key.value == "true" ? "false" : "true"};
  if (key.section == "moon" && key.name == "preset") return {"dione", "Europa"};
  // A rotation period that is slower than 0.9 of breakup for the tiny moons (t_grav ~ 1 h).
  if (key.section == "moon" && key.name == "spin_period") return {"'40 h'", "'100 h'"};
  if (const auto dimension = dimension_of_si_unit(key.unit); key.type == "string" && dimension) {
    // A [moon] quantity (the value as to_toml writes it, 'number unit'), scaled; unset: an example.
    const std::string text = key.value ? key.value->substr(1, key.value->size() - 2) : std::string(dimension_example(*dimension));
    std::size_t end = 0;
    const double v = std::stod(text, &end);
    std::vector<std::string> out;
    for (double w : {v * 1.25, v * 0.8, v * 0.5}) out.push_back(fmt::format("'{}{}'", w, text.substr(end)));
    return out;
  }
  // encounters.after: another encounter of the workflow (paper-T's T1; the tiny bodies of
  // KeyReaders have one encounter only, so it is tried in the fingerprint test alone).
  if (key.section == "encounters" && key.name == "after") return {"T1"};
  // [crust] (docs/crust.md): other fields, a map of tests/support; a digest alone builds nothing else.
  if (key.section == "crust" && key.name == "thickness_harmonics") return {"'c10 = 0.3'", "'s11 = 0.2'"};
  if (key.section == "crust" && key.name == "strength_harmonics") return {"'s11 = -0.3'", "'c10 = 0.2'"};
  if (key.section == "crust" && key.name == "weak_lines")
    return {"'pole_lon = 0, pole_lat = 0, half_width = 20, factor = 0.5'"};
  if (key.section == "crust" && key.name == "map_file")
    return {"'" + std::string(TIDALCRUST_SOURCE_DIR) + "/tests/support/crust-map.csv'"};
  if (key.section == "crust" && key.name == "map_digest") return {"'0123456789abcdef'"};
  if (key.type == "string") return {"renamed"};  // workflow.name, encounters.name
  std::vector<std::string> out;
  if (key.type == "choice") {
    const std::string list = key.range.substr(key.range.find(": ") + 2);
    for (std::size_t at = 0; at != std::string::npos;) {
      const auto comma = list.find(", ", at);
      out.push_back(list.substr(at, comma == std::string::npos ? comma : comma - at));
      at = comma == std::string::npos ? comma : comma + 2;
    }
  } else if (key.type == "integer") {
    const long long v = key.value ? std::stoll(*key.value) : 2;
    for (long long w : {v + 1, v - 1, 2 * v, 3LL, 1LL}) out.push_back(fmt::format("{}", w));
  } else {
    const double v = key.value ? std::stod(*key.value) : 0.3;
    // Not the value itself in another spelling (a default 0.0 scaled is "0").
    for (double w : {v * 1.25, v * 0.8, v + 0.01, 0.3, 0.05, 1.5})
      if (w != v) out.push_back(fmt::format("{}", w));
  }
  return out;
}

/// `base` with the key at `path` ("section.name" or "encounters.<name>.name") set to `value`, when
/// that is another value than the key's and apply_override and validate accept it; nothing
/// otherwise (not a valid value there, or a key a [material] body derives).
inline std::optional<Config> changed_config(const Config& base, const KeyInfo& key, const std::string& path,
                                            const std::string& value) {
  if ((key.type == "string" || key.type == "choice" ? "'" + value + "'" : value) == key.value) return std::nullopt;
  Config changed = base;
  try {
    apply_override(changed, path + "=" + value);
    validate(changed, "test");
  } catch (const InputError&) {
    return std::nullopt;
  }
  return changed;
}

}  // namespace tidalcrust::test_support
