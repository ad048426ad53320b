#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <regex>
#include <string>

namespace {

struct Result {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr
};

Result run_bench(const std::string& arguments) {
  const std::string command = fmt::format("'{}' bench {} 2>&1", TIDALCRUST_EXE, arguments);
  Result result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  char buffer[4096];
  std::size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) result.output.append(buffer, n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

/// The number after "key": in a JSON text, or -1.
double json_number(const std::string& json, const std::string& key) {
  std::smatch match;
  if (!std::regex_search(json, match, std::regex("\"" + key + "\": ([0-9.eE+-]+)"))) return -1;
  return std::stod(match[1].str());
}

const std::string quick = std::string("--config '") + TIDALCRUST_SOURCE_DIR + "/workflows/quick.toml'";

}  // namespace

TEST(CmdBench, JsonReportsTheBodyAndTheTimings) {
  const Result r = run_bench(quick + " --steps 2 --repeats 1 --textbook-steps 1 --threads 2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(json_number(r.output, "particles"), 1042) << r.output;  // quick: 400 interior + 642 shell
  EXPECT_GT(json_number(r.output, "springs"), 1000) << r.output;
  EXPECT_EQ(json_number(r.output, "hinges"), 1920) << r.output;  // 30 * 4^3 shell edges
  EXPECT_EQ(json_number(r.output, "threads"), 2) << r.output;
  EXPECT_GT(json_number(r.output, "ms_per_step"), 0) << r.output;
  EXPECT_GT(json_number(r.output, "textbook_ms_per_step"), 0) << r.output;
  EXPECT_GT(json_number(r.output, "speedup"), 0) << r.output;
}

TEST(CmdBench, BadArgumentsAreInputErrors) {
  Result r = run_bench(quick + " --steps 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--steps"), std::string::npos) << r.output;
  r = run_bench("--config /nonexistent/workflow.toml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("/nonexistent/workflow.toml"), std::string::npos) << r.output;
}
