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
                          "k_C", "V_IP", "V_SP", "V_Co", "h_S", "dt_max", "conservation", "momentum",
                          "angular_momentum", "kinetic_energy", "record", "fail_interval", "snapshot_steps", "perturber", "mass", "failures", "hemisphere_fraction", "mean_angle_from_subsatellite_deg", "longest_crack", "clusters",
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
  EXPECT_EQ(find("perturber", "mass").number, 0.5);
  EXPECT_EQ(find("perturber", "min_distance").number, 1.84);
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
