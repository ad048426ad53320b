#pragma once
// The two kinds of failure a user can see, each with its exit code (README "Command line").
#include <stdexcept>
#include <string>

namespace tidalcrust {

/// Bad input: malformed or unknown configuration, value out of range, missing or corrupt
/// checkpoint, wrong stage order. The message names the file, key or dataset. Exit code 2.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The simulation itself failed (numerical blow-up). Exit code 1.
struct SimulationError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline constexpr int exit_ok = 0;
inline constexpr int exit_simulation_failure = 1;
inline constexpr int exit_bad_input = 2;
inline constexpr int exit_interrupted = 130;

}  // namespace tidalcrust
