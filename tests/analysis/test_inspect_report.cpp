// inspect's report of a checkpoint (analysis/inspect_report): every key, exact counts and totals,
// the stability section of a relaxed body, and the error for an unreadable stored configuration.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "analysis/inspect_report.hpp"
#include "base/errors.hpp"
#include "io/json.hpp"
#include "model/config.hpp"
#include "io/state_hash.hpp"
#include "physics/conservation.hpp"
#include "support/synthetic_checkpoint.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;

namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST(InspectReport, JsonHasEveryKeyOfTheDesign) {
  const Checkpoint c = synthetic_checkpoint();
  const std::string json = inspect_report_json(build_inspect_report(c, "synthetic.h5"));
  for (const char* key : {"format_version", "stage", "complete", "time", "step", "dt", "state_hash", "parent_hash",
                          "counts", "interior", "shell", "springs_interior", "springs_shell", "springs_cross",
                          "hinges", "faces", "failed", "derived", "E_I", "L_I", "k_I", "L_S", "k_S", "M_S", "L_C",
                          "k_C", "V_IP", "V_SP", "V_Co", "h_S", "E_2D", "D_F", "D_F_eq23", "dt_max", "dt_safe", "dt_unstable", "conservation", "momentum",
                          "angular_momentum", "kinetic_energy", "record", "fail_interval", "snapshot_steps", "perturber", "mass", "failures", "hemisphere_fraction", "mean_angle_from_subsatellite_deg", "largest_network_length", "clusters",
                          "min_distance", "speed_at_min"})
    EXPECT_TRUE(contains(json, "\"" + std::string(key) + "\": ")) << key;
  EXPECT_TRUE(contains(json, "\"state_hash\": \"" + state_hash(c.state) + "\""));
  EXPECT_TRUE(contains(json, "\"stage\": \"encounter\""));
  EXPECT_TRUE(contains(json, "\"name\": \"T5 synthetic \\\"test\\\" & <body>\""));
  EXPECT_FALSE(contains(json, "\"stability\""));
}

TEST(InspectReport, CountsAndTotalsAreExact) {
  const Checkpoint c = synthetic_checkpoint();
  const InspectReport r = build_inspect_report(c, "synthetic.h5");
  auto find = [&](const std::string& section, const std::string& key) -> const ReportValue& {
    for (const auto& s : r.sections)
      if (s.name == section)
        for (const auto& [k, v] : s.entries)
          if (k == key) return v;
    throw std::runtime_error("no " + section + "." + key);
  };
  EXPECT_EQ(find("counts", "interior").integer, 1);
  EXPECT_EQ(find("counts", "shell").integer, 4);
  EXPECT_EQ(find("counts", "springs_interior").integer, 0);
  EXPECT_EQ(find("counts", "springs_shell").integer, 6);
  EXPECT_EQ(find("counts", "springs_cross").integer, 4);
  EXPECT_EQ(find("counts", "hinges").integer, 3);
  EXPECT_EQ(find("counts", "faces").integer, 4);
  EXPECT_EQ(find("counts", "failed").integer, 1);
  const Conservation totals = measure_conservation(c.body, c.state);
  EXPECT_EQ(find("conservation", "kinetic_energy").number, totals.kinetic_energy);
  EXPECT_EQ(find("conservation", "momentum").numbers,
            std::vector<double>(totals.momentum.begin(), totals.momentum.end()));
  EXPECT_EQ(find("derived", "M_S").number, 0.5);
  EXPECT_EQ(find("derived", "k_S").number, 0.06);
  EXPECT_EQ(find("gravity", "method").text, "direct");  // the default
  EXPECT_EQ(find("perturber", "mass").number, 0.5);
  EXPECT_EQ(find("perturber", "min_distance").number, 1.84);
}

TEST(InspectReport, TreeGravityShowsItsTargetErrorAndOpeningAngle) {
  Checkpoint c = synthetic_checkpoint();
  Config config = parse_config(c.config_toml, "synthetic");
  config.gravity.method = GravityMethod::tree;
  config.gravity.force_error = 1e-3;
  c.config_toml = to_toml(config);
  const std::string json = inspect_report_json(build_inspect_report(c, "synthetic.h5"));
  EXPECT_TRUE(contains(json, "\"method\": \"tree\"")) << json;
  EXPECT_TRUE(contains(json, "\"force_error\": 0.001")) << json;
  EXPECT_TRUE(contains(json, "\"opening_angle\": ")) << json;
}

