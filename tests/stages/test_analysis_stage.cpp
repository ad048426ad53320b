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
#include "model/config.hpp"
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

/// The configuration text of Tethys in SI (docs/moon.md), as a checkpoint stores it.
std::string tethys_config_toml() {
  return to_toml(parse_config(R"([workflow]
name = "tethys-si"
[moon]
preset = "tethys"
[resolution]
shell_level = 2
[[encounters]]
name = "T5"
perturber_mass = "3.1e20 kg"
pericenter = "977 km"
pericenter_speed = "0.447 km/s"
)",
                              "tethys-si.toml"));
}

bool near(const Json& value, double expected) {
  return value.is_number() && std::abs(value.get<double>() - expected) <= 1e-12 * std::abs(expected);
}

// A [moon] workflow's analysis gives summary.json's values in SI beside the model's (docs/moon.md,
// "Output in SI"), and figure data whose maps are planetocentric with a km scale and whose time
// axes are in hours; the same encounter without [moon] writes neither.
TEST(AnalysisStage, AMoonsSummaryAndFiguresAreInSiBesideTheModelUnits) {
  const ScratchFolder scratch("analysis_stage_si");
  Checkpoint c = synthetic_encounter(2);
  c.state.springs.failed[3] = c.state.springs.failed[4] = c.state.springs.failed[40] = 1;
  c.config_toml = tethys_config_toml();
  const fs::path file = scratch.path / "enc.h5", out = scratch.path / "analysis";
  write_checkpoint(file, c);
  analyze_encounter(file, c, out);
  const Json summary = Json::parse(read_file(out / "summary.json"));
  ASSERT_TRUE(summary.contains("si")) << summary.dump();
  EXPECT_EQ(summary.back(), summary["si"]);  // the new object last
  const Json& si = summary["si"];
  const double R_km = 531, M_kg = 0.62e21;
  const double t_grav_h = std::sqrt(531e3 * 531e3 * 531e3 / (6.674e-11 * M_kg)) / 3600;
  const double v_c_km_s = std::sqrt(6.674e-11 * M_kg / 531e3) / 1e3;
  EXPECT_EQ(si["moon"]["name"], "Tethys");
  EXPECT_TRUE(near(si["moon"]["radius_km"], R_km));
  EXPECT_TRUE(near(si["moon"]["mass_kg"], M_kg));
  EXPECT_TRUE(near(si["moon"]["t_grav_s"], t_grav_h * 3600));
  const Json& e = summary["encounter"];
  EXPECT_TRUE(near(si["encounter"]["perturber_mass_kg"], e["perturber_mass"].get<double>() * M_kg));
  EXPECT_TRUE(near(si["encounter"]["pericenter_km"], e["pericenter"].get<double>() * R_km));
  EXPECT_TRUE(near(si["encounter"]["min_distance_km"], e["min_distance"].get<double>() * R_km));
  EXPECT_TRUE(near(si["encounter"]["pericenter_speed_km_s"], e["pericenter_speed"].get<double>() * v_c_km_s));
  EXPECT_TRUE(near(si["time_from_pericenter_h"],
                   (summary["time"].get<double>() - e["pericenter_time"].get<double>()) * t_grav_h));
  const Json& failures = summary["failures"];
  ASSERT_GT(failures["total_crack_length"].get<double>(), 0);
  for (const char* key : {"largest_network_length", "largest_network_extent", "total_crack_length"})
    EXPECT_TRUE(near(si["failures"][std::string(key) + "_km"], failures[key].get<double>() * R_km)) << key;
  ASSERT_EQ(si["clusters"].size(), summary["clusters"].size());
  for (std::size_t k = 0; k < si["clusters"].size(); ++k)
    EXPECT_TRUE(near(si["clusters"][k]["length_km"], summary["clusters"][k]["length"].get<double>() * R_km));
  // Energies in J (null where the model's are: this record has no energy samples).
  ASSERT_EQ(si["energy"].size(), summary["energy"].size() - 1);  // all but the units text
  for (const auto& [key, value] : summary["energy"].items()) {
    if (key == "units") continue;
    EXPECT_TRUE(value.is_null() ? si["energy"][key + "_J"].is_null()
                                : near(si["energy"][key + "_J"], value.get<double>() * 6.674e-11 * M_kg * M_kg / 531e3))
        << key;
  }
  // Planetocentric longitude: 0 at the subsatellite point (90 in the orbital frame).
  const Json& lon = summary["failed_springs"]["longitude_deg"];
  ASSERT_EQ(si["failed_springs"]["planetocentric_longitude_deg"].size(), lon.size());
  for (std::size_t k = 0; k < lon.size(); ++k) {
    double expected = lon[k].get<double>() - 90;
    if (expected <= -180) expected += 360;
    EXPECT_DOUBLE_EQ(si["failed_springs"]["planetocentric_longitude_deg"][k].get<double>(), expected);
  }

  const Json data = Json::parse(read_file(out / "figure_data.json"));
  EXPECT_EQ(data["map"]["frame"], "planetocentric");
  EXPECT_EQ(data["map"]["longitude_shift_deg"], -90.0);
  EXPECT_EQ(data["map"]["subsatellite"], Json::array({0.0, 0}));
  EXPECT_EQ(data["map"]["scale_bar"]["length_km"], 200.0);  // a round length up to R/2
  EXPECT_TRUE(near(data["map"]["scale_bar"]["length_R"], 200 / R_km));
  EXPECT_EQ(data["map"]["scale_bar"]["label"], "200 km");
  EXPECT_EQ(data["time_axis"]["label"], "t \u2212 t_peri [h]");
  EXPECT_TRUE(near(data["time_axis"]["per_t_grav"], t_grav_h));
  EXPECT_TRUE(near(data["length_axis"]["per_R"], R_km));
  EXPECT_EQ(data["si"]["moon"], si["moon"]);
  const std::string map_title = data["titles"]["fracture_map"];
  EXPECT_NE(map_title.find("\nTethys: M\u2082 = 3.1e+20 kg, q = 977 km, V_q = 0.4466 km/s; dt = "), std::string::npos)
      << map_title;
  EXPECT_NE(map_title.find("largest crack network"), std::string::npos) << map_title;
  EXPECT_NE(map_title.find(" h (+"), std::string::npos) << map_title;  // hours, then t_grav
  EXPECT_TRUE(analysis_is_current(out, c));
  // An analysis of the moon written before the output in SI is redone.
  Json without = summary;
  without.erase("si");
  std::ofstream(out / "summary.json") << json_text(without);
  EXPECT_FALSE(analysis_is_current(out, c));

  // The same encounter without [moon]: no SI, maps in the orbital frame, time in t_grav.
  c.config_toml.clear();
  analyze_encounter(file, c, out);
  EXPECT_FALSE(Json::parse(read_file(out / "summary.json")).contains("si"));
  const Json model = Json::parse(read_file(out / "figure_data.json"));
  EXPECT_EQ(model["map"]["frame"], "orbital");
  EXPECT_EQ(model["map"]["subsatellite"], Json::array({90.0, 0}));
  EXPECT_EQ(model["time_axis"]["label"], "t \u2212 t_peri [t_grav]");
  EXPECT_TRUE(model["si"].is_null());
  EXPECT_TRUE(analysis_is_current(out, c));
}

}  // namespace
}  // namespace tidalcrust
