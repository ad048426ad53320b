// The closed choices of the configuration (model/choices.hpp): every name table reads back what it
// prints, through the tables and through a workflow file, and a value that is not in a table is
// a one-line error that names the key and lists the choices.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <string_view>
#include <tuple>

#include "base/errors.hpp"
#include "model/choices.hpp"
#include "model/config.hpp"
#include "support/cli_runner.hpp"
#include "support/files.hpp"

using namespace tidalcrust;

namespace {

/// Every row of E's table: its name parses to its value and its value prints as its name; the
/// names are distinct and non-empty, each with a meaning; a near miss (case) is refused.
template <Choice E>
void expect_table_round_trips() {
  std::set<std::string_view> names;
  for (const auto& row : ChoiceTable<E>::rows) {
    EXPECT_FALSE(row.name.empty());
    EXPECT_FALSE(row.meaning.empty()) << row.name;
    EXPECT_TRUE(names.insert(row.name).second) << row.name << " twice";
    ASSERT_TRUE(find_choice<E>(row.name).has_value()) << row.name;
    EXPECT_EQ(*find_choice<E>(row.name), row.value);
    EXPECT_EQ(choice_name(row.value), row.name);
    EXPECT_EQ(choice_meaning(row.value), row.meaning);
    EXPECT_EQ(parse_choice<E>(choice_name(row.value), "test"), row.value);
    std::string upper(row.name);
    for (char& ch : upper) ch = static_cast<char>(ch - 'a' + 'A');
    EXPECT_FALSE(find_choice<E>(upper).has_value()) << upper;
  }
  EXPECT_FALSE(find_choice<E>("").has_value());
}

/// Sets `key` to every name of E's table in a Config (--set and a [section] table of a workflow
/// file), prints the configuration and reads the print back: the same value each time.
template <Choice E, class Get>
void expect_config_round_trips(const std::string& key, Get get, const std::string& other_keys = "",
                               const std::set<std::string_view>& skipped = {}) {
  const std::string section = key.substr(0, key.find('.')), name = key.substr(key.find('.') + 1);
  for (const auto& row : ChoiceTable<E>::rows) {
    if (skipped.contains(row.name)) continue;  // a value that needs other keys set with it (tested apart)
    Config config = parse_config(other_keys, "other keys");
    apply_override(config, key + "=" + std::string(row.name));  // a bare word, as a shell passes it
    EXPECT_EQ(get(config), row.value) << key << " = " << row.name;
    const std::string text = to_toml(config);
    EXPECT_NE(text.find(name + " = '" + std::string(row.name) + "'"), std::string::npos) << text;
    EXPECT_EQ(get(parse_config(text, "printed")), row.value) << key << " = " << row.name;
    const Config from_file =
        parse_config(other_keys + "[" + section + "]\n" + name + " = \"" + std::string(row.name) + "\"\n", "file.toml");
    EXPECT_EQ(get(from_file), row.value) << key << " = " << row.name;
  }
}

std::string parse_error(const std::string& text) {
  try {
    parse_config(text, "bad.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Choices, EveryNameTableRoundTrips) {
  expect_table_round_trips<CrustSupport>();
  expect_table_round_trips<CrossCoupling>();
  expect_table_round_trips<HydrostaticSupport>();
  expect_table_round_trips<FailureRuleKind>();
  expect_table_round_trips<GravityMethod>();
  expect_table_round_trips<GravityKernel>();
}

TEST(Choices, EveryChoiceKeyRoundTripsThroughTheResolvedConfiguration) {
  // "lithostatic" needs the welded coupling, "floating" an ocean (and an ocean nothing else); the
  // welded coupling an interior that reaches the crust.
  expect_config_round_trips<CrustSupport>("relax.crust_support", [](const Config& c) { return c.relax.crust_support; },
                                          "[interior]\nradius = 0.96\n[cross]\ncoupling = \"welded\"\n", {"floating"});
  // "floating" and an ocean need each other: from a file only, and back through the print.
  const Config floating =
      parse_config("[ocean]\nthickness = 0.3\nbulk_modulus = 2.0\n[relax]\ncrust_support = \"floating\"\n", "file.toml");
  EXPECT_EQ(floating.relax.crust_support, CrustSupport::floating);
  EXPECT_EQ(parse_config(to_toml(floating), "printed").relax.crust_support, CrustSupport::floating);
  expect_config_round_trips<CrossCoupling>("cross.coupling", [](const Config& c) { return c.cross.coupling; },
                                           "[interior]\nradius = 0.96\n");
  expect_config_round_trips<HydrostaticSupport>("stretch.hydrostatic_support",
                                                [](const Config& c) { return c.stretch.hydrostatic_support; });
  expect_config_round_trips<FailureRuleKind>("encounter.failure_rule",
                                             [](const Config& c) { return c.encounter.failure_rule; });
  expect_config_round_trips<GravityMethod>("gravity.method", [](const Config& c) { return c.gravity.method; });
  expect_config_round_trips<GravityKernel>("gravity.kernel", [](const Config& c) { return c.gravity.kernel; });
}

TEST(Choices, TheKeyCommentComesFromTheTable) {
  EXPECT_EQ(choice_doc<CrustSupport>(),
            "\"paper\" (crust carries the cross springs' sideways push), \"balanced\" (no crust pre-stress), "
            "\"lithostatic\" (crust compressed by its own weight; welded crust only) or \"floating\" (crust floats "
            "on an ocean; [ocean] only)");
  EXPECT_EQ(choice_names<GravityKernel>(), "fast, portable");
  const std::string text = to_toml(Config{});
  EXPECT_NE(text.find("method = 'direct'  # [-] \"direct\" (every pair, the reference) or \"tree\" (octree, "
                      "quadrupoles)\n"),
            std::string::npos)
      << text;
}

TEST(Choices, AValueOutsideTheTableNamesTheKeyAndListsTheChoices) {
  EXPECT_EQ(parse_error("[relax]\ncrust_support = \"glued\"\n"),
            "bad.toml: relax.crust_support = \"glued\" is not one of: paper, balanced, lithostatic, floating");
  EXPECT_EQ(parse_error("[cross]\ncoupling = \"glued\"\n"),
            "bad.toml: cross.coupling = \"glued\" is not one of: paper, welded");
  EXPECT_EQ(parse_error("[stretch]\nhydrostatic_support = \"stiffen\"\n"),
            "bad.toml: stretch.hydrostatic_support = \"stiffen\" is not one of: strengthen, compress");
  EXPECT_EQ(parse_error("[encounter]\nfailure_rule = \"fast\"\n"),
            "bad.toml: encounter.failure_rule = \"fast\" is not one of: paper, local, shadow, griffith, "
            "critical_distance, nonlocal, nonlocal_principal");
  EXPECT_EQ(parse_error("[gravity]\nmethod = \"fmm\"\n"), "bad.toml: gravity.method = \"fmm\" is not one of: direct, tree");
  EXPECT_EQ(parse_error("[gravity]\nkernel = \"exact\"\n"),
            "bad.toml: gravity.kernel = \"exact\" is not one of: fast, portable");
  EXPECT_EQ(parse_error("[gravity]\nkernel = 1\n"), "bad.toml: gravity: 'kernel' must be one of: fast, portable");
  Config config;
  try {
    apply_override(config, "gravity.method=fmm");
    ADD_FAILURE() << "gravity.method = fmm accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--set: gravity.method = \"fmm\" is not one of: direct, tree");
  }
}

TEST(Choices, ABadChoiceOnTheCommandLineIsOneLineAndExitCodeTwo) {
  using namespace test_support;
  const ScratchFolder out("choices");
  const std::string workflow = workflow_file("quick.toml").string();
  for (const auto& [option, key, names] :
       {std::tuple{"--set relax.crust_support=glued", "relax.crust_support", "paper, balanced"},
        std::tuple{"--set encounter.failure_rule=fast", "encounter.failure_rule", "paper, local"},
        std::tuple{"--set cross.coupling=glued", "cross.coupling", "paper, welded"},
        std::tuple{"--gravity-kernel exact", "gravity.kernel", "fast, portable"}}) {
    const CliResult r = run_cli("run " + test_support::quoted(workflow) + " --out " + test_support::quoted(out.path) + " " + option);
    EXPECT_EQ(r.exit_code, exit_bad_input) << option << ": " << r.err;
    EXPECT_NE(r.err.find(key), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(std::string("is not one of: ") + names), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;  // one line
  }
  EXPECT_TRUE(std::filesystem::is_empty(out.path));  // refused before anything was written
}