TEST(InspectReport, RelaxedBodyShowsStabilityAndNoPerturber) {
  Checkpoint c = synthetic_checkpoint();
  RelaxRecord relaxed;
  relaxed.probe_runs = 1;
  relaxed.probe_failures = 0;
  relaxed.probe_max_shell_strain = 0.0021;
  c.stage.record = relaxed;
  c.state.perturber = Perturber{};
  const std::string json = inspect_report_json(build_inspect_report(c, "relaxed.h5"));
  EXPECT_TRUE(contains(json, "\"stability\": {\n    \"failures\": 0,\n    \"max_shell_strain\": 0.0021\n  }"))
      << json;
  EXPECT_FALSE(contains(json, "\"perturber\""));
  const std::string table = inspect_report_table(build_inspect_report(c, "relaxed.h5"));
  EXPECT_TRUE(contains(table, "\nstability\n  failures  ")) << table;
}

TEST(InspectReport, UnparsableStoredConfigurationNamesTheDataset) {
  Checkpoint c = synthetic_checkpoint();
  c.config_toml = "[interior]\nradius = \"big\"\n";
  try {
    build_inspect_report(c, "odd.h5");
    ADD_FAILURE() << "no error";
  } catch (const InputError& err) {
    EXPECT_TRUE(contains(err.what(), "odd.h5:/parameters/config")) << err.what();
  }
}

TEST(InspectReport, EveryNumberHasAUnit) {
  const InspectReport r = build_inspect_report(synthetic_checkpoint(), "synthetic.h5");
  std::vector<const ReportSection*> sections{&r.top};
  for (const auto& s : r.sections) sections.push_back(&s);
  for (const ReportSection* s : sections)
    for (const auto& [key, v] : s->entries) {
      if (v.kind == ReportValue::Kind::integer || v.kind == ReportValue::Kind::number ||
          v.kind == ReportValue::Kind::numbers) {
        EXPECT_FALSE(v.unit.empty()) << s->name << "." << key;
      }
    }
  const std::string table = inspect_report_table(r);
  for (const char* line : {"\ndt ", "\n  pericenter ", "\n  pericenter_speed ", "\n  E_I ", "\n  momentum "}) {
    const auto at = table.find(line);
    ASSERT_NE(at, std::string::npos) << line << table;
    const std::string row = table.substr(at + 1, table.find('\n', at + 1) - at - 1);
    const std::string unit = std::string(line) == "\ndt "                  ? " t_grav"
                             : std::string(line) == "\n  pericenter "      ? " R"
                             : std::string(line) == "\n  pericenter_speed " ? " sqrt(GM/R)"
                             : std::string(line) == "\n  E_I "             ? " e_g"
                                                                            : "] M sqrt(GM/R)";
    EXPECT_TRUE(row.ends_with(unit)) << row;
  }
  const std::string json = inspect_report_json(r);
  EXPECT_TRUE(contains(json, "\"units\": {")) << json;
  EXPECT_TRUE(contains(json, "\"pericenter_speed\": \"sqrt(GM/R)\"")) << json;
  EXPECT_TRUE(contains(json, "\"time\": \"t_grav\"")) << json;
}

TEST(InspectReport, FingerprintIsOneShortLineAndProvenanceIsShown) {
  Checkpoint c = synthetic_checkpoint();
  c.provenance = {"9.8.7", "abc123def456", "GNU 12.2.0", "-O2 -ffp-contract=off"};
  const InspectReport r = build_inspect_report(c, "synthetic.h5");
  const std::string table = inspect_report_table(r);
  // The multi-line fingerprint is not in the table; its hash is, on one line.
  EXPECT_FALSE(contains(table, "integrator.dt = 0.002")) << table;
  const auto at = table.find("\nfingerprint_hash ");
  ASSERT_NE(at, std::string::npos) << table;
  const std::string row = table.substr(at + 1, table.find('\n', at + 1) - at - 1);
  EXPECT_TRUE(row.ends_with(fingerprint_hash(c.stage.fingerprint))) << row;
  EXPECT_EQ(fingerprint_hash(c.stage.fingerprint).size(), 5u + 16u);
  EXPECT_EQ(fingerprint_hash(""), "none");
  EXPECT_NE(fingerprint_hash("a = 1\n"), fingerprint_hash("a = 2\n"));
  EXPECT_TRUE(contains(table, "\nprovenance\n  version ")) << table;
  for (const char* part : {"9.8.7\n", "abc123def456\n", "GNU 12.2.0\n", "-O2 -ffp-contract=off\n"})
    EXPECT_TRUE(contains(table, part)) << part;
  // The JSON carries the full text and the same provenance.
  const std::string json = inspect_report_json(r);
  EXPECT_TRUE(contains(json, "\"fingerprint\": \"encounter.damping = 0.01\\nintegrator.dt = 0.002\\n\"")) << json;
  EXPECT_TRUE(contains(json, "\"git_commit\": \"abc123def456\"")) << json;
  EXPECT_TRUE(contains(json, "\"version\": \"9.8.7\"")) << json;
}

