// tidalcrust analyze --from ENC.h5 --out DIR: fracture statistics, paper-style figures and
// conservation diagnostics of one encounter (paper section 3).
#include <fmt/format.h>

#include <cxxopts.hpp>
#include <filesystem>
#include <string>

#include "stages/analysis_stage.hpp"
#include "io/checkpoint_file.hpp"
#include "cli/cli_options.hpp"
#include "cli/commands.hpp"
#include "base/errors.hpp"
#include "analysis/fracture_analysis.hpp"

namespace tidalcrust {

namespace fs = std::filesystem;

int command_analyze(int argc, char** argv) {
  cxxopts::Options options =
      command_options("analyze", "Snapshots ENC.snap-<step>.h5 beside ENC.h5 form the hemisphere snapshot row.");
  options.add_options()
      ("from", "encounter checkpoint (ENC.h5)", cxxopts::value<std::string>())
      ("out", "output folder for figures and summary.json", cxxopts::value<std::string>())
      ("no-figures", "write summary.json, cracks.json and figure_data.json without drawing the figures (as "
                     "[analysis] figures = false does for run)")
      ("h,help", "show this help");
  const auto parsed = parse_arguments(options, argc, argv);
  if (parsed.count("help")) {
    fmt::print("{}", options.help());
    return exit_ok;
  }
  if (!parsed.count("from")) throw InputError("--from ENC.h5 is required (see --help)");
  if (!parsed.count("out")) throw InputError("--out DIR is required (see --help)");
  const fs::path from = parsed["from"].as<std::string>();
  const fs::path out = parsed["out"].as<std::string>();

  const Checkpoint checkpoint = read_checkpoint(from);
  const bool with_figures = parsed.count("no-figures") == 0;
  const auto figures = analyze_encounter(from, checkpoint, out, with_figures);
  const std::string& name = stage_record<EncounterRecord>(checkpoint, from.string()).encounter.name;
  fmt::print("{}\n", fracture_summary_line(name.empty() ? from.stem().string() : name,
                                           analyze_fractures(checkpoint)));
  if (const std::string warning = failure_trend_line(name.empty() ? from.stem().string() : name, checkpoint);
      !warning.empty())
    fmt::print("warning: {}\n", warning);
  if (with_figures)
    fmt::print("wrote {} figures and summary.json to {}\n", figures.size(), out.string());
  else
    fmt::print("wrote summary.json to {} (no figures: --no-figures)\n", out.string());
  return exit_ok;
}

}  // namespace tidalcrust
