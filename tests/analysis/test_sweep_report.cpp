// The tables of `report` (analysis/sweep_report) of a [moon] workflow: the ensemble table gives the
// inputs and every statistic in a model unit again in SI, last (docs/moon.md, "Output in SI").
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "analysis/sweep_report.hpp"

using namespace tidalcrust;

namespace {

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) out.push_back(cell);
  return out;
}

}  // namespace

TEST(SweepReport, AMoonsEnsembleTableHasItsStatisticsInSiLast) {
  SweepReport report;
  EnsembleRow row;
  row.encounter = encounter_of("T5", 0.5, 1.84, 1.6);
  row.members = row.finished = 3;
  for (std::size_t i = 0; i < ensemble_statistics().size(); ++i)
    row.statistics.push_back({3, 1.0 + static_cast<double>(i), 0.25, 0.1, 0.5, 2.5 + static_cast<double>(i), 1, 0});
  report.ensembles.push_back(row);
  const std::string model_csv = ensemble_report_csv(report);
  report.moon = MoonScale{"Tethys", model_units(0.62e21, 531e3)};
  const std::string csv = ensemble_report_csv(report);
  std::istringstream lines(csv), model_lines(model_csv);
  std::string header, values, model_header, model_values;
  std::getline(lines, header), std::getline(lines, values);
  std::getline(model_lines, model_header), std::getline(model_lines, model_values);
  // The model columns as without [moon], then the SI ones.
  ASSERT_TRUE(header.starts_with(model_header + ","));
  ASSERT_TRUE(values.starts_with(model_values + ","));
  const auto names = cells(header.substr(model_header.size() + 1));
  const auto si = cells(values.substr(model_values.size() + 1));
  ASSERT_EQ(names.size(), si.size());
  EXPECT_EQ(names.at(0), "M2 [kg]");
  EXPECT_EQ(names.at(1), "q [km]");
  EXPECT_EQ(names.at(2), "V_q [km/s]");
  EXPECT_NEAR(std::stod(si.at(1)), 1.84 * 531, 1e-9);
  // Per statistic in R or G M^2/R: mean, sd, low, high.
  std::size_t k = 3;
  for (std::size_t i = 0; i < ensemble_statistics().size(); ++i) {
    const auto dimension = dimension_of_model_unit(ensemble_statistics()[i].unit);
    if (!dimension) continue;
    const std::string name = ensemble_statistics()[i].name;
    EXPECT_EQ(names.at(k), name + "_mean [" + std::string(output_unit(*dimension).symbol) + "]");
    EXPECT_DOUBLE_EQ(std::stod(si.at(k)), model_to_output(report.moon->units, *dimension, 1.0 + static_cast<double>(i)))
        << name;
    EXPECT_DOUBLE_EQ(std::stod(si.at(k + 1)), model_to_output(report.moon->units, *dimension, 0.25)) << name;
    k += 4;
  }
  EXPECT_EQ(k, names.size());
  EXPECT_EQ(k, 3u + 4u * 4u);  // total and largest crack length (km), energy deposited and dissipated (J)
}
