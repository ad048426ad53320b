#pragma once
// Other values to try for a configuration key (the key tests: StageFingerprint.EveryKey...,
// KeyReaders.*): a boolean flipped, a name renamed, a choice's other names (from its range "one
// of: a, b", the choice's table), a number shifted, scaled and a few fixed ones. Some may be out of
// the key's range; the tests skip the values that apply_override or validate refuse.
#include <fmt/format.h>

#include <string>
#include <vector>

#include "model/config.hpp"

namespace tidalcrust::test_support {

inline std::vector<std::string> other_key_values(const KeyInfo& key) {
  if (key.type == "boolean") return {key.value == "true" ? "false" : "true"};
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
    for (double w : {v * 1.25, v * 0.8, v + 0.01, 0.3, 0.05, 1.5}) out.push_back(fmt::format("{}", w));
  }
  return out;
}

}  // namespace tidalcrust::test_support
