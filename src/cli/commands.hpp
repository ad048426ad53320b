#pragma once
// The commands of the command line, in one table (commands.cpp): `tidalcrust --help` lists them
// with their one-line summaries, main() dispatches on it, and each command's own --help starts
// with the same summary (command_options). The single-stage commands (build, stretch, relax,
// encounter) are rows of the stage table (stages/stage_kinds.hpp), run by command_stage.
// Each command takes the arguments after its name (argv[0] is the name) and returns the exit
// code; bad input is thrown as InputError and turned into exit code 2 by main().
#include <cxxopts.hpp>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace tidalcrust {

struct StageKind;

struct Command {
  std::string name;
  std::string summary;                  ///< one line
  std::function<int(int, char**)> run;
};

/// Every command, in the order `tidalcrust --help` lists them.
const std::vector<Command>& commands();
/// The command named `name`, or null.
const Command* find_command(std::string_view name);
/// The options of command `name` (which must be in the table): "tidalcrust NAME", its summary and,
/// below it, `details`.
cxxopts::Options command_options(std::string_view name, const std::string& details = "");
/// `tidalcrust --help`: the usage line, one line per command, --version and --help.
std::string command_list();

int command_run(int argc, char** argv);
int command_submit(int argc, char** argv);
int command_report(int argc, char** argv);
/// `tidalcrust build|stretch|relax|encounter`: one stage from a checkpoint (or, build, from the
/// configuration) into --out (cli/stage_command.cpp).
int command_stage(const StageKind& kind, int argc, char** argv);
int command_analyze(int argc, char** argv);
int command_inspect(int argc, char** argv);
int command_compare(int argc, char** argv);
int command_estimate(int argc, char** argv);
int command_bench(int argc, char** argv);
int command_validate(int argc, char** argv);
int command_config(int argc, char** argv);

}  // namespace tidalcrust
