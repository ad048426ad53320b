// tidalcrust: crustal failure on icy moons during strong tidal encounters.
#include <fmt/format.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <new>
#include <string>
#include <string_view>

#include "base/errors.hpp"
#include "build_info.hpp"
#include "cli/commands.hpp"
#include "io/stop_signal.hpp"

namespace {

/// "<path>: cannot create directories: Permission denied" from libstdc++'s "filesystem error:
/// cannot create directories: Permission denied [<path>]".
std::string filesystem_error_text(const std::filesystem::filesystem_error& err) {
  std::string what = err.what();
  if (what.starts_with("filesystem error: ")) what.erase(0, 18);
  if (const auto bracket = what.find(" ["); bracket != std::string::npos) what.erase(bracket);
  std::string paths = err.path1().string();
  if (!err.path2().empty()) paths += " -> " + err.path2().string();
  return paths.empty() ? what : paths + ": " + what;
}

}  // namespace

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
  } catch (const Interrupted& err) {
    fmt::print(stderr, "tidalcrust {}: {}\n", name, err.what());
    return exit_interrupted;
  } catch (const SimulationError& err) {
    fmt::print(stderr, "tidalcrust {}: simulation failed: {}\n", name, err.what());
    return exit_simulation_failure;
  } catch (const std::filesystem::filesystem_error& err) {
    // A folder that cannot be made or a file that cannot be removed (read-only, no space, no
    // permission): the user's environment, not a bug; one line naming the path.
    fmt::print(stderr, "tidalcrust {}: error: {}\n", name, filesystem_error_text(err));
    return exit_bad_input;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "tidalcrust {}: error: out of memory (the limit of this process, ulimit -v, or of the machine)\n",
               name);
    return exit_simulation_failure;
  } catch (const std::exception& err) {
    fmt::print(stderr, "tidalcrust {}: internal error: {}\n", name, err.what());
    return exit_simulation_failure;
  }
}
