// The analysis stage on a real encounter: the demo's "strong" encounter (workflows/quick-balanced.toml,
// the T5 orbit; quick.toml's cracks are all shorter than an arc needs) analysed into its folder; its summary.json carries the crack geometry
// (docs/crack-geometry.md) with finite values, and the crack-geometry figure.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/checkpoint_file.hpp"
#include "io/json.hpp"
#include "stages/analysis_stage.hpp"
#include "stages/encounter_stage.hpp"
#include "support/files.hpp"
#include "support/quick_workflow.hpp"
#include "support/synthetic_encounter.hpp"

namespace tidalcrust {
namespace {

namespace fs = std::filesystem;
using namespace test_support;

bool finite_number(const Json& value) { return value.is_number() && std::isfinite(value.get<double>()); }

TEST(AnalysisStage, SummaryOfAQuickEncounterHasTheCrackGeometry) {
  const ScratchFolder scratch("analysis_stage_quick");
  Config config = load_config(workflow_file("quick-balanced.toml"));
  config.relax.stability_probe = false;  // the probe runs on a copy: the relaxed state is the same
  Checkpoint relaxed = begin_relax(stretch_stage(build_stage(config), config), config);
  ASSERT_EQ(run_relax(relaxed, config, quiet_loop()), LoopOutcome::finished);
  Checkpoint c = begin_encounter(relaxed, config, config.find_encounter("strong"));
  const fs::path file = scratch.path / "strong.h5";
  ASSERT_EQ(run_encounter(c, config, quiet_loop(), file), LoopOutcome::finished);
  const fs::path out = scratch.path / "analysis";
  analyze_encounter(file, c, out);

  const Json summary = Json::parse(read_file(out / "summary.json"));
  // The new keys come last, in summary.json and in its failures object: the crust's (docs/crust.md),
  // for this uniform crust factors of exactly 1 and no weak or thin part.
  ASSERT_EQ(summary.back(), summary["crust"]);
  EXPECT_FALSE(summary["crust"]["varies"].get<bool>());
  EXPECT_EQ(summary["crust"]["thickness_factor_min"].get<double>(), 1.0);
  EXPECT_EQ(summary["crust"]["weak"]["springs"].get<int>(), 0);
  EXPECT_TRUE(summary["crust"]["weak"]["capture_ratio"].is_null());
  EXPECT_EQ(summary["failures"].back(), summary["failures"]["longest_arc_misfit_deg"]);
  const Json& failures = summary["failures"];
  std::printf("[ info ] quick-balanced strong: %s\n", failures.dump().c_str());
  ASSERT_GT(failures["count"].get<int>(), 30);
  for (const char* key : {"concentricity", "crack_rose_peak_deg", "median_arc_radius_deg",
                          "median_arc_pole_axis_from_subsatellite_deg", "longest_arc_radius_deg",
                          "longest_arc_pole_axis_from_subsatellite_deg", "longest_arc_span_deg",
                          "longest_arc_misfit_deg"})
    EXPECT_TRUE(finite_number(failures[key])) << key << ": " << failures[key];
  EXPECT_GT(failures["fitted_arcs"].get<int>(), 0);

  const Json& g = summary["crack_geometry"];
  ASSERT_EQ(g["arcs"].size(), failures["fitted_arcs"].get<std::size_t>());
  for (const Json& arc : g["arcs"]) {
    for (const char* key : {"length", "extent", "pole_longitude_deg", "pole_latitude_deg", "radius_deg", "arc_deg",
                            "arc_length", "rms_misfit_deg", "pole_from_subsatellite_deg",
                            "pole_axis_from_subsatellite_deg"})
      EXPECT_TRUE(finite_number(arc[key])) << key << ": " << arc;
    EXPECT_GE(arc["extent"].get<double>(), 0.5);
    EXPECT_GE(arc["springs"].get<int>(), 6);
    EXPECT_LE(arc["radius_deg"].get<double>(), 90.0);
    ASSERT_EQ(arc["pole"].size(), 3u);
  }
  EXPECT_TRUE(finite_number(g["concentricity"]));
  EXPECT_EQ(g["concentricity"], failures["concentricity"]);
  EXPECT_TRUE(finite_number(g["pole_axis_from_subsatellite"]["median_deg"]));
  EXPECT_EQ(g["rose"]["histogram"].size(), 18u);
  std::int64_t rose_total = 0;
  for (const Json& n : g["rose"]["histogram"]) rose_total += n.get<std::int64_t>();
  EXPECT_EQ(rose_total, g["rose"]["elements"].get<std::int64_t>());
  EXPECT_EQ(g["rose"]["elements"], failures["count"]);
  // One crack azimuth per failed spring, in [0, 180).
  ASSERT_EQ(summary["failed_springs"]["crack_azimuth_deg"].size(), failures["count"].get<std::size_t>());
  for (const Json& a : summary["failed_springs"]["crack_azimuth_deg"]) {
    ASSERT_TRUE(finite_number(a));
    EXPECT_GE(a.get<double>(), 0.0);
    EXPECT_LT(a.get<double>(), 180.0);
  }
  // Tidal cracks on the T5 orbit are concentric about the subsatellite point more than random.
  EXPECT_GT(failures["concentricity"].get<double>(), 0.7);
  EXPECT_TRUE(fs::exists(out / "crack_geometry.png"));
  EXPECT_TRUE(fs::exists(out / "crack_geometry.svg"));
}

// `run` reuses an analysis only when it is of this state and has the crack geometry: a summary.json
// written before it existed is redone.
TEST(AnalysisStage, AnAnalysisWithoutTheCrackGeometryIsNotCurrent) {
  const ScratchFolder scratch("analysis_stage_current");
  Checkpoint c = synthetic_encounter(2);
  c.state.springs.failed[3] = 1;
  const fs::path file = scratch.path / "enc.h5", out = scratch.path / "analysis";
  write_checkpoint(file, c);
  analyze_encounter(file, c, out);
  EXPECT_TRUE(analysis_is_current(out, c));
  Json summary = Json::parse(read_file(out / "summary.json"));
  summary.erase("crack_geometry");
  std::ofstream(out / "summary.json") << json_text(summary);
  EXPECT_FALSE(analysis_is_current(out, c));
}

// cracks.json: the clusters of summary.json with one polyline per failed spring; an analysis
// without it (written before it existed) is redone.
TEST(AnalysisStage, CracksJsonHoldsTheClustersAndIsRequired) {
  const ScratchFolder scratch("analysis_stage_cracks");
  Checkpoint c = synthetic_encounter(2);
  c.state.springs.failed[3] = c.state.springs.failed[4] = 1;
  const fs::path file = scratch.path / "enc.h5", out = scratch.path / "analysis";
  write_checkpoint(file, c);
  analyze_encounter(file, c, out);
  const Json summary = Json::parse(read_file(out / "summary.json"));
  const Json cracks = Json::parse(read_file(out / "cracks.json"));
  EXPECT_EQ(cracks["format"], "tidalcrust-cracks");
  EXPECT_EQ(cracks["state_hash"], summary["state_hash"]);
  EXPECT_EQ(cracks["crack_count"], summary["failures"]["clusters"]);
  ASSERT_EQ(cracks["cracks"].size(), summary["clusters"].size());
  std::size_t springs = 0;
  for (std::size_t k = 0; k < cracks["cracks"].size(); ++k) {
    const Json& crack = cracks["cracks"][k];
    EXPECT_EQ(crack["length"], summary["clusters"][k]["length"]);
    EXPECT_EQ(crack["springs"].size(), summary["clusters"][k]["springs"]);
    ASSERT_EQ(crack["polylines"].size(), crack["springs"].size());
    for (const Json& line : crack["polylines"]) {
      EXPECT_EQ(line.size(), 3u);  // face centroid, spring midpoint, face centroid
      for (const Json& vertex : line) {
        EXPECT_GT(vertex[0].get<double>(), -180.0);
        EXPECT_LE(vertex[0].get<double>(), 180.0);
        EXPECT_LE(std::abs(vertex[1].get<double>()), 90.0);
      }
    }
    springs += crack["springs"].size();
  }
  EXPECT_EQ(springs, 2u);
  EXPECT_TRUE(analysis_is_current(out, c));
  fs::remove(out / "cracks.json");
  EXPECT_FALSE(analysis_is_current(out, c));
}

}  // namespace
}  // namespace tidalcrust
