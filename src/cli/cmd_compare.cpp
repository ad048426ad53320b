// tidalcrust compare A.h5 B.h5 [--json]: how alike the fractures of two encounters of one body are.
// tidalcrust compare --resolution A.h5 B.h5 [C.h5 ...] [--out DIR] [--json]: one encounter at
// several shell levels, the convergence table (analysis/resolution_study.hpp) and fracture maps.
// tidalcrust compare --ensembles A/report/ensembles.json B/report/ensembles.json [--pair NA:NB] [--json]: whether
// two ensembles' statistics differ beyond their spread (Welch, analysis/ensemble_statistics.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cxxopts.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "io/checkpoint_file.hpp"
#include "cli/cli_options.hpp"
#include "cli/commands.hpp"
#include "base/errors.hpp"
#include "analysis/fracture_comparison.hpp"
#include "analysis/resolution_study.hpp"
#include "analysis/sweep_report.hpp"
#include "analysis/figure_text.hpp"
#include "analysis/plot_data.hpp"
#include "figures/figure_script.hpp"
#include "io/atomic_file.hpp"
#include "io/json.hpp"
#include "io/state_hash.hpp"

namespace tidalcrust {
namespace {

Json side_json(const std::string& file, const Checkpoint& c, const FractureSummary& f) {
  return {{"file", file},
          {"stage", c.stage.name()},
          {"encounter", c.stage.as<EncounterRecord>().encounter.name},
          {"time", c.state.time},
          {"step", c.state.step},
          {"state_hash", state_hash(c.state)},
          {"failures", failure_summary_json(f)}};
}

std::string number(double v, const char* format = "{:.4g}") {
  return std::isfinite(v) ? fmt::format(fmt::runtime(format), v) : "n/a";
}

std::string level_text(const ResolutionRow& r) { return r.shell_level >= 0 ? std::to_string(r.shell_level) : "?"; }

void print_resolution_table(const ResolutionStudy& study) {
  fmt::print("resolution study of encounter {}: M2 = {} M, q = {} R, V_q = {} sqrt(GM/R), eps_S = {}, {} rule\n",
             study.encounter.name, study.encounter.perturber_mass, study.encounter.pericenter,
             study.encounter.pericenter_speed, study.failure_strain, choice_name(study.failure_rule));
  const auto line = [](const auto&... cells) {
    fmt::print("{:>5} {:>7} {:>9} {:>9} {:>7} {:>9} {:>10} {:>9} {:>8} {:>10} {:>8} {:>8} {:>8} {:>8}\n", cells...);
  };
  line("level", "N_S", "particles", "dt", "failed", "area", "total", "largest", "clusters", "hemisphere",
       "median", "d area", "d hemi", "d crack");
  line("", "", "", "[t_grav]", "springs", "fraction", "crack", "crack [R]", "", "fraction", "ang [deg]", "[%]", "[%]",
       "[%]");
  for (const auto& r : study.rows) {
    const FractureSummary& f = r.fractures;
    line(level_text(r), r.shell_nodes, r.particles, number(r.dt), f.count(), number(f.failed_area_fraction),
         number(f.total_crack_length), number(f.longest_crack_length), f.clusters.size(),
         number(f.hemisphere_fraction), number(f.median_angle_from_subsatellite_deg, "{:.1f}"),
         number(r.area_fraction_change_percent, "{:+.1f}"), number(r.hemisphere_fraction_change_percent, "{:+.1f}"),
         number(r.crack_length_change_percent, "{:+.1f}"));
  }
  for (const auto& r : study.rows) fmt::print("level {}: {}  state_hash {}\n", level_text(r), r.file, r.state_hash);
  fmt::print("d area, d hemi, d crack: change of the failed area fraction, the hemisphere fraction and the total crack "
             "length from the row above (the area is L_S / 2 x the crack length: it halves with L_S)\n");
}

/// DIR/convergence.json, convergence.csv and convergence_maps.png/.svg; returns the files written.
std::vector<std::filesystem::path> write_resolution_outputs(const ResolutionStudy& study,
                                                            const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw InputError(fmt::format("{}: cannot create the output folder: {}", dir.string(),
                                 ec ? ec.message() : "a file of that name exists"));
  write_file_atomically(dir / "convergence.json", json_text(resolution_study_json(study)));
  write_file_atomically(dir / "convergence.csv", resolution_study_csv(study));
  std::vector<const FractureSummary*> panels;
  std::vector<std::string> titles, hashes;
  for (const auto& r : study.rows) {
    panels.push_back(&r.fractures);
    hashes.push_back(r.state_hash);
    titles.push_back(fmt::format("level {}, N_S = {}: {:.1f}% of the area failed", level_text(r), r.shell_nodes,
                                 100 * r.fractures.failed_area_fraction));
  }
  const std::string title = fmt::format("{}: fracture maps by shell level\n{}; eps_S = {}, {} failure rule",
                                        study.encounter.name, encounter_parameters_text(study.encounter),
                                        general_text(study.failure_strain), choice_name(study.failure_rule));
  std::vector<std::filesystem::path> written{dir / "convergence.json", dir / "convergence.csv"};
  written.push_back(write_figure_data_file(
      dir, {{"convergence_maps", fracture_map_row_json((dir / "convergence_maps").string(), panels, hashes, titles, title)}}));
  draw_figures("compare", {dir.string()});
  for (const char* extension : {".png", ".svg"}) written.push_back(dir / (std::string("convergence_maps") + extension));
  return written;
}

int compare_resolutions(const cxxopts::ParseResult& parsed, const std::vector<std::string>& files) {
  const ResolutionStudy study = build_resolution_study(files);
  std::vector<std::filesystem::path> written;
  if (parsed.count("out")) written = write_resolution_outputs(study, parsed["out"].as<std::string>());
  if (parsed.count("json")) {
    fmt::print("{}", json_text(resolution_study_json(study)));
    return exit_ok;
  }
  print_resolution_table(study);
  for (const auto& f : written) fmt::print("wrote {}\n", f.string());
  return exit_ok;
}

/// The ensemble named `name` of the table read from `file`; InputError naming both otherwise.
const StoredEnsemble& ensemble_named(const std::vector<StoredEnsemble>& table, const std::string& file,
                                     const std::string& name) {
  const auto e = std::find_if(table.begin(), table.end(), [&](const StoredEnsemble& x) { return x.name == name; });
  if (e == table.end()) throw InputError(fmt::format("{}: no ensemble named '{}'", file, name));
  return *e;
}

/// Every ensemble of A also in B (by name, finished members on both sides), or the pairs --pair
/// names, statistic by statistic.
int compare_ensembles(const cxxopts::ParseResult& parsed, const std::vector<std::string>& files) {
  if (files.size() != 2)
    throw InputError(fmt::format("compare --ensembles: expected two ensemble tables A.json B.json, got {}", files.size()));
  const std::vector<StoredEnsemble> a = read_ensemble_report(files[0]), b = read_ensemble_report(files[1]);
  Json out = {{"a", files[0]}, {"b", files[1]}, {"confidence", ensemble_confidence},
              {"method", "Welch's t test (unequal variances, Welch-Satterthwaite degrees of freedom) on the members"},
              {"ensembles", Json::array()}};
  const auto json_number = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
  std::vector<std::pair<const StoredEnsemble*, const StoredEnsemble*>> pairs;
  if (parsed.count("pair")) {
    for (const std::string& pair : parsed["pair"].as<std::vector<std::string>>()) {
      const auto colon = pair.find(':');
      if (colon == std::string::npos || colon == 0 || colon + 1 == pair.size())
        throw InputError(fmt::format("--pair '{}': expected NAME_IN_A:NAME_IN_B", pair));
      pairs.emplace_back(&ensemble_named(a, files[0], pair.substr(0, colon)),
                         &ensemble_named(b, files[1], pair.substr(colon + 1)));
    }
  } else {
    // An ensemble with no finished member on one side has nothing to compare (a workflow run with
    // --only leaves its other encounters' ensembles empty).
    for (const StoredEnsemble& ea : a)
      for (const StoredEnsemble& eb : b)
        if (eb.name == ea.name && ea.finished > 0 && eb.finished > 0) pairs.emplace_back(&ea, &eb);
  }
  for (const auto& [pa, eb] : pairs) {
    const StoredEnsemble& ea = *pa;
    const std::string name = ea.name == eb->name ? ea.name : ea.name + " vs " + eb->name;
    Json rows = Json::array();
    if (!parsed.count("json"))
      fmt::print("ensemble {} ({} members in A, {} in B): mean +- sd; B - A with its 95% interval\n", name, ea.finished,
                 eb->finished);
    for (std::size_t i = 0; i < ensemble_statistics().size(); ++i) {
      const SampleSummary &sa = ea.statistics[i], &sb = eb->statistics[i];
      const MeanDifference d = compare_means(sa, sb);
      const std::string verdict = !std::isfinite(d.p_value) ? "n/a" : d.beyond_noise ? "differs" : "within the noise";
      rows.push_back({{"statistic", ensemble_statistics()[i].name}, {"unit", ensemble_statistics()[i].unit},
                      {"a_mean", json_number(sa.mean)}, {"a_sd", json_number(sa.standard_deviation)},
                      {"b_mean", json_number(sb.mean)}, {"b_sd", json_number(sb.standard_deviation)},
                      {"difference", json_number(d.difference)}, {"low", json_number(d.low)},
                      {"high", json_number(d.high)}, {"p_value", json_number(d.p_value)},
                      {"beyond_noise", d.beyond_noise}});
      if (!parsed.count("json"))
        fmt::print("  {:<22} A {:>10} +- {:<9} B {:>10} +- {:<9} B - A {:>10} [{}, {}]  p = {}  {}\n",
                   fmt::format("{} [{}]", ensemble_statistics()[i].name, ensemble_statistics()[i].unit),
                   number(sa.mean), number(sa.standard_deviation, "{:.2g}"), number(sb.mean),
                   number(sb.standard_deviation, "{:.2g}"), number(d.difference, "{:+.4g}"), number(d.low), number(d.high),
                   number(d.p_value, "{:.2g}"), verdict);
    }
    out["ensembles"].push_back({{"name", name}, {"a_members", ea.finished}, {"b_members", eb->finished},
                                {"statistics", rows}});
  }
  if (out["ensembles"].empty())
    throw InputError(fmt::format("{} and {} have no ensemble of the same name with finished members on both sides",
                                 files[0], files[1]));
  if (parsed.count("json")) fmt::print("{}", json_text(out));
  return exit_ok;
}

}  // namespace

int command_compare(int argc, char** argv) {
  cxxopts::Options options =
      command_options("compare",
                      "Two checkpoints: overlap of failed springs (Jaccard index), angular distributions about the\n"
                      "subsatellite point (Kolmogorov-Smirnov distance), cracks and state hashes.\n"
                      "With --resolution: the same encounter at several shell levels (two or more\n"
                      "checkpoints, any order), a convergence table and, with --out, its files.\n"
                      "With --ensembles: two report/ensembles.json files, whether each statistic of the\n"
                      "ensembles of the same name (or the pairs --pair names) differs beyond the members'\n"
                      "spread (Welch's t test).");
  options.add_options()
      ("json", "print one JSON object")
      ("resolution", "compare one encounter at several resolutions: rows sorted by shell node count")
      ("ensembles", "compare two ensemble tables (report/ensembles.json): every statistic, Welch's t test")
      ("out", "with --resolution: write DIR/convergence.json, convergence.csv, convergence_maps.png/.svg",
       cxxopts::value<std::string>())
      ("pair", "with --ensembles: compare ensemble NAME_A of A with NAME_B of B (NAME_A:NAME_B, repeatable)",
       cxxopts::value<std::vector<std::string>>())
      ("h,help", "show this help")
      ("files", "A.h5 B.h5", cxxopts::value<std::vector<std::string>>());
  options.parse_positional({"files"});
  options.positional_help("A.h5 B.h5 | --resolution A.h5 B.h5 [C.h5 ...] | --ensembles A.json B.json");
  const auto parsed = parse_arguments(options, argc, argv);
  if (parsed.count("help")) {
    fmt::print("{}", options.help());
    return exit_ok;
  }
  const auto files = parsed.count("files") ? parsed["files"].as<std::vector<std::string>>() : std::vector<std::string>{};
  if (parsed.count("resolution") && parsed.count("ensembles"))
    throw InputError("compare: --resolution and --ensembles exclude each other");
  if (parsed.count("resolution")) {
    if (parsed.count("pair")) throw InputError("compare: --pair is for --ensembles only (see --help)");
    return compare_resolutions(parsed, files);
  }
  if (parsed.count("ensembles")) {
    if (parsed.count("out")) throw InputError("compare: --out is for --resolution only (see --help)");
    return compare_ensembles(parsed, files);
  }
  if (parsed.count("out")) throw InputError("compare: --out is for --resolution only (see --help)");
  if (parsed.count("pair")) throw InputError("compare: --pair is for --ensembles only (see --help)");
  if (files.size() != 2) throw InputError(fmt::format("expected two checkpoint files A.h5 B.h5, got {} (see --help)", files.size()));

  const Checkpoint a = read_checkpoint(files[0]);
  const Checkpoint b = read_checkpoint(files[1]);
  for (const auto& [c, file] : {std::pair{&a, &files[0]}, std::pair{&b, &files[1]}})
    stage_record<EncounterRecord>(*c, *file);
  require_same_body(a.body, b.body, files[0], files[1]);
  const FractureComparison r = compare_fractures(a.body, a.state, b.state);

  if (parsed.count("json")) {
    const Json json = {{"a", side_json(files[0], a, r.a)},
                       {"b", side_json(files[1], b, r.b)},
                       {"same_body", true},
                       {"identical_state", state_hash(a.state) == state_hash(b.state)},
                       {"common_failed", r.common_failed},
                       {"either_failed", r.either_failed},
                       {"jaccard", r.jaccard},
                       {"ks_distance_angle_from_subsatellite", r.ks_distance}};
    fmt::print("{}", json_text(json));
    return exit_ok;
  }
  fmt::print("{:<34} {:>16} {:>16}\n", "", "A", "B");
  auto row = [](const char* name, const std::string& x, const std::string& y) { fmt::print("{:<34} {:>16} {:>16}\n", name, x, y); };
  row("time [t_grav]", number(a.state.time, "{:.6g}"), number(b.state.time, "{:.6g}"));
  row("step", fmt::format("{}", a.state.step), fmt::format("{}", b.state.step));
  row("failed shell springs", fmt::format("{}", r.a.count()), fmt::format("{}", r.b.count()));
  row("fraction of shell springs", number(r.a.fraction_shell), number(r.b.fraction_shell));
  row("failed area fraction", number(r.a.failed_area_fraction), number(r.b.failed_area_fraction));
  row("subsatellite hemisphere fraction", number(r.a.hemisphere_fraction), number(r.b.hemisphere_fraction));
  row("mean angle from subsatellite [deg]", number(r.a.mean_angle_from_subsatellite_deg, "{:.2f}"),
      number(r.b.mean_angle_from_subsatellite_deg, "{:.2f}"));
  row("median angle from subsatellite [deg]", number(r.a.median_angle_from_subsatellite_deg, "{:.2f}"),
      number(r.b.median_angle_from_subsatellite_deg, "{:.2f}"));
  row("cracks (clusters)", fmt::format("{}", r.a.clusters.size()), fmt::format("{}", r.b.clusters.size()));
  row("largest crack network [R]", number(r.a.longest_crack_length), number(r.b.longest_crack_length));
  row("largest network extent [R]", number(r.a.longest_crack_extent), number(r.b.longest_crack_extent));
  row("total crack length [R]", number(r.a.total_crack_length), number(r.b.total_crack_length));
  fmt::print("A: {}  state_hash {}\nB: {}  state_hash {}\n", files[0], state_hash(a.state), files[1], state_hash(b.state));
  fmt::print("failed in both {}, in either {}: Jaccard index {}\n", r.common_failed, r.either_failed, number(r.jaccard));
  fmt::print("Kolmogorov-Smirnov distance of the angle-from-subsatellite distributions: {}\n", number(r.ks_distance));
  return exit_ok;
}

}  // namespace tidalcrust
