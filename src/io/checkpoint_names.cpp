#include "io/checkpoint_names.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>

namespace tidalcrust {

std::filesystem::path body_folder(const std::filesystem::path& root, const Config& config, const Encounter* encounter) {
  const std::uint64_t seed = encounter ? body_seed_of(config, *encounter) : config.workflow.seed;
  return seed == config.workflow.seed ? root / "body" : root / ("body-seed" + std::to_string(seed));
}

std::filesystem::path sibling_checkpoint(const std::filesystem::path& out, const std::string& suffix) {
  std::filesystem::path p = out;
  p.replace_extension();
  p += "." + suffix + ".h5";
  return p;
}

void remove_checkpoint_files(const std::filesystem::path& file) {
  std::error_code ignored;
  std::filesystem::remove(file, ignored);
  std::filesystem::path xdmf = file;
  std::filesystem::remove(xdmf.replace_extension(".xdmf"), ignored);
}

void remove_stage_outputs(const std::filesystem::path& file, bool keep_resume_files,
                          const std::vector<std::filesystem::path>& keep) {
  std::vector<std::filesystem::path> outputs = {file, sibling_checkpoint(file, "diagnostic")};
  if (!keep_resume_files) {
    outputs.push_back(sibling_checkpoint(file, "mid"));
    for (const auto& snapshot : find_snapshots(file)) outputs.push_back(snapshot.file);
  }
  std::error_code ignored;
  for (const auto& output : outputs) {
    const bool kept = std::any_of(keep.begin(), keep.end(), [&](const std::filesystem::path& k) {
      return std::filesystem::weakly_canonical(k, ignored) == std::filesystem::weakly_canonical(output, ignored);
    });
    if (!kept) remove_checkpoint_files(output);
  }
}

std::filesystem::path snapshot_path(const std::filesystem::path& checkpoint_file, std::int64_t step) {
  return checkpoint_file.parent_path() /
         fmt::format("{}{}{}{}", checkpoint_file.stem().string(), snapshot_infix, step, checkpoint_file.extension().string());
}

std::vector<SnapshotFile> find_snapshots(const std::filesystem::path& checkpoint_file) {
  std::vector<SnapshotFile> found;
  const std::filesystem::path folder = checkpoint_file.parent_path().empty() ? "." : checkpoint_file.parent_path();
  const std::string prefix = checkpoint_file.stem().string() + std::string(snapshot_infix);
  const std::string suffix = checkpoint_file.extension().string();
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= prefix.size() + suffix.size() || !name.starts_with(prefix) || !name.ends_with(suffix)) continue;
    const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
    std::int64_t step = 0;
    const auto [end, err] = std::from_chars(digits.data(), digits.data() + digits.size(), step);
    if (err != std::errc() || end != digits.data() + digits.size() || step < 0) continue;
    found.push_back({step, checkpoint_file.parent_path() / name});
  }
  std::sort(found.begin(), found.end(), [](const SnapshotFile& a, const SnapshotFile& b) { return a.step < b.step; });
  return found;
}

std::vector<std::size_t> choose_snapshot_panels(const std::vector<double>& times, double pericenter_time,
                                                std::size_t max_panels) {
  const std::size_t n = times.size();
  std::vector<std::size_t> chosen;
  if (n == 0 || max_panels == 0) return chosen;
  if (n <= max_panels) {
    for (std::size_t i = 0; i < n; ++i) chosen.push_back(i);
    return chosen;
  }
  std::size_t nearest = 0;
  for (std::size_t i = 1; i < n; ++i)
    if (std::abs(times[i] - pericenter_time) < std::abs(times[nearest] - pericenter_time)) nearest = i;
  if (max_panels == 1) return {n - 1};
  for (std::size_t k = 0; k < max_panels; ++k) chosen.push_back((k * (n - 1) + (max_panels - 1) / 2) / (max_panels - 1));
  if (std::find(chosen.begin(), chosen.end(), nearest) == chosen.end()) {
    // Replace the evenly spread pick closest to pericenter, keeping the first and the last.
    std::size_t replace = 1;
    for (std::size_t k = 1; k + 1 < chosen.size(); ++k)
      if (std::abs(times[chosen[k]] - pericenter_time) < std::abs(times[chosen[replace]] - pericenter_time)) replace = k;
    chosen[replace] = nearest;
    std::sort(chosen.begin(), chosen.end());
  }
  chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
  return chosen;
}

}  // namespace tidalcrust
