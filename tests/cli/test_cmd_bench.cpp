#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "support/cli_runner.hpp"
#include "support/files.hpp"

namespace {

using tidalcrust::test_support::CliResult;
using tidalcrust::test_support::quoted;
using tidalcrust::test_support::run_cli;
using tidalcrust::test_support::workflow_file;

/// The number after "key": in a JSON text, or -1.
double json_number(const std::string& json, const std::string& key) {
  std::smatch match;
  if (!std::regex_search(json, match, std::regex("\"" + key + "\": ([0-9.eE+-]+)"))) return -1;
  return std::stod(match[1].str());
}

const std::string quick = "--config " + quoted(workflow_file("quick.toml"));

}  // namespace

TEST(CmdBench, JsonReportsTheBodyAndTheTimings) {
  const CliResult r = run_cli("bench " + quick + " --steps 2 --repeats 1 --textbook-steps 1 --threads 2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(json_number(r.out, "particles"), 1042) << r.out;  // quick: 400 interior + 642 shell
  EXPECT_GT(json_number(r.out, "springs"), 1000) << r.out;
  EXPECT_EQ(json_number(r.out, "hinges"), 1920) << r.out;  // 30 * 4^3 shell edges
  EXPECT_EQ(json_number(r.out, "threads"), 2) << r.out;
  EXPECT_GT(json_number(r.out, "ms_per_step"), 0) << r.out;
  EXPECT_GT(json_number(r.out, "textbook_ms_per_step"), 0) << r.out;
  EXPECT_GT(json_number(r.out, "speedup"), 0) << r.out;
  // Both gravity kernels are timed: the portable one's cost is reported next to the fast one.
  EXPECT_GT(json_number(r.out, "fast_ms_per_step"), 0) << r.out;
  EXPECT_GT(json_number(r.out, "portable_ms_per_step"), 0) << r.out;
  EXPECT_NEAR(json_number(r.out, "portable_over_fast"),
              json_number(r.out, "portable_ms_per_step") / json_number(r.out, "fast_ms_per_step"), 1e-9)
      << r.out;
  EXPECT_NE(r.out.find("\"gravity_kernel\": \"fast/"), std::string::npos) << r.out;
}

TEST(CmdBench, BadArgumentsAreInputErrors) {
  CliResult r = run_cli("bench " + quick + " --steps 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--steps"), std::string::npos) << r.err;
  r = run_cli("bench --config /nonexistent/workflow.toml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("/nonexistent/workflow.toml"), std::string::npos) << r.err;
}
