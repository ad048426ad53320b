// tidalcrust: crustal failure on icy moons during strong tidal encounters.
#include <fmt/format.h>

#include <cstdio>
#include <cstring>
#include <exception>
#include <string_view>

#include "build_info.hpp"
#include "cli/commands.hpp"
#include "base/errors.hpp"

namespace {

void print_usage(std::FILE* to) {
  std::fputs(
      "usage: tidalcrust COMMAND [OPTIONS]\n"
      "  run WORKFLOW.toml [--out DIR] [--threads N] [--jobs N] [--dt-factor F] [--only NAME]... [--body-only]\n"
      "  submit WORKFLOW.toml --slurm [--partition P] [--time T] [--cpus-per-task C] [--max-running K]\n"
      "         [--account A] [--out DIR] [--dry-run]\n"
      "  report WORKFLOW.toml [--out DIR] [--dt-factor F]\n"
      "  build     --config WORKFLOW.toml --out BODY.h5\n"
      "  stretch   --from BODY.h5 --out STRETCHED.h5\n"
      "  relax     --from STRETCHED.h5 --out RELAXED.h5\n"
      "  encounter --from RELAXED.h5 --out ENC.h5 (--encounter NAME | --m2 M --q Q --vq V)\n"
      "  analyze   --from ENC.h5 --out DIR\n"
      "  inspect CKPT.h5 [--json | --fingerprint]\n"
      "  compare A.h5 B.h5 [--json]\n"
      "  compare --resolution A.h5 B.h5 [C.h5 ...] [--out DIR] [--json]\n"
      "  estimate [--body NAME | --mass KG --radius KM] [--json]\n"
      "  bench [--config WORKFLOW.toml] [--steps N] [--json]\n"
      "  validate WORKFLOW.toml [--out DIR] [--measure breathing,love,flexure,p-wave]\n"
      "  --version, --help\n"
      "Each command takes --help.\n",
      to);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace tidalcrust;
  if (argc < 2) {
    print_usage(stderr);
    return exit_bad_input;
  }
  if (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) {
    print_usage(stdout);
    return exit_ok;
  }
  if (std::strcmp(argv[1], "--version") == 0) {
    fmt::print("tidalcrust {} (commit {}; {}; {})\n", build_info::version, build_info::git_commit, build_info::compiler,
               build_info::build_flags);
    return exit_ok;
  }
  const std::string_view name = argv[1];
  struct Entry {
    std::string_view name;
    int (*run)(int, char**);
  };
  static const Entry entries[] = {
      {"run", command_run},         {"submit", command_submit},   {"build", command_build},     {"stretch", command_stretch},
      {"relax", command_relax},     {"encounter", command_encounter}, {"analyze", command_analyze},
      {"inspect", command_inspect}, {"compare", command_compare}, {"estimate", command_estimate},
      {"bench", command_bench}, {"validate", command_validate}, {"report", command_report}};
  for (const auto& entry : entries) {
    if (entry.name != name) continue;
    try {
      return entry.run(argc - 1, argv + 1);
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
  fmt::print(stderr, "tidalcrust: unknown command '{}'\n", name);
  print_usage(stderr);
  return exit_bad_input;
}
