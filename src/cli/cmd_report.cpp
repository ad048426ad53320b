// `tidalcrust report WORKFLOW.toml`: the table of every encounter of a workflow (CSV and JSON)
// and its phase diagrams, from the checkpoints `run` wrote (analysis/sweep_report.hpp).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <utility>

#include "analysis/sweep_report.hpp"
#include "base/errors.hpp"
#include "cli/cli_options.hpp"
#include "cli/commands.hpp"
#include "analysis/plot_data.hpp"
#include "figures/figure_script.hpp"
#include "io/atomic_file.hpp"
#include "io/json.hpp"
#include "stages/workflow.hpp"

namespace tidalcrust {

namespace fs = std::filesystem;

namespace {

/// A number as it appears in a file name (as in sweep encounter names): shortest form, no '+'.
std::string file_number(double v) {
  std::string text = fmt::format("{}", v);
  std::erase(text, '+');
  return text;
}

std::string q_text(double q) { return std::isfinite(q) ? fmt::format("{:g}", q) : "-"; }

}  // namespace

int command_report(int argc, char** argv) {
  cxxopts::Options options =
      command_options("report", "The table as CSV and JSON; unfinished or missing encounters are listed as such.");
  options.positional_help("WORKFLOW.toml");
  options.add_options()("workflow", "workflow TOML file", cxxopts::value<std::string>())(
      "out", "the output root run used (default checkpoints/<workflow name>)", cxxopts::value<std::string>())(
      "dt-factor", "report the encounters run at this dt factor (run --dt-factor)",
      cxxopts::value<double>()->default_value("1.0"))(
      "set", "override one value as run did: section.key=value (repeatable)",
      cxxopts::value<std::vector<std::string>>())("h,help", "show this help");
  options.parse_positional({"workflow"});
  auto parsed = parse_arguments(options, argc, argv);
  if (parsed.count("help")) return fmt::print("{}\n", options.help()), exit_ok;
  const WorkflowArguments w = read_workflow_arguments(parsed);
  // The time step as run resolved it (chosen from the stretched body for a [material] body).
  const SweepReport report = build_sweep_report(w.config, w.root, w.dt_factor, [&](const Encounter* encounter) {
    return body_chain_config(w.config, w.root, encounter);
  });
  const fs::path dir = report.folder / "report";
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw InputError(fmt::format("{}: cannot create the report folder: {}", dir.string(), ec.message()));
  write_file_atomically(dir / "sweep.csv", sweep_report_csv(report));
  write_file_atomically(dir / "sweep.json", json_text(sweep_report_json(report)));
  if (!report.ensembles.empty()) {
    write_file_atomically(dir / "ensembles.csv", ensemble_report_csv(report));
    write_file_atomically(dir / "ensembles.json", json_text(ensemble_report_json(report)));
  }
  // One phase diagram per (M2, eps_S) of the workflow; of an ensemble, its encounters before the
  // expansion coloured by the share of members that cracked.
  const SweepReport drawn = report.ensembles.empty() ? report : crack_probability_report(report);
  std::map<std::pair<double, double>, bool> groups;
  for (const auto& r : drawn.rows) groups[{r.encounter.perturber_mass, r.failure_strain}] = true;
  Json diagrams = Json::object();
  std::vector<std::string> figures;
  for (const auto& [key, unused] : groups) {
    const std::string stem = fmt::format("phase_M{}_eps{}", file_number(key.first), file_number(key.second));
    diagrams[stem] = phase_diagram_json((dir / stem).string(), drawn, key.first, key.second, !report.ensembles.empty());
    figures.push_back(stem + ".png"), figures.push_back(stem + ".svg");
  }
  write_figure_data_file(dir, diagrams);
  draw_figures("report", {dir.string()});

  fmt::print("report of workflow {} ({} encounters in {}):\n", report.workflow, report.rows.size(),
             report.folder.string());
  for (const auto status : {SweepStatus::finished, SweepStatus::unfinished, SweepStatus::missing, SweepStatus::stale,
                            SweepStatus::unreadable}) {
    std::vector<std::string> names;
    for (const auto& r : report.rows)
      if (r.status == status) names.push_back(r.note.empty() ? r.encounter.name : r.encounter.name + " (" + r.note + ")");
    if (names.empty()) continue;
    if (status == SweepStatus::finished)
      fmt::print("  finished: {}\n", names.size());
    else
      fmt::print("  {}: {}: {}\n", status_name(status), names.size(), fmt::join(names, ", "));
  }
  for (const auto& e : report.ensembles) {
    const auto stat = [&](std::string_view name) {
      for (std::size_t i = 0; i < e.statistics.size(); ++i)
        if (ensemble_statistics()[i].name == name) return e.statistics[i];
      return SampleSummary{};
    };
    const SampleSummary failures = stat("failures"), length = stat("total_crack_length");
    if (failures.count < 2) {  // no spread yet: the values, not NaNs
      fmt::print("  ensemble {}: {} of {} members finished, {} cracked{}\n", e.encounter.name, e.finished, e.members,
                 e.cracked.successes,
                 failures.count == 1 ? fmt::format("; failed springs {:.0f}, total crack length {:.3g} R (one member: "
                                                   "no spread yet)", failures.mean, length.mean)
                                     : std::string());
      continue;
    }
    fmt::print("  ensemble {}: {} of {} members finished, {} cracked; failed springs {:.1f} +- {:.1f} [{:.1f}, {:.1f}], "
               "total crack length {:.3g} +- {:.2g} R [{:.3g}, {:.3g}] (mean +- sd [95% interval of the mean])\n",
               e.encounter.name, e.finished, e.members, e.cracked.successes, failures.mean, failures.standard_deviation,
               failures.low, failures.high, length.mean, length.standard_deviation, length.low, length.high);
  }
  for (const auto& b : report.boundaries)
    fmt::print("  M2 = {:g}, eps_S = {:g}, V_q = {:g}: cracked up to q = {}, intact from q = {}; eq. 5 strain = eps_S "
               "at q = {:.3g}\n",
               b.perturber_mass, b.failure_strain, b.pericenter_speed, q_text(b.largest_cracked_q),
               q_text(b.smallest_intact_q), b.eq5_q);
  for (const auto& b : report.boundaries)
    if (std::isfinite(b.half_probability_q))
      fmt::print("  M2 = {:g}, eps_S = {:g}, V_q = {:g}: half the members crack at q = {:.4g} (95% range {} to {})\n",
                 b.perturber_mass, b.failure_strain, b.pericenter_speed, b.half_probability_q,
                 q_text(b.half_probability_q_low), q_text(b.half_probability_q_high));
  if (!report.ensembles.empty())
    fmt::print("ensemble table: {}, {}\n", (dir / "ensembles.csv").string(), (dir / "ensembles.json").string());
  fmt::print("table: {}, {}\nphase diagrams: {} in {}\n", (dir / "sweep.csv").string(), (dir / "sweep.json").string(),
             fmt::join(figures, ", "), dir.string());
  return exit_ok;
}

}  // namespace tidalcrust
