// tidalcrust: crustal failure on icy moons during strong tidal encounters.
#include <fmt/format.h>

#include <cstdio>
#include <exception>
#include <string_view>

#include "base/errors.hpp"
#include "build_info.hpp"
#include "cli/commands.hpp"

int main(int argc, char** argv) {
  using namespace tidalcrust;
  if (argc < 2) {
    std::fputs(command_list().c_str(), stderr);
    return exit_bad_input;
  }
  const std::string_view name = argv[1];
  if (name == "--help" || name == "-h") {
    std::fputs(command_list().c_str(), stdout);
    return exit_ok;
  }
  if (name == "--version") {
    fmt::print("tidalcrust {} (commit {}; {}; {})\n", build_info::version, build_info::git_commit, build_info::compiler,
               build_info::build_flags);
    return exit_ok;
  }
  const Command* command = find_command(name);
  if (!command) {
    fmt::print(stderr, "tidalcrust: unknown command '{}'\n", name);
    std::fputs(command_list().c_str(), stderr);
    return exit_bad_input;
  }
  try {
    return command->run(argc - 1, argv + 1);
  } catch (const InputError& err) {
    fmt::print(stderr, "tidalcrust {}: error: {}\n", name, err.what());
    return exit_bad_input;
  } catch (const SimulationError& err) {
    fmt::print(stderr, "tidalcrust {}: simulation failed: {}\n", name, err.what());
    return exit_simulation_failure;
  } catch (const std::exception& err) {
    fmt::print(stderr, "tidalcrust {}: internal error: {}\n", name, err.what());
    return exit_simulation_failure;
  }
}
