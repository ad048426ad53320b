#include "io/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

#include "base/errors.hpp"
#include "io/atomic_file.hpp"

namespace tidalcrust {

ProgressReporter::ProgressReporter(std::string label, std::int64_t first_step, std::int64_t start_step,
                                   std::int64_t last_step, std::optional<std::filesystem::path> status_file)
    : label_(std::move(label)),
      first_step_(first_step),
      start_step_(start_step),
      last_step_(last_step),
      status_file_(std::move(status_file)),
      start_(std::chrono::steady_clock::now()),
      last_print_(start_),
      terminal_(isatty(fileno(stderr)) != 0) {}

void ProgressReporter::update(std::int64_t step, bool force) {
  auto now = std::chrono::steady_clock::now();
  if (!force && now - last_print_ < std::chrono::seconds(1)) return;
  last_print_ = now;
  double seconds = std::chrono::duration<double>(now - start_).count();
  double rate = seconds > 0 ? static_cast<double>(step - start_step_) / seconds : 0.0;
  double eta = rate > 0 ? static_cast<double>(last_step_ - step) / rate : 0.0;
  double percent = last_step_ > first_step_
                       ? 100.0 * static_cast<double>(step - first_step_) / static_cast<double>(last_step_ - first_step_)
                       : 100.0;
  // On a terminal the line rewrites itself; in a log each update is its own line.
  fmt::print(stderr, "{}{}: step {} of {} ({:.0f}%), {:.0f} steps/s, ETA {:.0f} s{}", terminal_ ? "\r" : "",
             label_, step, last_step_, percent, rate, eta, terminal_ ? "   " : "\n");
  std::fflush(stderr);
  write_status(step, rate, eta, "running");
}

void ProgressReporter::finish(std::int64_t step, const std::string& state) {
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  double rate = seconds > 0 ? static_cast<double>(step - start_step_) / seconds : 0.0;
  fmt::print(stderr, "{}{}: {} at step {} ({:.1f} s, {:.0f} steps/s)\n", terminal_ ? "\r" : "", label_, state,
             step, seconds, rate);
  write_status(step, rate, 0.0, state);
}

void ProgressReporter::write_status(std::int64_t step, double rate, double eta, const std::string& state) const {
  if (!status_file_) return;
  const Json status = {{"stage", label_},
                       {"state", state},
                       {"step", step},
                       {"first_step", first_step_},
                       {"start_step", start_step_},
                       {"last_step", last_step_},
                       {"steps_per_second", rate},
                       {"eta_seconds", eta},
                       {"pid", static_cast<std::int64_t>(getpid())}};
  write_status_file(*status_file_, status);
}

void write_status_file(const std::filesystem::path& file, const Json& status) {
  try {
    write_file_atomically(file, json_text(status));
  } catch (const InputError&) {
    // a status file is a courtesy; never fail the run for it
  }
}

}  // namespace tidalcrust
