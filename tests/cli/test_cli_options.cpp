#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cli/cli_options.hpp"
#include "base/errors.hpp"
#include "support/cli_runner.hpp"
#include "support/files.hpp"

using namespace tidalcrust;

namespace {
std::vector<std::string> spelled(std::vector<std::string> args) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  return spell_single_letter_long_options(static_cast<int>(argv.size()), argv.data());
}
}  // namespace

TEST(CliOptions, SingleLetterLongOptionsBecomeShortOptions) {
  using V = std::vector<std::string>;
  EXPECT_EQ(spelled({"encounter", "--q", "2.1", "--vq", "1.6"}), (V{"encounter", "-q", "2.1", "--vq", "1.6"}));
  EXPECT_EQ(spelled({"encounter", "--q=-2", "--m2=1"}), (V{"encounter", "-q", "-2", "--m2=1"}));
  EXPECT_EQ(spelled({"x", "--", "--q"}), (V{"x", "--", "--q"}));
  EXPECT_EQ(spelled({"--q"}), (V{"--q"}));  // argv[0] is the program
}

TEST(CliOptions, ParsesDoubleDashSingleLetterOption) {
  cxxopts::Options options("test");
  options.add_options()("q", "pericenter", cxxopts::value<double>())("vq", "speed", cxxopts::value<double>());
  std::vector<std::string> args = {"test", "--q", "2.5", "--vq=1.5"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  const auto parsed = parse_arguments(options, static_cast<int>(argv.size()), argv.data());
  EXPECT_EQ(parsed["q"].as<double>(), 2.5);
  EXPECT_EQ(parsed["vq"].as<double>(), 1.5);
  std::vector<std::string> bad = {"test", "--nope", "1"};
  argv.clear();
  for (auto& a : bad) argv.push_back(a.data());
  EXPECT_THROW(parse_arguments(options, static_cast<int>(argv.size()), argv.data()), InputError);
}

TEST(CliOptions, ThreadCountOutsideItsRangeIsABadInput) {
  EXPECT_EQ(checked_thread_count(0), 0);
  EXPECT_EQ(checked_thread_count(max_threads), max_threads);
  EXPECT_THROW(checked_thread_count(-1), InputError);
  EXPECT_THROW(checked_thread_count(max_threads + 1), InputError);
}

// Every command that takes --threads refuses 100000 with one line and exit 2 before any work
// (OpenMP crashed when asked for that many).
TEST(CliOptions, EveryCommandRefusesAHugeThreadCount) {
  const test_support::ScratchFolder scratch("huge_threads");
  const std::string quick = test_support::quoted(test_support::workflow_file("quick.toml"));
  const std::string out = test_support::quoted(scratch.path / "x.h5");
  for (const std::string& args :
       {"run " + quick + " --out " + test_support::quoted(scratch.path / "run"), "build --config " + quick + " --out " + out,
        "bench --config " + quick + " --steps 1",
        "validate " + quick + " --out " + test_support::quoted(scratch.path / "validate")}) {
    const auto r = test_support::run_cli(args + " --threads 100000");
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find("--threads must be between 0"), std::string::npos) << r.err;
  }
  EXPECT_TRUE(std::filesystem::is_empty(scratch.path));
}

TEST(CliOptions, HelpAndVersionGoToStandardOutput) {
  const auto help = test_support::run_cli("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("usage: tidalcrust COMMAND"), std::string::npos) << help.out;
  EXPECT_TRUE(help.err.empty()) << help.err;
  const auto version = test_support::run_cli("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.out.rfind("tidalcrust 0.1.0 (commit ", 0), 0u) << version.out;
  const auto none = test_support::run_cli("");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("usage:"), std::string::npos);
}
