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
int command_build(int, char**) { return pending("build"); }
int command_stretch(int, char**) { return pending("stretch"); }
int command_relax(int, char**) { return pending("relax"); }
int command_encounter(int, char**) { return pending("encounter"); }
int command_analyze(int, char**) { return pending("analyze"); }
int command_compare(int, char**) { return pending("compare"); }
int command_estimate(int, char**) { return pending("estimate"); }

}  // namespace tidalcrust
