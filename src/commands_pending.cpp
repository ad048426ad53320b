// Subcommands whose implementation has not landed yet. Each helper that implements one
// removes it from here and defines it in its own cmd_*.cpp file.
#include <fmt/format.h>

#include "commands.hpp"
#include "errors.hpp"

namespace tidalcrust {
namespace {
int pending(const char* name) {
  fmt::print(stderr, "tidalcrust {}: not implemented yet\n", name);
  return exit_simulation_failure;
}
}  // namespace

int command_run(int, char**) { return pending("run"); }
int command_encounter(int, char**) { return pending("encounter"); }

}  // namespace tidalcrust
