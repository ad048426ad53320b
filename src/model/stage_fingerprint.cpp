#include "model/stage_fingerprint.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>
#include <sstream>
#include <string_view>
#include <vector>

namespace tidalcrust {
namespace {

/// A line as compared: without its trailing comment; a body stage's line of an encounter key
/// ("encounters.NAME.key = value", as written before 2026-12-06) without the encounter's name,
/// "encounters.*.key = value" (what stage_fingerprint writes now).
std::string canonical_line(std::string line) {
  if (const auto comment = line.find("  # "); comment != std::string::npos) line.erase(comment);
  constexpr std::string_view prefix = "encounters.";
  const auto equals = line.find(" = ");
  if (line.starts_with(prefix) && equals != std::string::npos) {
    const auto last_dot = line.rfind('.', equals);  // names may hold dots, keys do not
    if (last_dot != std::string::npos && last_dot >= prefix.size()) line = "encounters.*" + line.substr(last_dot);
  }
  return line;
}

/// The distinct canonical lines of a fingerprint, sorted.
std::vector<std::string> canonical_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line = canonical_line(std::move(line)); !line.empty()) lines.push_back(std::move(line));
  std::sort(lines.begin(), lines.end());
  lines.erase(std::unique(lines.begin(), lines.end()), lines.end());
  return lines;
}

/// "section.key" of a line "section.key = value".
std::string_view key_of(std::string_view line) { return line.substr(0, line.find(" = ")); }

}  // namespace

std::string stage_fingerprint(const Config& config, StageId stage, const Encounter* own) {
  std::string text;
  for (const KeyInfo& key : describe_keys(config))
    if (key.read_by.contains(stage) && key.value) text += fmt::format("{}.{} = {}\n", key.section, key.name, *key.value);
  if (own) {
    text += "[[encounters]]\n";
    for (const KeyInfo& key : describe_keys(*own, config))
      if (key.read_by.contains(stage) && key.value) text += fmt::format("{} = {}\n", key.name, *key.value);
    return text;
  }
  // A body stage reads the encounters' values, not which encounter holds them (relax probes each
  // distinct eps_S): one line per distinct value, so that expanding an encounter into ensemble
  // members, or renaming it, reuses the relaxed body. Exact while each encounter key is read on
  // its own (test StageFingerprint.ABodyStageReadsEachEncounterKeyOnItsOwn).
  std::set<std::string> encounter_lines;
  for (const Encounter& e : config.encounters)
    for (const KeyInfo& key : describe_keys(e, config))
      if (key.read_by.contains(stage) && key.value) encounter_lines.insert(fmt::format("encounters.*.{} = {}\n", key.name, *key.value));
  for (const std::string& line : encounter_lines) text += line;
  return text;
}

bool same_fingerprint(const std::string& a, const std::string& b) { return canonical_lines(a) == canonical_lines(b); }

std::string first_difference(const std::string& old_text, const std::string& new_text) {
  const std::vector<std::string> old_lines = canonical_lines(old_text), new_lines = canonical_lines(new_text);
  auto has = [](const std::vector<std::string>& lines, const std::string& line) {
    return std::binary_search(lines.begin(), lines.end(), line);
  };
  auto line_of_key = [](const std::vector<std::string>& lines, std::string_view key) {
    for (const auto& line : lines)
      if (key_of(line) == key) return line;
    return std::string();
  };
  std::istringstream in(new_text);  // in the new text's order
  for (std::string line; std::getline(in, line);) {
    line = canonical_line(std::move(line));
    if (!line.empty() && !has(old_lines, line))
      return fmt::format("'{}' -> '{}'", line_of_key(old_lines, key_of(line)), line);
  }
  for (const auto& line : old_lines)
    if (!has(new_lines, line)) return fmt::format("'{}' -> ''", line);
  return "";
}

std::string recomputed_fingerprint(const Checkpoint& checkpoint, const std::string& origin) {
  const Config config = parse_config(checkpoint.config_toml, origin + ":/parameters/config");
  const Encounter* own = record_encounter(checkpoint.stage.record);
  if (own)
    for (const Encounter& e : config.encounters)
      if (e.name == own->name) own = &e;
  return stage_fingerprint(config, stage_id(checkpoint.stage.record), own);
}

}  // namespace tidalcrust
