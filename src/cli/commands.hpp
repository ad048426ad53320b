#pragma once
// One function per subcommand of the command line (README "Command line").
// Each takes the arguments after the subcommand name (argv[0] is the subcommand) and returns
// the exit code; bad input is thrown as InputError and turned into exit code 2 by main().

namespace tidalcrust {

int command_run(int argc, char** argv);
int command_submit(int argc, char** argv);
int command_build(int argc, char** argv);
int command_stretch(int argc, char** argv);
int command_relax(int argc, char** argv);
int command_encounter(int argc, char** argv);
int command_analyze(int argc, char** argv);
int command_inspect(int argc, char** argv);
int command_compare(int argc, char** argv);
int command_estimate(int argc, char** argv);
int command_bench(int argc, char** argv);
int command_validate(int argc, char** argv);
int command_report(int argc, char** argv);

}  // namespace tidalcrust
