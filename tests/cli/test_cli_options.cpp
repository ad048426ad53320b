#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cli/cli_options.hpp"
#include "base/errors.hpp"

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
