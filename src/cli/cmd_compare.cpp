// tidalcrust compare A.h5 B.h5 [--json]: how alike the fractures of two encounters of one body are.
#include <fmt/format.h>

#include <cmath>
#include <cxxopts.hpp>
#include <string>
#include <vector>

#include "io/checkpoint_file.hpp"
#include "cli/cli_options.hpp"
#include "cli/commands.hpp"
#include "base/errors.hpp"
#include "analysis/fracture_comparison.hpp"
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

}  // namespace

int command_compare(int argc, char** argv) {
  cxxopts::Options options("tidalcrust compare",
                           "Compare the fractures of two encounter checkpoints branched from the same body:\n"
                           "overlap of failed springs (Jaccard index), angular distributions about the\n"
                           "subsatellite point (Kolmogorov-Smirnov distance), cracks and state hashes.");
  options.add_options()
      ("json", "print one JSON object")
      ("h,help", "show this help")
      ("files", "A.h5 B.h5", cxxopts::value<std::vector<std::string>>());
  options.parse_positional({"files"});
  options.positional_help("A.h5 B.h5");
  const auto parsed = parse_arguments(options, argc, argv);
  if (parsed.count("help")) {
    fmt::print("{}", options.help());
    return exit_ok;
  }
  const auto files = parsed.count("files") ? parsed["files"].as<std::vector<std::string>>() : std::vector<std::string>{};
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
  row("subsatellite hemisphere fraction", number(r.a.hemisphere_fraction), number(r.b.hemisphere_fraction));
  row("mean angle from subsatellite [deg]", number(r.a.mean_angle_from_subsatellite_deg, "{:.2f}"),
      number(r.b.mean_angle_from_subsatellite_deg, "{:.2f}"));
  row("median angle from subsatellite [deg]", number(r.a.median_angle_from_subsatellite_deg, "{:.2f}"),
      number(r.b.median_angle_from_subsatellite_deg, "{:.2f}"));
  row("cracks (clusters)", fmt::format("{}", r.a.clusters.size()), fmt::format("{}", r.b.clusters.size()));
  row("longest crack [R]", number(r.a.longest_crack_length), number(r.b.longest_crack_length));
  row("longest crack extent [R]", number(r.a.longest_crack_extent), number(r.b.longest_crack_extent));
  fmt::print("A: {}  state_hash {}\nB: {}  state_hash {}\n", files[0], state_hash(a.state), files[1], state_hash(b.state));
  fmt::print("failed in both {}, in either {}: Jaccard index {}\n", r.common_failed, r.either_failed, number(r.jaccard));
  fmt::print("Kolmogorov-Smirnov distance of the angle-from-subsatellite distributions: {}\n", number(r.ks_distance));
  return exit_ok;
}

}  // namespace tidalcrust
