#include "io/test_points.hpp"

#include <fmt/format.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <utility>

#include "base/errors.hpp"
#include "io/stop_signal.hpp"

namespace tidalcrust {

namespace {

enum class Counted { step, write, body_check };

/// One point: the N-th step or write of this process.
struct Point {
  Counted counted;
  std::int64_t n;
};

/// "step:N" or "write:N" (N >= 1) from the variable `name`; nothing when it is unset or empty.
std::optional<Point> point_from_environment(const char* name, bool writes_allowed) {
  const char* value = std::getenv(name);
  if (!value || !*value) return std::nullopt;
  const std::string_view text(value);
  const auto colon = text.find(':');
  const std::string_view kind = text.substr(0, colon);
  std::int64_t n = 0;
  const char* first = colon == std::string_view::npos ? value + text.size() : value + colon + 1;
  const char* last = value + text.size();
  const auto [end, error] = std::from_chars(first, last, n);
  const bool kind_ok = kind == "step" || (writes_allowed ? kind == "write" : kind == "body-check");
  if (!kind_ok || colon == std::string_view::npos || error != std::errc() || end != last || n < 1)
    throw InputError(fmt::format("environment variable {}='{}': expected step:N or {}:N with N >= 1 (a testing aid)",
                                 name, value, writes_allowed ? "write" : "body-check"));
  return Point{kind == "step" ? Counted::step : kind == "write" ? Counted::write : Counted::body_check, n};
}

/// The failing reads "N:K" of TIDALCRUST_TEST_READ_EIO: attempts N to N+K-1; nothing when unset.
std::optional<std::pair<std::int64_t, std::int64_t>> read_failures_from_environment() {
  const char* name = "TIDALCRUST_TEST_READ_EIO";
  const char* value = std::getenv(name);
  if (!value || !*value) return std::nullopt;
  const std::string_view text(value);
  const auto colon = text.find(':');
  std::int64_t n = 0, k = 0;
  const char* last = value + text.size();
  bool ok = colon != std::string_view::npos;
  if (ok) {
    const auto [end_n, error_n] = std::from_chars(value, value + colon, n);
    const auto [end_k, error_k] = std::from_chars(value + colon + 1, last, k);
    ok = error_n == std::errc() && end_n == value + colon && error_k == std::errc() && end_k == last && n >= 1 && k >= 1;
  }
  if (!ok) throw InputError(fmt::format("environment variable {}='{}': expected N:K with N, K >= 1 (a testing aid)", name, value));
  return std::pair{n, k};
}

struct Points {
  std::optional<std::pair<std::int64_t, std::int64_t>> read_failures = read_failures_from_environment();
  std::int64_t reads = 0;
  std::optional<Point> kill = point_from_environment("TIDALCRUST_TEST_KILL_AT", true);
  std::optional<Point> hold = point_from_environment("TIDALCRUST_TEST_HOLD_AT", false);
  std::filesystem::path hold_file;
  std::int64_t steps = 0, writes = 0, body_checks = 0;

  Points() {
    if (!hold) return;
    const char* file = std::getenv("TIDALCRUST_TEST_HOLD_FILE");
    if (!file || !*file)
      throw InputError("environment variable TIDALCRUST_TEST_HOLD_AT is set but TIDALCRUST_TEST_HOLD_FILE is not");
    hold_file = file;
  }
};

Points& points() {
  static Points p;
  return p;
}

bool reached(const std::optional<Point>& point, Counted counted, std::int64_t count) {
  return point && point->counted == counted && point->n == count;
}

/// SIGKILL from the process itself: the same end as `kill -9` from outside, no cleanup.
[[noreturn]] void kill_now() {
  ::kill(::getpid(), SIGKILL);
  std::abort();  // not reached
}

/// Appends this process's pid as a line to the hold file (several processes may hold on one)
/// and waits (polling: the wait is for an event, its length does not matter) until a test removes
/// the file or a stop signal arrives.
void hold(const std::filesystem::path& file) {
  std::ofstream(file, std::ios::app) << ::getpid() << std::endl;
  std::error_code ignored;
  while (std::filesystem::exists(file, ignored) && !stop_requested())
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
}

}  // namespace

void test_point_after_step() {
  Points& p = points();
  if (!p.kill && !p.hold) return;
  ++p.steps;
  if (reached(p.kill, Counted::step, p.steps)) kill_now();
  if (reached(p.hold, Counted::step, p.steps)) hold(p.hold_file);
}

void test_point_after_body_check() {
  Points& p = points();
  if (!p.hold) return;
  ++p.body_checks;
  if (reached(p.hold, Counted::body_check, p.body_checks)) hold(p.hold_file);
}

int test_point_read_attempt() {
  Points& p = points();
  if (!p.read_failures) return 0;
  ++p.reads;
  const auto [first, count] = *p.read_failures;
  return p.reads >= first && p.reads < first + count ? EIO : 0;
}

int test_point_flock_error() {
  const char* value = std::getenv("TIDALCRUST_TEST_FLOCK_ERROR");
  if (!value || !*value) return 0;
  const std::string_view text(value);
  if (text == "ENOLCK") return ENOLCK;
  if (text == "EOPNOTSUPP") return EOPNOTSUPP;
  throw InputError(fmt::format("environment variable TIDALCRUST_TEST_FLOCK_ERROR='{}': expected ENOLCK or EOPNOTSUPP "
                               "(a testing aid)",
                               value));
}

long test_point_clock_skew() {
  const char* value = std::getenv("TIDALCRUST_TEST_CLOCK_SKEW");
  if (!value || !*value) return 0;
  long seconds = 0;
  const char* last = value + std::string_view(value).size();
  const auto [end, error] = std::from_chars(value, last, seconds);
  if (error != std::errc() || end != last)
    throw InputError(fmt::format("environment variable TIDALCRUST_TEST_CLOCK_SKEW='{}': expected whole seconds "
                                 "(a testing aid)",
                                 value));
  return seconds;
}

void test_point_mid_write() {
  Points& p = points();
  if (!p.kill) return;
  ++p.writes;
  if (reached(p.kill, Counted::write, p.writes)) kill_now();
}

}  // namespace tidalcrust
