// The help that cannot drift: `tidalcrust config --defaults` prints every key from the one
// description of the configuration, docs/configuration.md is its --markdown output, `tidalcrust
// --help` lists the command table, each command's --help starts with its line there, and README.md
// names exactly the commands of the table.
#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <set>
#include <string>

#include "cli/commands.hpp"
#include "io/json.hpp"
#include "model/config.hpp"
#include "support/cli_runner.hpp"
#include "support/files.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;

TEST(ConfigCli, DocsPageIsTheProgramsOutput) {
  const CliResult page = run_cli("config --defaults --markdown");
  ASSERT_EQ(page.exit_code, 0) << page.err;
  EXPECT_EQ(page.out, read_file(source_file("docs/configuration.md")))
      << "docs/configuration.md is stale: regenerate it with "
         "`build/tidalcrust config --defaults --markdown > docs/configuration.md`";
}

TEST(ConfigCli, DefaultsListEveryKeyWithItsDefaultAndStages) {
  const Config defaults;
  const CliResult text = run_cli("config --defaults");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  for (const KeyInfo& key : describe_keys(defaults))
    EXPECT_NE(text.out.find("\n" + key.name + " = " + key.value.value_or("unset") + "\n    " + key.doc + "\n"),
              std::string::npos)
        << key.section << "." << key.name;
  EXPECT_NE(text.out.find("\nradius = 0.92\n    r_I, radius of the sphere the interior nodes fill\n"
                          "    number, unit R, range [0.05, 1]; stages: build, stretch\n"),
            std::string::npos)
      << text.out;
  EXPECT_NE(text.out.find("; stages: stretch, relax, encounter when gravity.method = \"tree\"\n"), std::string::npos);
  EXPECT_NE(text.out.find("\ncheckpoint_interval = 500\n"), std::string::npos);

  const CliResult json = run_cli("config --defaults --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const Json keys = Json::parse(json.out)["keys"];
  ASSERT_EQ(keys.size(), 107u);  // 96 keys of Config, 11 of [[encounters]]
  std::set<std::string> names;
  for (const auto& k : keys) names.insert(k["section"].get<std::string>() + "." + k["name"].get<std::string>());
  EXPECT_EQ(names.size(), 107u);
  for (const auto& k : keys)
    if (k["section"] == "integrator" && k["name"] == "dt") {
      EXPECT_EQ(k["default"], "0.002");
      EXPECT_EQ(k["stages"], Json::array({"relax", "encounter"}));
    }
}

TEST(ConfigCli, WorkflowPrintsItsResolvedConfiguration) {
  const CliResult r = run_cli("config " + quoted(workflow_file("quick.toml")) + " --set relax.damping=40");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Config expected = load_config(workflow_file("quick.toml"));
  apply_override(expected, "relax.damping=40");
  EXPECT_EQ(r.out, to_toml(expected));
  for (const char* bad : {"config", "config --markdown", "config --defaults --markdown --json",
                          "config --defaults --set relax.damping=40", "config no-such-file.toml"}) {
    const CliResult refused = run_cli(bad);
    EXPECT_EQ(refused.exit_code, 2) << bad << "\n" << refused.err;
    EXPECT_EQ(count_lines(refused.err), 1) << bad << "\n" << refused.err;
  }
}

// A [moon] value with a unit udunits2 does not know: one line naming the file and the key, exit 2;
// the shipped workflows/tethys.toml is accepted.
TEST(ConfigCli, MoonWithABadUnitIsExitCodeTwo) {
  const ScratchFolder folder("moon");
  std::string text = read_file(workflow_file("tethys.toml"));
  text.replace(text.find("\"10.6 km\""), 9, "\"10.6 kmm\"");
  write_file(folder.path / "bad.toml", text);
  const CliResult bad = run_cli("config " + quoted(folder.path / "bad.toml"));
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find("bad.toml: moon.crust_thickness = \"10.6 kmm\": 'kmm' is not a unit udunits2 knows"),
            std::string::npos)
      << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  const CliResult good = run_cli("config " + quoted(workflow_file("tethys.toml")));
  EXPECT_EQ(good.exit_code, 0) << good.err;
  EXPECT_NE(good.out.find("preset = 'tethys'"), std::string::npos);
}

TEST(CommandTable, HelpListsEveryCommandOnceWithTheLineOfItsOwnHelp) {
  const CliResult help = run_cli("--help");
  ASSERT_EQ(help.exit_code, 0);
  std::set<std::string> names;
  for (const Command& c : commands()) {
    EXPECT_TRUE(names.insert(c.name).second) << c.name << " twice in the table";
    EXPECT_EQ(c.summary.find('\n'), std::string::npos) << c.name;
    const std::string line = "  " + c.name;
    const auto at = help.out.find(line + " ");
    ASSERT_NE(at, std::string::npos) << c.name << "\n" << help.out;
    EXPECT_EQ(help.out.find(line + " ", at + 1), std::string::npos) << c.name << " listed twice";
    EXPECT_NE(help.out.find(c.summary + "\n", at), std::string::npos) << c.name;
    const CliResult own = run_cli(c.name + " --help");
    EXPECT_EQ(own.exit_code, 0) << c.name << "\n" << own.err;
    EXPECT_EQ(own.out.substr(0, c.summary.size() + 1), c.summary + "\n") << c.name << "\n" << own.out;
  }
  EXPECT_GE(names.size(), 14u);
  for (const char* stage : {"build", "stretch", "relax", "encounter"}) EXPECT_TRUE(names.contains(stage)) << stage;
  const CliResult unknown = run_cli("frobnicate");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("unknown command 'frobnicate'"), std::string::npos) << unknown.err;
}

// README.md's command summary names exactly the commands of the table: every "tidalcrust NAME" at
// the start of a command in its code (fenced blocks and `inline code`) is a command, and every
// command appears so.
TEST(CommandTable, ReadmeNamesEveryCommand) {
  const std::string readme = read_file(source_file("README.md"));
  ASSERT_FALSE(readme.empty());
  std::string code;
  const std::regex fenced("```[^\\n]*\\n([\\s\\S]*?)```"), inline_code("`([^`\\n]+)`");
  std::string prose;
  std::sregex_iterator end;
  std::size_t last = 0;
  for (std::sregex_iterator it(readme.begin(), readme.end(), fenced); it != end; ++it) {
    code += (*it)[1].str() + "\n";
    prose += readme.substr(last, static_cast<std::size_t>(it->position()) - last);
    last = static_cast<std::size_t>(it->position() + it->length());
  }
  prose += readme.substr(last);
  for (std::sregex_iterator it(prose.begin(), prose.end(), inline_code); it != end; ++it)
    code += (*it)[1].str() + "\n";
  std::set<std::string> named;
  const std::regex command("(^|[\\s/])tidalcrust ([a-z][a-z-]*)");
  for (std::sregex_iterator it(code.begin(), code.end(), command); it != end; ++it) named.insert((*it)[2].str());
  std::set<std::string> table;
  for (const Command& c : commands()) table.insert(c.name);
  for (const auto& name : named)
    EXPECT_TRUE(table.contains(name)) << "README.md shows `tidalcrust " << name << "`, which is no command";
  for (const auto& name : table)
    EXPECT_TRUE(named.contains(name)) << "README.md's command summary lacks `tidalcrust " << name << "`";
}
