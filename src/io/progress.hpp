#pragma once
// Progress of a long stage: a line on the terminal (stage, step, steps/s, ETA) at most once a
// second, and a small status JSON file that other programs can poll.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "io/json.hpp"

namespace tidalcrust {

/// Writes the JSON object `status` to `file` atomically (io/atomic_file.hpp), so a poller never reads
/// half a file; a status file is a courtesy, so failures are ignored.
void write_status_file(const std::filesystem::path& file, const Json& status);

class ProgressReporter {
 public:
  /// `status_file` empty: no status file. `label` e.g. "relax" or "encounter T5". The stage runs
  /// from `first_step` to `last_step`; this process starts at `start_step` (> first_step when it
  /// resumed), so the percentage is of the stage and the rate and ETA are of this process's steps.
  ProgressReporter(std::string label, std::int64_t first_step, std::int64_t start_step, std::int64_t last_step,
                   std::optional<std::filesystem::path> status_file);
  /// Called after every step; prints/writes only when a second has passed (or force).
  void update(std::int64_t step, bool force = false);
  /// Final line and status "done" (or the given state, e.g. "interrupted").
  void finish(std::int64_t step, const std::string& state = "done");

 private:
  void write_status(std::int64_t step, double rate, double eta, const std::string& state) const;

  std::string label_;
  std::int64_t first_step_, start_step_, last_step_;
  std::optional<std::filesystem::path> status_file_;
  std::chrono::steady_clock::time_point start_, last_print_;
  bool terminal_;
};

}  // namespace tidalcrust
