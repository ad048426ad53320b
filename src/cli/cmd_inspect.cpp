// tidalcrust inspect CKPT.h5 [--json | --fingerprint]: validate a checkpoint and summarise it.
#include <cxxopts.hpp>
#include <fmt/format.h>

#include <cstdio>
#include <string>
#include <vector>

#include "io/checkpoint_file.hpp"
#include "cli/cli_options.hpp"
#include "cli/commands.hpp"
#include "base/errors.hpp"
#include "analysis/inspect_report.hpp"

namespace tidalcrust {

int command_inspect(int argc, char** argv) {
  cxxopts::Options options = command_options("inspect");
  options.add_options()("json", "print one JSON object (values, their units, the full fingerprint)")(
      "fingerprint", "print the stage fingerprint's full text (the table shows its hash)")("h,help", "show this help")(
      "checkpoint", "checkpoint file", cxxopts::value<std::vector<std::string>>());
  options.parse_positional({"checkpoint"});
  options.positional_help("CKPT.h5");
  const auto parsed = parse_arguments(options, argc, argv);
  if (parsed.count("help")) {
    fmt::print("{}", options.help());
    return exit_ok;
  }
  if (!parsed.count("checkpoint") || parsed["checkpoint"].as<std::vector<std::string>>().size() != 1)
    throw InputError("expected exactly one checkpoint file (usage: tidalcrust inspect CKPT.h5 [--json | --fingerprint])");
  if (parsed.count("json") && parsed.count("fingerprint"))
    throw InputError("--json and --fingerprint exclude each other (the JSON holds the fingerprint)");
  const std::string file = parsed["checkpoint"].as<std::vector<std::string>>().front();

  const Checkpoint checkpoint = read_checkpoint(file);
  if (parsed.count("fingerprint")) {
    const std::string& text = checkpoint.stage.fingerprint;
    fmt::print("{}", text.empty()          ? "none (written by a single-stage command of an older version)\n"
                     : text.back() == '\n' ? text
                                           : text + "\n");
    return exit_ok;
  }
  const InspectReport report = build_inspect_report(checkpoint, file);
  fmt::print("{}", parsed.count("json") ? inspect_report_json(report) : inspect_report_table(report));
  return exit_ok;
}

}  // namespace tidalcrust
