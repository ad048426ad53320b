#include "cli/commands.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "stages/stage_kinds.hpp"
#include "base/invariant.hpp"

namespace tidalcrust {

const std::vector<Command>& commands() {
  static const std::vector<Command> table = [] {
    std::vector<Command> out = {
        {"run", "Run a whole workflow; rerun the same command to resume.", command_run},
        {"submit", "Submit a workflow as Slurm jobs: the body chain, then a job array of its encounters.",
         command_submit},
        {"report", "Table and phase diagrams of the encounters of a workflow that run has computed.", command_report}};
    for (const StageKind& kind : stage_kinds())
      out.push_back({kind.name(), kind.summary,
                     [&kind](int argc, char** argv) { return command_stage(kind, argc, argv); }});
    const std::vector<Command> rest = {
        {"analyze", "Fracture statistics, figures (PNG + SVG) and summary.json of an encounter checkpoint.",
         command_analyze},
        {"inspect", "Validate a checkpoint and print its stage, counts, Table 3 quantities and conservation totals.",
         command_inspect},
        {"compare", "Compare the fractures of encounters: two checkpoints, one encounter at several resolutions, or two ensemble tables.", command_compare},
        {"estimate", "Physical units of a body (paper Table 1) and the impulse estimates of an encounter (section 1.1).",
         command_estimate},
        {"bench", "Time full integration steps of a body and the textbook step at the same N.", command_bench},
        {"validate", "Compare the relaxed body of a workflow with continuum elasticity.", command_validate},
        {"config", "Every configuration key with its default, unit, range, meaning and the stages that read it.",
         command_config}};
    out.insert(out.end(), rest.begin(), rest.end());
    return out;
  }();
  return table;
}

const Command* find_command(std::string_view name) {
  const auto& table = commands();
  const auto found = std::find_if(table.begin(), table.end(), [&](const Command& c) { return c.name == name; });
  return found == table.end() ? nullptr : &*found;
}

cxxopts::Options command_options(std::string_view name, const std::string& details) {
  const Command* command = find_command(name);
  TIDALCRUST_ASSERT(command != nullptr, fmt::format("command_options: '{}' is not in the command table", name));
  return cxxopts::Options(fmt::format("tidalcrust {}", name),
                          details.empty() ? command->summary : command->summary + "\n" + details);
}

std::string command_list() {
  std::size_t width = 0;
  for (const auto& c : commands()) width = std::max(width, c.name.size());
  std::string out = "usage: tidalcrust COMMAND [OPTIONS]\n\ncommands:\n";
  for (const auto& c : commands()) out += fmt::format("  {:<{}}  {}\n", c.name, width, c.summary);
  out += fmt::format("\n  {:<{}}  {}\n", "--version", width, "program version, commit, compiler and flags");
  out += fmt::format("  {:<{}}  {}\n", "--help", width, "this list");
  out += "Each command takes --help for its options.\n";
  return out;
}

}  // namespace tidalcrust
