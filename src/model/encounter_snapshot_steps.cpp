#include "model/encounter_snapshot_steps.hpp"

#include <fmt/format.h>

#include <string>

#include "base/errors.hpp"

namespace tidalcrust {

void store_snapshot_steps(StageInfo& stage, const std::vector<std::int64_t>& steps) {
  stage.scalars[encounter_snapshot_keys::count] = static_cast<double>(steps.size());
  for (std::size_t i = 0; i < steps.size(); ++i)
    stage.scalars[encounter_snapshot_keys::step_prefix + std::to_string(i)] = static_cast<double>(steps[i]);
}

std::vector<std::int64_t> snapshot_steps(const StageInfo& stage) {
  std::vector<std::int64_t> steps;
  const auto count = stage.scalars.find(encounter_snapshot_keys::count);
  if (count == stage.scalars.end()) return steps;
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(count->second); ++i) {
    const std::string key = encounter_snapshot_keys::step_prefix + std::to_string(i);
    const auto it = stage.scalars.find(key);
    if (it == stage.scalars.end())
      throw InputError(fmt::format("encounter scalar '{}' (/checkpoint/scalars) is missing", key));
    steps.push_back(static_cast<std::int64_t>(it->second));
  }
  return steps;
}

}  // namespace tidalcrust