// Of a [moon] workflow (docs/moon.md, "Output in SI"), every number in a model unit has its SI
// value beside it, in the table and in the JSON's "si" object; the moon's scale is a section.
TEST(InspectReport, AMoonsNumbersHaveTheirSiValueBeside) {
  Checkpoint c = synthetic_checkpoint();
  c.config_toml = "[workflow]\nname = \"synthetic\"\n[moon]\npreset = \"tethys\"\n";
  const InspectReport r = build_inspect_report(c, "synthetic.h5");
  ASSERT_TRUE(r.moon);
  EXPECT_EQ(r.moon->name, "Tethys");
  const ModelUnits& u = r.moon->units;
  const double t_grav_h = u.time_s / 3600, R_km = 531;
  std::vector<const ReportSection*> sections{&r.top};
  for (const auto& s : r.sections) sections.push_back(&s);
  std::size_t converted = 0;
  for (const ReportSection* s : sections)
    for (const auto& [key, v] : s->entries) {
      const auto dimension = dimension_of_model_unit(v.unit);
      EXPECT_EQ(v.dimension.has_value(), dimension.has_value() && v.kind == ReportValue::Kind::number)
          << s->name << "." << key;
      if (!v.dimension) continue;
      ++converted;
      EXPECT_EQ(v.si, model_to_output(u, *v.dimension, v.number)) << s->name << "." << key;
    }
  EXPECT_GT(converted, 10u);
  const auto find = [&](const std::string& section, const std::string& key) -> const ReportValue& {
    for (const auto& s : r.sections)
      if (s.name == section)
        for (const auto& [k, v] : s.entries)
          if (k == key) return v;
    throw std::runtime_error("no " + section + "." + key);
  };
  EXPECT_NEAR(find("record", "pericenter").si, find("record", "pericenter").number * R_km, 1e-12 * R_km);
  EXPECT_NEAR(find("perturber", "time_from_pericenter").si,
              (c.state.time - c.stage.as<EncounterRecord>().pericenter_time) * t_grav_h, 1e-12);
  EXPECT_EQ(find("moon", "radius").number, 531);
  EXPECT_EQ(find("moon", "radius").unit, "km");

  const std::string table = inspect_report_table(r);
  EXPECT_TRUE(contains(table, "SI for the moon (Tethys: R = 531 km")) << table;
  const auto at = table.find("\n  pericenter ");
  ASSERT_NE(at, std::string::npos) << table;
  const std::string row = table.substr(at + 1, table.find('\n', at + 1) - at - 1);
  EXPECT_TRUE(contains(row, " R = ") && row.ends_with(" km")) << row;
  const Json json = Json::parse(inspect_report_json(r));
  ASSERT_TRUE(json.contains("si"));
  EXPECT_EQ(json["si"]["record"]["pericenter_km"].get<double>(), find("record", "pericenter").si);
  EXPECT_EQ(json["si"]["time_h"].get<double>(), model_to_output(u, Dimension::time, c.state.time));
  EXPECT_EQ(json["moon"]["name"], "Tethys");
  EXPECT_EQ(json["units"]["moon"]["radius"], "km");
  // Without [moon]: no SI anywhere.
  const InspectReport model = build_inspect_report(synthetic_checkpoint(), "synthetic.h5");
  EXPECT_FALSE(model.moon);
  EXPECT_FALSE(contains(inspect_report_json(model), "\"si\""));
  EXPECT_FALSE(contains(inspect_report_table(model), " km"));
}
