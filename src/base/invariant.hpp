#pragma once
// TIDALCRUST_ASSERT: the check of an internal invariant. Which error to use (docs/architecture.md,
// "Errors"):
// - InputError (base/errors.hpp, exit 2): what a user gave us is wrong: a configuration file, an
//   option, a checkpoint or folder named on the command line. Thrown only where that input is
//   read or checked, with a message naming the file, key or dataset.
// - SimulationError (base/errors.hpp, exit 1): valid input, but the run itself failed (a blow-up).
// - TIDALCRUST_ASSERT (here; exit 1, "internal error: <what> (<file>:<line>)"): a broken internal
//   invariant, something the code before the check guarantees (the sizes of a body and its
//   state, indices the checkpoint reader has checked, the arguments one function passes
//   another). A bug, never the user's doing.
#include <stdexcept>
#include <string>
#include <string_view>

namespace tidalcrust {

/// A broken internal invariant (a bug, not bad input), thrown by TIDALCRUST_ASSERT with the
/// message "<what> (<file>:<line>)". src/cli/main.cpp prints "internal error: <message>" and
/// exits with code 1 (exit_simulation_failure).
struct InternalError : std::logic_error {
  using std::logic_error::logic_error;
};

/// Throws InternalError "<what> (<file>:<line>)", with `file` from its src/, stages/ or tests/
/// folder on (not the build machine's absolute path).
[[noreturn]] inline void fail_invariant(std::string_view what, std::string_view file, int line) {
  for (std::string_view root : {"/src/", "/stages/", "/tests/"})
    if (const auto at = file.rfind(root); at != std::string_view::npos) {
      file.remove_prefix(at + 1);
      break;
    }
  throw InternalError(std::string(what) + " (" + std::string(file) + ":" + std::to_string(line) + ")");
}

}  // namespace tidalcrust

/// Checks an internal invariant: when `condition` is false, throws InternalError "<what>
/// (<file>:<line>)". `what` (a string) is evaluated only then. Never compiled out (the checks
/// guard invariants whose failure would silently give wrong bits); not for user input, which gets
/// InputError where it is read.
#define TIDALCRUST_ASSERT(condition, what) \
  ((condition) ? static_cast<void>(0) : ::tidalcrust::fail_invariant((what), __FILE__, __LINE__))
