#include <gtest/gtest.h>
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "model/config.hpp"
#include "base/errors.hpp"
#include "base/invariant.hpp"

using namespace tidalcrust;

namespace {
std::string workflow(const char* name) {
  return std::string(TIDALCRUST_SOURCE_DIR) + "/workflows/" + name;
}
std::string message_of(const std::string& text) {
  try {
    parse_config(text, "bad.toml");
  } catch (const InputError& err) {
    return err.what();
  }
  return "";
}
}  // namespace

TEST(Config, ShippedWorkflowsParse) {
  auto t = load_config(workflow("paper-T.toml"));
  EXPECT_EQ(t.workflow.name, "paper-T");
  EXPECT_EQ(t.shell.level, 4);
  EXPECT_DOUBLE_EQ(t.interior.min_separation, 0.10);
  EXPECT_DOUBLE_EQ(t.interior.spring_distance, 0.23);
  ASSERT_EQ(t.encounters.size(), 4u);
  EXPECT_EQ(t.find_encounter("T1").failure_strain.value(), 0.002);
  auto n = load_config(workflow("paper-N.toml"));
  EXPECT_FALSE(n.shell.enabled);
  auto q = load_config(workflow("quick.toml"));
  EXPECT_LE(q.shell.level, 3);
}

TEST(Config, ResolvedTextRoundTrips) {
  auto config = load_config(workflow("paper-T.toml"));
  std::string text = to_toml(config);
  Config again = parse_config(text, "resolved");
  EXPECT_EQ(to_toml(again), text);
  EXPECT_NE(text.find("dt = 0.002"), std::string::npos);
  EXPECT_NE(text.find("failure_strain = 0.002"), std::string::npos);
}

TEST(Config, UnknownKeyNamesKeyAndFile) {
  auto msg = message_of("[interior]\ncuont = 3\n");
  EXPECT_NE(msg.find("bad.toml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("interior.cuont"), std::string::npos) << msg;
  EXPECT_NE(message_of("[nope]\nx = 1\n").find("unknown section 'nope'"), std::string::npos);
  EXPECT_NE(message_of("[[encounters]]\nname='a'\nmass=1\n").find("unknown key 'mass'"), std::string::npos);
}

TEST(Config, MalformedTomlGivesLine) {
  auto msg = message_of("[interior]\ncount = = 3\n");
  EXPECT_NE(msg.find("bad.toml:2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("malformed"), std::string::npos) << msg;
}

TEST(Config, OutOfRangeAndWrongType) {
  EXPECT_NE(message_of("[integrator]\ndt = -1.0\n").find("integrator.dt"), std::string::npos);
  EXPECT_NE(message_of("[shell]\nlevel = 2.5\n").find("'level' must be an integer"), std::string::npos);
  EXPECT_NE(message_of("[interior]\nmin_separation = 0.5\nspring_distance = 0.3\n").find("min_separation"),
            std::string::npos);
  EXPECT_NE(message_of("[[encounters]]\nname = 'x'\npericenter = 0.5\n").find("pericenter = 0.5 is out of range (1,"),
            std::string::npos);
  EXPECT_NE(message_of("[[encounters]]\nname = 'x'\npericenter = 1\n").find("out of range"), std::string::npos);
  EXPECT_NE(message_of("[[encounters]]\nname = 'x'\nperturber_mass = nan\n").find("perturber_mass"),
            std::string::npos);
  EXPECT_NE(message_of("[[encounters]]\nname='a'\n[[encounters]]\nname='a'\n").find("twice"),
            std::string::npos);
}

TEST(Config, OverridesApplyAndValidate) {
  auto config = load_config(workflow("paper-T.toml"));
  apply_override(config, "shell.failure_strain=0.002");
  EXPECT_DOUBLE_EQ(config.shell.failure_strain, 0.002);
  apply_override(config, "encounters.T5.pericenter=2.0");
  EXPECT_DOUBLE_EQ(config.find_encounter("T5").pericenter, 2.0);
  EXPECT_THROW(apply_override(config, "shell.nope=1"), InputError);
  apply_override(config, "integrator.dt=0");
  EXPECT_THROW(validate(config, "--set"), InputError);
  apply_override(config, "integrator.dt=0.002");
  apply_override(config, "encounters.T5.pericenter=0.9");
  EXPECT_THROW(validate(config, "--set"), InputError);
  EXPECT_THROW(config.find_encounter("T7"), InputError);
}

TEST(Config, ScalingTheTimeStepKeepsSchedulesInTime) {
  auto config = load_config(workflow("paper-T.toml"));
  scale_time_step(config, 0.5);
  EXPECT_DOUBLE_EQ(config.integrator.dt, 0.001);
  EXPECT_EQ(config.encounter.fail_interval, 6);  // t_fail stays 3 x 0.002 = 0.006 t_grav
  EXPECT_EQ(config.encounter.sample_interval, 20);
  const Config unscaled = load_config(workflow("paper-T.toml"));
  EXPECT_EQ(config.relax.rest_length_interval, 2 * unscaled.relax.rest_length_interval);
  EXPECT_EQ(config.relax.hinge_reset_interval, 2 * unscaled.relax.hinge_reset_interval);
  EXPECT_EQ(config.relax.checkpoint_interval, 2 * unscaled.relax.checkpoint_interval);
  EXPECT_EQ(config.encounter.checkpoint_interval, 2 * unscaled.encounter.checkpoint_interval);
  EXPECT_EQ(config.interior.count, unscaled.interior.count);  // counts that are not schedules stay
  EXPECT_EQ(config.stretch.max_iterations, unscaled.stretch.max_iterations);
  scale_time_step(config, 4.0);  // dt 0.004: 1.5 steps rounds to 2, never below 1
  EXPECT_EQ(config.encounter.fail_interval, 2);
  scale_time_step(config, 10.0);
  EXPECT_EQ(config.encounter.fail_interval, 1);
}

TEST(Config, SeedIsAnUnsignedInteger) {
  EXPECT_EQ(parse_config("[workflow]\nseed = 9223372036854775807\n", "a").workflow.seed, 9223372036854775807u);
  EXPECT_NE(message_of("[workflow]\nseed = -1\n").find("'seed' must be >= 0"), std::string::npos);
  EXPECT_NE(message_of("[workflow]\nseed = 1.5\n").find("'seed' must be an integer"), std::string::npos);
  Config config;
  config.workflow.seed = 9223372036854775808u;  // TOML could not store it
  EXPECT_THROW(validate(config, "x"), InputError);
}

TEST(Config, EncounterTablesUseTheSameDescription) {
  Encounter spec;
  spec.name = "T1";
  spec.pericenter_speed = 1.6;
  EXPECT_EQ(encounter_toml(spec),
            "[[encounters]]\nname = 'T1'\nperturber_mass = 0.5  # [M] M2\npericenter = 1.84  # [R] q\n"
            "pericenter_speed = 1.6  # [sqrt(GM/R)] V_q; default parabolic, sqrt(2 (1 + M2) / q) of the table's M2 "
            "and q\n");
  spec.failure_strain = 0.002;
  EXPECT_NE(encounter_toml(spec).find("failure_strain = 0.002  # [-] eps_S override\n"), std::string::npos);
  EXPECT_NE(message_of("[[encounters]]\nname = 'x'\npericenter = 'far'\n").find("pericenter = \"far\": a string is a quantity with its unit"),
            std::string::npos);
  EXPECT_EQ(parse_config("[[encounters]]\nname = 'x'\npericenter = 2\n", "a").encounters.at(0).pericenter, 2.0);

  auto config = load_config(workflow("paper-T.toml"));
  apply_override(config, "encounters.T5.failure_strain=0.004");
  EXPECT_EQ(config.find_encounter("T5").failure_strain, 0.004);
  EXPECT_THROW(apply_override(config, "encounters.T5.mass=1"), InputError);
  EXPECT_THROW(apply_override(config, "encounters.T9.pericenter=2"), InputError);
  EXPECT_THROW(apply_override(config, "encounters.T5.pericenter=true"), InputError);
}

// Every workflow the project ships reads, validates and keeps its resolved configuration through a
// write and a read (what each checkpoint stores): none is found broken only when someone runs it.
TEST(Config, EveryShippedWorkflowReadsAndKeepsItsResolvedConfiguration) {
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(TIDALCRUST_SOURCE_DIR) / "workflows")) {
    if (entry.path().extension() != ".toml") continue;
    ++files;
    const Config config = load_config(entry.path());
    const std::string stored = to_toml(config);
    const Config again = parse_config(stored, "stored " + entry.path().filename().string());
    EXPECT_EQ(to_toml(again), stored) << entry.path();
    EXPECT_EQ(again.encounters, config.encounters) << entry.path();
    EXPECT_FALSE(config.encounters.empty()) << entry.path();
  }
  EXPECT_GE(files, 21u);
}

TEST(Config, DescribedValuesAreTheResolvedText) {
  const auto config = load_config(workflow("quick.toml"));
  const std::string text = to_toml(config);
  const auto keys = describe_keys(config);
  EXPECT_EQ(keys.size(), 96u);  // every key of Config, [workflow] to [spin] and [ocean], and [analysis]
  for (const KeyInfo& key : keys) {
    if (!key.value) {  // an unset optional key: to_toml leaves it out
      EXPECT_TRUE(key.optional) << key.section << "." << key.name;
      continue;
    }
    EXPECT_NE(text.find("\n" + key.name + " = " + *key.value + "  # [" + key.unit + "] " + key.doc + "\n"),
              std::string::npos)
        << key.section << "." << key.name;
  }
  EXPECT_NE(text.find("\n[integrator]\ndt = "), std::string::npos);
  EXPECT_EQ(describe_keys(Encounter{}, config).size(), 11u);
  EXPECT_EQ(integer_key_value(config, "relax", "checkpoint_interval"), config.relax.checkpoint_interval);
  EXPECT_THROW(integer_key_value(config, "relax", "damping"), InternalError);  // not an integer key
}

TEST(Config, ABareWordOverridesAStringKeyAndIsRefusedForANumber) {
  Config config;
  apply_override(config, "relax.crust_support=paper");  // the default is balanced
  EXPECT_EQ(config.relax.crust_support, CrustSupport::paper);
  apply_override(config, "encounter.failure_rule=\"paper\"");
  EXPECT_EQ(config.encounter.failure_rule, FailureRuleKind::paper);
  EXPECT_THROW(apply_override(config, "integrator.dt=small"), InputError);
  try {
    apply_override(config, "relax.crust_support=glued");
    ADD_FAILURE() << "an unknown crust support was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "--set: relax.crust_support = \"glued\" is not one of: paper, balanced, lithostatic, floating");
  }
}

TEST(Config, SweepExpandsIntoNamedEncountersThatTheStoredConfigurationKeeps) {
  const Config config = parse_config(R"(
[workflow]
name = "sweep"
[[encounters]]
name = "T5"
[sweep]
perturber_mass = [0.1, 0.5]
pericenter = {from = 1.5, to = 2.5, count = 3}
failure_strain = [0.001, 0.002]
)",
                                     "sweep.toml");
  ASSERT_EQ(config.encounters.size(), 1u + 2 * 3 * 2);
  EXPECT_EQ(config.encounters[0].name, "T5");  // listed encounters first
  const Encounter& first = config.encounters[1];
  EXPECT_EQ(first.name, "M0.1_q1.5_Vpar_eps0.001");
  EXPECT_EQ(first.perturber_mass, 0.1);
  EXPECT_EQ(first.pericenter, 1.5);
  EXPECT_EQ(first.pericenter_speed, std::sqrt(2.0 * 1.1 / 1.5));  // parabolic when no speed is swept
  EXPECT_EQ(first.failure_strain, 0.001);
  EXPECT_EQ(config.encounters[4].name, "M0.1_q2_Vpar_eps0.002");
  EXPECT_EQ(config.encounters.back().name, "M0.5_q2.5_Vpar_eps0.002");
  // The stored configuration keeps the [sweep] table, not its expansion; reading it back gives
  // the encounters again.
  const std::string stored = to_toml(config);
  EXPECT_NE(stored.find("[sweep]"), std::string::npos) << stored;
  EXPECT_EQ(stored.find("M0.1_q1.5_Vpar_eps0.001"), std::string::npos) << stored;
  const Config again = parse_config(stored, "stored");
  EXPECT_EQ(again.encounters, config.encounters);
  EXPECT_EQ(again.sweep, config.sweep);
  EXPECT_EQ(to_toml(again), stored);
  const Config speeds = parse_config("[sweep]\nperturber_mass = [1.0]\npericenter = [2.0]\npericenter_speed = [1.6, 1.94]\n", "s.toml");
  ASSERT_EQ(speeds.encounters.size(), 2u);
  EXPECT_EQ(speeds.encounters[1].name, "M1_q2_V1.94");
  EXPECT_EQ(speeds.encounters[1].pericenter_speed, 1.94);
  EXPECT_FALSE(speeds.encounters[1].failure_strain);
}

namespace {

/// A workflow of `masses` x `pericenters` swept encounters (and one listed, "T5").
std::string sweep_of(int masses, int pericenters, bool listed = true) {
  return fmt::format("[workflow]\nname = \"n\"\n{}[sweep]\n"
                     "perturber_mass = {{from = 0.1, to = 1.0, count = {}}}\n"
                     "pericenter = {{from = 1.5, to = 3.0, count = {}}}\npericenter_speed = [1.7]\n",
                     listed ? "[[encounters]]\nname = \"T5\"\n" : "", masses, pericenters);
}

}  // namespace

// Issue 28, item 9: every checkpoint stores the resolved configuration (to_toml); of a sweep it
// holds the [sweep] table, so its size does not grow with the number of encounters (it grew by
// ~250 bytes per encounter: 2.5 MB at 10,000).
// A range {from, to, count} stands for decimals: every value is the double of the decimal it names
// (and so is every folder name), also where from + i (to - from)/(count - 1) rounds off it.
TEST(Config, ASweepRangeGivesTheDecimalsItNames) {
  const Config config = parse_config(R"(
[sweep]
perturber_mass = [0.5]
pericenter = { from = 1.9, to = 2.4, count = 6 }
pericenter_speed = { from = 0.3, to = 1.2, count = 10 }
)",
                                     "range.toml");
  ASSERT_EQ(config.encounters.size(), 60u);
  std::set<double> qs, speeds;
  for (const auto& e : config.encounters) {
    qs.insert(e.pericenter), speeds.insert(e.pericenter_speed);
    EXPECT_EQ(e.name, fmt::format("M0.5_q{}_V{}", e.pericenter, e.pericenter_speed));
    EXPECT_LE(e.name.size(), 16u) << e.name;  // no 2.1999999999999997
  }
  EXPECT_EQ(qs, (std::set<double>{1.9, 2.0, 2.1, 2.2, 2.3, 2.4}));
  EXPECT_EQ(speeds, (std::set<double>{0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2}));
}

TEST(Config, StoredConfigurationOfASweepDoesNotGrowWithItsSize) {
  std::vector<std::size_t> sizes;
  for (const auto& [masses, pericenters] : {std::pair{1, 10}, std::pair{10, 100}, std::pair{100, 100}}) {
    const Config config = parse_config(sweep_of(masses, pericenters, false), "w.toml");
    ASSERT_EQ(config.encounters.size(), static_cast<std::size_t>(masses * pericenters));
    const std::string stored = to_toml(config);
    const Config again = parse_config(stored, "stored");
    EXPECT_EQ(again.encounters, config.encounters);
    sizes.push_back(stored.size());
  }
  // 10, 1000 and 10000 encounters: only the axes' values (110 and 200 numbers) are added.
  EXPECT_LT(sizes[1], sizes[0] + 5000);  // at most 20 characters a value
  EXPECT_LT(sizes[2], sizes[0] + 5000);
  EXPECT_LT(sizes[2], 20000u);
}

// A --set of one swept encounter makes the expansion differ from the table: then every
// encounter is stored as a table, and reading it back gives the changed encounter.
TEST(Config, AChangedSweptEncounterIsStoredAsATable) {
  Config config = parse_config(sweep_of(2, 2), "w.toml");
  apply_override(config, "encounters.M1_q3_V1.7.pericenter_speed=1.9");
  const std::string stored = to_toml(config);
  EXPECT_EQ(stored.find("[sweep]"), std::string::npos) << stored;
  const Config again = parse_config(stored, "stored");
  EXPECT_EQ(again.encounters, config.encounters);
  EXPECT_EQ(again.find_encounter("M1_q3_V1.7").pericenter_speed, 1.9);
}

// One limit for [[encounters]] and [sweep], alone or together, with one message.
TEST(Config, OneLimitOnTheEncountersOfAWorkflow) {
  std::string listed;
  for (std::size_t i = 0; i <= max_encounters; ++i) listed += fmt::format("[[encounters]]\nname = \"e{}\"\n", i);
  // e0 ... e5000: 5001 tables, and 5000 swept.
  const std::string half_listed = listed.substr(0, listed.find("[[encounters]]\nname = \"e5001\""));
  const std::pair<std::string, std::string> cases[] = {
      {listed, "w.toml: the workflow has 10001 encounters (10001 [[encounters]] tables, 0 from [sweep]); at most 10000"},
      {half_listed + "[sweep]\nperturber_mass = {from = 0.1, to = 1, count = 5}\npericenter = {from = 1.5, to = 3, count = 1000}\n",
       "w.toml: the workflow has 10001 encounters (5001 [[encounters]] tables, 5000 from [sweep]); at most 10000"},
      {"[sweep]\nperturber_mass = {from = 0.1, to = 1, count = 1000}\npericenter = {from = 1.5, to = 3, count = 1000}\n"
       "pericenter_speed = {from = 1.5, to = 3, count = 1000}\nfailure_strain = {from = 0.001, to = 0.01, count = 1000}\n",
       "w.toml: the workflow has 1000000000000 encounters (0 [[encounters]] tables, 1000000000000 from [sweep]); at most 10000"},
  };
  for (const auto& [text, expected] : cases) {
    try {
      parse_config(text, "w.toml");
      ADD_FAILURE() << "accepted: " << expected;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), expected);
    }
  }
  // At the limit: accepted.
  EXPECT_EQ(parse_config(listed.substr(0, listed.find("[[encounters]]\nname = \"e10000\"")), "w.toml").encounters.size(),
            max_encounters);
}

TEST(Config, BadSweepsAreOneLineErrorsNamingTheFileAndKey) {
  const std::pair<const char*, const char*> cases[] = {
      {"[sweep]\npericenter = [2.0]\n", "needs perturber_mass and pericenter"},
      {"[sweep]\nperturber_mass = []\npericenter = [2.0]\n", "sweep.perturber_mass: has no values"},
      {"[sweep]\nperturber_mass = [0.5, \"x\"]\npericenter = [2.0]\n", "sweep.perturber_mass: every entry"},
      {"[sweep]\nperturber_mass = [0.5]\npericenter = {from = 1.5, to = 2}\n", "a range needs"},
      {"[sweep]\nperturber_mass = [0.5]\npericenter = {from = 1.5, to = 2, count = 0}\n", "count = 0 is out of range"},
      {"[sweep]\nperturber_mass = [0.5]\npericenter = {from = 1.5, to = 2, count = 2, step = 1}\n", "unknown key 'step'"},
      {"[sweep]\nperturber_mass = [0.5]\npericenter = [2.0]\nspeed = [1]\n", "unknown key 'sweep.speed'"},
      {"[sweep]\nperturber_mass = [0.5]\npericenter = [0.5]\n", "pericenter = 0.5 is out of range"},
      {"[sweep]\nperturber_mass = [0.5, 0.5]\npericenter = [2.0]\n", "appears twice"},
      {"[sweep]\nperturber_mass = {from = 0.1, to = 1, count = 1000}\npericenter = {from = 1.5, to = 3, count = 100}\n",
       "the workflow has 100000 encounters"},
  };
  for (const auto& [text, expected] : cases) {
    try {
      parse_config(text, "w.toml");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind("w.toml: ", 0), 0u) << message;
      EXPECT_NE(message.find(expected), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
}

namespace {
/// The message of the InputError for `text`, checked to be one line naming bad.toml.
std::string one_line_error(const std::string& text) {
  const std::string message = message_of(text);
  EXPECT_FALSE(message.empty()) << "accepted: " << text.substr(0, 200);
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_EQ(message.rfind("bad.toml", 0), 0u) << message;
  return message;
}
}  // namespace

TEST(Config, EveryNameThatBecomesAPathIsOnePortableFileName) {
  const std::string long_name(max_path_name_bytes + 1, 'a');
  // TOML basic strings: \u0000 is a NUL, \t a tab, \u00e9 a non-ASCII letter.
  const std::string bad[] = {"..", ".", "../../x", "a/b", "/abs", "a\\\\b", "x\\u0000y", "tab\\there", "new\\nline",
                             "-looks-like-an-option", "caf\\u00e9", "sp ace", "a:b", long_name};
  for (const std::string& name : bad) {
    const std::string workflow_message = one_line_error(fmt::format("[workflow]\nname = \"{}\"\n", name));
    EXPECT_NE(workflow_message.find("workflow.name"), std::string::npos) << workflow_message;
    const std::string encounter_message = one_line_error(fmt::format("[[encounters]]\nname = \"{}\"\n", name));
    EXPECT_NE(encounter_message.find("encounter name"), std::string::npos) << encounter_message;
    EXPECT_FALSE(path_name_problem(name).empty()) << name;
  }
  // The folders beside the encounters are not encounter names.
  for (const char* reserved : {"body", "slurm", "validate", "status.json", "analysis", "dt2", "dt0.5"})
    EXPECT_NE(one_line_error(fmt::format("[[encounters]]\nname = \"{}\"\n", reserved)).find("reserved"),
              std::string::npos);
  // The names in use stay valid, up to the length limit.
  for (const std::string& name : {std::string("T10b"), std::string("M0.5_q2_V1.94_eps0.002"), std::string("a.b-c_d"),
                                  std::string(".hidden"), std::string("dtx"), std::string(max_path_name_bytes, 'n')}) {
    EXPECT_EQ(path_name_problem(name), "") << name;
    EXPECT_EQ(message_of(fmt::format("[workflow]\nname = \"{}\"\n[[encounters]]\nname = \"{}\"\n", name, name)), "")
        << name;
  }
  // --only NAME and --set overrides go through the same check.
  Config config = parse_config("[[encounters]]\nname = \"a\"\n", "w.toml");
  EXPECT_THROW(config.find_encounter(".."), InputError);
  apply_override(config, "workflow.name=\"../x\"");
  EXPECT_THROW(validate(config, "--set"), InputError);
  // The control character is shown escaped: the message stays one line.
  const std::string nul = one_line_error("[workflow]\nname = \"a\\u0000b\"\n");
  EXPECT_NE(nul.find("a\\x00b"), std::string::npos) << nul;
}

TEST(Config, TheCrackNeighbourhoodIsGivenOnceAsALengthOrInSpacings) {
  // As a length (R), in (0, 2]; with exclusion_radius at its default; both given: one clear line.
  EXPECT_EQ(*parse_config("[encounter]\nexclusion_distance = 0.113\n", "w.toml").encounter.exclusion_distance, 0.113);
  EXPECT_FALSE(parse_config("[encounter]\nexclusion_radius = 3\n", "w.toml").encounter.exclusion_distance);
  const std::string both = one_line_error("[encounter]\nexclusion_radius = 3\nexclusion_distance = 0.113\n");
  EXPECT_NE(both.find("give one of them"), std::string::npos) << both;
  for (const char* out_of_range : {"0", "-0.1", "2.5", "\"0.1 km\""})
    EXPECT_NE(one_line_error(fmt::format("[encounter]\nexclusion_distance = {}\n", out_of_range)).find("exclusion_distance"),
              std::string::npos)
        << out_of_range;
  Config config;
  apply_override(config, "encounter.exclusion_distance=0.2");
  apply_override(config, "encounter.exclusion_radius=6");
  EXPECT_THROW(validate(config, "--set"), InputError);
}

TEST(Config, NestingIsBoundedBeforeParsing) {
  std::string dotted = "x";
  for (int i = 0; i < 40'000; ++i) dotted += ".x";
  std::string inline_tables = "a = ", arrays = "a = ";
  for (int i = 0; i < 200; ++i) inline_tables += "{b = ", arrays += "[";
  inline_tables += "1" + std::string(200, '}');
  arrays += "1" + std::string(200, ']');
  std::string header = "[t";
  for (int i = 0; i < 100; ++i) header += ".t";
  const std::string cases[] = {"[workflow]\nname = \"w\"\n" + dotted + " = 1\n", inline_tables + "\n", arrays + "\n",
                               header + "]\nk = 1\n", "[[encounters]]\nname = \"a\"\n" + header.substr(1) + " = 2\n"};
  for (const std::string& text : cases) {
    const std::string message = one_line_error(text);
    EXPECT_NE(message.find("nested deeper than"), std::string::npos) << message;
  }
  EXPECT_NE(one_line_error("\n\n" + dotted + " = 1\n").find("bad.toml:3:"), std::string::npos);
  // Dots, brackets and braces inside strings and comments are not nesting.
  const std::string quoted = "[workflow]\nname = \"w\"  # " + dotted + "\n[[encounters]]\nname = \"" +
                             std::string(10, '.') + "x\"\n";
  const std::string message = message_of(quoted + "'''" + std::string(300, '[') + "'''\n");
  EXPECT_EQ(message.find("nested"), std::string::npos) << message;
  // A --set value is checked the same way.
  Config config;
  try {
    apply_override(config, "integrator.dt=" + arrays.substr(4));
    ADD_FAILURE() << "accepted a deep --set value";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nested deeper than"), std::string::npos) << e.what();
  }
}

TEST(Config, EveryRangeErrorOfANumericKeyNamesTheKey) {
  // The key fuzz of issue 28: every numeric key, in its section and in an [[encounters]] table.
  const Config base = parse_config("[workflow]\nname = \"w\"\n[[encounters]]\nname = \"e\"\n", "w.toml");
  const char* values[] = {"nan", "inf", "-inf", "-1", "0", "1e308", "-1e308", "1e-320", "9223372036854775807",
                          "-9223372036854775808", "9223372036854775808"};
  std::vector<std::string> keys;
  for (const KeyInfo& key : describe_keys(base))
    if (key.type == "number" || key.type == "integer") keys.push_back(key.section + "." + key.name);
  for (const KeyInfo& key : describe_keys(base.encounters[0], base))
    if (key.type == "number" || key.type == "integer") keys.push_back("encounters.e." + key.name);
  ASSERT_GT(keys.size(), 40u);
  for (const std::string& key : keys)
    for (const char* value : values) {
      Config config = base;
      try {
        apply_override(config, key + "=" + value);
        validate(config, "--set");
      } catch (const InputError& e) {
        const std::string message = e.what();
        const std::string name = key.substr(key.rfind('.') + 1);
        EXPECT_NE(message.find(name), std::string::npos) << key << "=" << value << ": " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      }
    }
}

// Issue 24, item 1: [ensemble] expands every encounter (listed and swept) into its members, with
// stratified pericenter offsets symmetric about q; the stored configuration keeps the table.
TEST(Config, EnsembleExpandsEveryEncounterIntoMembersThatTheStoredConfigurationKeeps) {
  const Config config = parse_config(R"(
[workflow]
name = "ens"
[[encounters]]
name = "T5"
pericenter = 2.0
[sweep]
perturber_mass = [0.5]
pericenter = [1.5, 2.5]
[ensemble]
members = 4
pericenter_perturbation = 0.002
)",
                                     "ens.toml");
  ASSERT_EQ(config.ensemble_bases.size(), 3u);
  ASSERT_EQ(config.encounters.size(), 12u);
  EXPECT_EQ(config.encounters[0].name, "T5_m0");
  EXPECT_EQ(config.encounters[3].name, "T5_m3");
  EXPECT_EQ(config.encounters[4].name, "M0.5_q1.5_Vpar_m0");
  // u_k = (2k + 1)/n - 1: -3/4, -1/4, 1/4, 3/4 of delta.
  const double expected[] = {2.0 * (1 - 0.0015), 2.0 * (1 - 0.0005), 2.0 * (1 + 0.0005), 2.0 * (1 + 0.0015)};
  double sum = 0;
  for (int k = 0; k < 4; ++k) {
    EXPECT_DOUBLE_EQ(config.encounters[k].pericenter, expected[k]) << k;
    sum += config.encounters[k].pericenter;
    EXPECT_EQ(config.encounters[k].pericenter_speed, config.ensemble_bases[0].pericenter_speed);
  }
  EXPECT_NEAR(sum / 4, 2.0, 1e-15);
  const std::string stored = to_toml(config);
  EXPECT_NE(stored.find("[ensemble]"), std::string::npos) << stored;
  EXPECT_NE(stored.find("[sweep]"), std::string::npos) << stored;
  EXPECT_EQ(stored.find("T5_m0"), std::string::npos) << stored;
  const Config again = parse_config(stored, "stored");
  EXPECT_EQ(again.encounters, config.encounters);
  EXPECT_EQ(again.ensemble, config.ensemble);
  EXPECT_EQ(to_toml(again), stored);
}

TEST(Config, EnsembleOverridesReexpandTheMembers) {
  Config config = parse_config("[workflow]\nname = \"e\"\n[[encounters]]\nname = \"T5\"\n", "e.toml");
  apply_override(config, "ensemble.members=3");
  ASSERT_EQ(config.encounters.size(), 3u);
  EXPECT_EQ(config.encounters[2].name, "T5_m2");
  apply_override(config, "ensemble.members=5");
  EXPECT_EQ(config.encounters.size(), 5u);
  // An encounter before the expansion: every member follows.
  apply_override(config, "encounters.T5.perturber_mass=0.25");
  for (const auto& e : config.encounters) EXPECT_EQ(e.perturber_mass, 0.25) << e.name;
  // One member: stored as tables, read back the same.
  apply_override(config, "encounters.T5_m1.failure_strain=0.004");
  const std::string stored = to_toml(config);
  EXPECT_EQ(stored.find("[ensemble]"), std::string::npos) << stored;
  EXPECT_EQ(parse_config(stored, "stored").encounters, config.encounters);
  validate(config, "e.toml");
}

TEST(Config, AnEnsembleThatVariesTheBodyGivesMemberKTheSeedPlusK) {
  const Config config = parse_config(R"(
[workflow]
name = "seeds"
seed = 7
[[encounters]]
name = "T5"
pericenter = 2.0
[[encounters]]
name = "own"
pericenter = 2.0
body_seed = 40
[ensemble]
members = 3
vary = "body_seed"
)",
                                     "seeds.toml");
  ASSERT_EQ(config.encounters.size(), 6u);
  // Member 0 stays on the encounter's own body; member k on seed s + k; the pericenter is the base's.
  EXPECT_EQ(config.encounters[0].body_seed, std::nullopt);
  EXPECT_EQ(config.encounters[1].body_seed, 8u);
  EXPECT_EQ(config.encounters[2].body_seed, 9u);
  EXPECT_EQ(config.encounters[3].body_seed, 40u);
  EXPECT_EQ(config.encounters[5].body_seed, 42u);
  for (const auto& e : config.encounters) EXPECT_EQ(e.pericenter, 2.0) << e.name;
  EXPECT_EQ(body_seed_of(config, config.encounters[0]), 7u);
  EXPECT_EQ(body_config_of(config, config.encounters[2]).workflow.seed, 9u);
  EXPECT_EQ(body_config_of(config, config.encounters[0]).workflow.seed, 7u);
  const std::string stored = to_toml(config);
  EXPECT_NE(stored.find("vary = \"body_seed\""), std::string::npos) << stored;
  EXPECT_EQ(parse_config(stored, "stored").encounters, config.encounters);
  // run --only: a base's name means its members in order, a member's name that member alone.
  std::vector<std::string> named;
  for (const auto& e : config.encounters_named("own")) named.push_back(e.name);
  EXPECT_EQ(named, (std::vector<std::string>{"own_m0", "own_m1", "own_m2"}));
  ASSERT_EQ(config.encounters_named("T5_m1").size(), 1u);
  EXPECT_EQ(config.encounters_named("T5_m1")[0].body_seed, 8u);
  EXPECT_THROW(config.encounters_named("T6"), InputError);

  // "both": its own body and its own pericenter.
  Config both = parse_config("[workflow]\nseed = 1\n[[encounters]]\nname = \"T\"\npericenter = 2.0\n", "b.toml");
  apply_override(both, "ensemble.vary=both");
  apply_override(both, "ensemble.members=4");
  ASSERT_EQ(both.encounters.size(), 4u);
  EXPECT_EQ(both.encounters[3].body_seed, 4u);
  EXPECT_DOUBLE_EQ(both.encounters[3].pericenter, 2.0 * (1 + 0.005 * 0.75));
  // A later --set workflow.seed moves every member's body with it.
  apply_override(both, "workflow.seed=100");
  EXPECT_EQ(both.encounters[1].body_seed, 101u);
  EXPECT_EQ(both.encounters[0].body_seed, std::nullopt);
  validate(both, "b.toml");

  // Errors: an unknown variation, a seed past the largest, a name that is a body folder.
  EXPECT_NE(one_line_error("[ensemble]\nmembers = 3\nvary = \"seeds\"\n")
                .find("ensemble.vary = \"seeds\" is not one of: pericenter, body_seed, both"),
            std::string::npos);
  EXPECT_NE(one_line_error("[workflow]\nseed = 9223372036854775807\n[[encounters]]\nname = \"T\"\n[ensemble]\nmembers = "
                           "3\nvary = \"both\"\n")
                .find("past the largest seed"),
            std::string::npos);
  EXPECT_NE(one_line_error("[[encounters]]\nname = \"body-seed3\"\n").find("is reserved"), std::string::npos);
  EXPECT_NE(one_line_error("[[encounters]]\nname = \"T\"\nbody_seed = -1\n").find("'body_seed' must be >= 0"),
            std::string::npos);
}

TEST(Config, BadEnsemblesAreOneLineErrorsNamingTheFileAndKey) {
  const std::pair<const char*, const char*> cases[] = {
      {"[ensemble]\npericenter_perturbation = 0.001\n", "[ensemble] needs members"},
      {"[ensemble]\nmembers = 1\n", "ensemble.members = 1 is out of range [3, 1000]"},
      {"[ensemble]\nmembers = 1001\n", "ensemble.members = 1001 is out of range"},
      {"[ensemble]\nmembers = 2.5\n", "ensemble.members: must be an integer"},
      {"[ensemble]\nmembers = 3\npericenter_perturbation = 0\n", "pericenter_perturbation = 0 is out of range (0, 0.05]"},
      {"[ensemble]\nmembers = 3\npericenter_perturbation = 0.5\n", "pericenter_perturbation = 0.5 is out of range (0, 0.05]"},
      {"[ensemble]\nmembers = 3\npericenter_perturbation = \"1e-3\"\n", "must be a number"},
      {"[ensemble]\nmembers = 3\nseed = 2\n", "unknown key 'ensemble.seed'"},
      {"ensemble = 3\n", "'ensemble' must be a table"},
      {"[sweep]\nperturber_mass = {from = 0.1, to = 1, count = 100}\npericenter = {from = 1.5, to = 3, count = 20}\n"
       "[ensemble]\nmembers = 10\n",
       "the workflow has 2000 encounters of 10 members each (20000 in all); at most 10000"},
  };
  for (const auto& [text, expected] : cases)
    EXPECT_NE(one_line_error(text).find(expected), std::string::npos) << text;
  Config config = parse_config("[[encounters]]\nname = \"T5\"\n", "e.toml");
  EXPECT_THROW(apply_override(config, "ensemble.members=1"), InputError);
  EXPECT_THROW(apply_override(config, "ensemble.size=4"), InputError);
  // The keys in either order: the perturbation first, then members.
  Config either = parse_config("[[encounters]]\nname = \"T5\"\n", "e.toml");
  apply_override(either, "ensemble.pericenter_perturbation=0.002");
  try {
    validate(either, "e.toml");
    ADD_FAILURE() << "an ensemble without members was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "e.toml: [ensemble] needs members (e.g. --set ensemble.members=10)");
  }
  apply_override(either, "ensemble.members=4");
  ASSERT_EQ(either.encounters.size(), 4u);
  EXPECT_DOUBLE_EQ(either.encounters[0].pericenter, 1.84 * (1 - 0.002 * 0.75));
}

// issue 27 item 6: one default speed (parabolic) for an [[encounters]] table, as for a [sweep].
TEST(Config, AnEncounterWithoutASpeedIsParabolicAsASweptOne) {
  Config config = parse_config(R"(
[[encounters]]
name = "A"
perturber_mass = 0.3
pericenter = 2.0
[[encounters]]
name = "B"
pericenter_speed = 1.6
[sweep]
perturber_mass = [0.3]
pericenter = [2.0]
)",
                               "speeds.toml");
  ASSERT_EQ(config.encounters.size(), 3u);
  EXPECT_EQ(config.encounters[0].pericenter_speed, std::sqrt(2.0 * 1.3 / 2.0));
  EXPECT_EQ(config.encounters[0].pericenter_speed, config.encounters[2].pericenter_speed);  // the swept one
  EXPECT_EQ(config.encounters[1].pericenter_speed, 1.6);                                   // given: kept
  EXPECT_EQ(Encounter{}.pericenter_speed, parabolic_speed(Encounter{}.perturber_mass, Encounter{}.pericenter));
  // The resolved text keeps the speed (a stored configuration does not depend on the default).
  EXPECT_EQ(parse_config(to_toml(config), "resolved").encounters, config.encounters);
  // --set of M2 or q keeps a parabolic encounter parabolic, and a given speed given.
  apply_override(config, "encounters.A.pericenter=3.0");
  apply_override(config, "encounters.B.pericenter=3.0");
  EXPECT_EQ(config.encounters[0].pericenter_speed, std::sqrt(2.0 * 1.3 / 3.0));
  EXPECT_EQ(config.encounters[1].pericenter_speed, 1.6);
}

// issue 27 item 6: defaults a new user can trust; the paper's workflows name the paper's choices.
TEST(Config, DefaultsAreTheBalancedCrustAndTheLocalRuleAndThePaperWorkflowsNameThePapers) {
  const Config defaults;
  EXPECT_EQ(defaults.relax.crust_support, CrustSupport::balanced);
  EXPECT_EQ(defaults.encounter.failure_rule, FailureRuleKind::local);
  EXPECT_EQ(defaults.cross.min_per_shell_node, 3);  // what the balanced support needs
  for (const char* name : {"paper-T.toml", "paper-N.toml", "quick.toml"}) {
    const Config c = load_config(workflow(name));
    EXPECT_EQ(c.relax.crust_support, CrustSupport::paper) << name;
    EXPECT_EQ(c.encounter.failure_rule, FailureRuleKind::paper) << name;
    EXPECT_EQ(c.cross.min_per_shell_node, 0) << name;
  }
}

TEST(Config, SnapshotIntervalIsCheckedAgainstTheTimeStep) {
  EXPECT_EQ(parse_config("[encounter]\nsnapshot_interval = 0.5\n", "s.toml").encounter.snapshot_interval, 0.5);
  const std::string shorter = message_of("[integrator]\ndt = 0.004\n[encounter]\nsnapshot_interval = 0.001\n");
  EXPECT_NE(shorter.find("bad.toml: encounter.snapshot_interval = 0.001 is shorter than integrator.dt"),
            std::string::npos)
      << shorter;
  const std::string negative = message_of("[encounter]\nsnapshot_interval = -1\n");
  EXPECT_NE(negative.find("bad.toml: encounter.snapshot_interval = -1 is out of range"), std::string::npos) << negative;
}

// issue 25 item 4: an encounter history. `after` names another encounter of the workflow (no
// cycle); the encounter is on that one's body; an ensemble runs the history per member; the
// orientation keys and `after` are written back only when given (so that encounters without them
// keep their stored text and fingerprints).
TEST(Config, AnEncounterHistoryNamesEncountersOfTheWorkflowWithoutACycle) {
  const std::string a = "[[encounters]]\nname = \"A\"\n";
  const std::pair<std::string, const char*> cases[] = {
      {a + "[[encounters]]\nname = \"B\"\nafter = \"C\"\n", "encounter 'B': after = \"C\": no encounter of that name"},
      {a + "after = \"A\"\n", "encounter 'A': after = \"A\": the history returns to 'A' (a cycle)"},
      {a + "after = \"B\"\n[[encounters]]\nname = \"B\"\nafter = \"A\"\n", "the history returns to"},
      {"[workflow]\nseed = 2\n" + a + "[[encounters]]\nname = \"B\"\nafter = \"A\"\nbody_seed = 5\n",
       "encounter 'B': after = \"A\": body_seed = 5 differs from the body of 'A' (seed 2)"},
      {a + "inclination = 181\n", "encounter 'A': inclination = 181 is out of range [0, 180] (deg)"},
      {a + "argument_of_pericenter = -400\n", "argument_of_pericenter = -400 is out of range [-360, 360] (deg)"},
      {a + "after = 3\n", "'after' must be"},
  };
  for (const auto& [text, expected] : cases)
    EXPECT_NE(one_line_error(text).find(expected), std::string::npos) << text << "\n" << message_of(text);

  const Config config = parse_config("[workflow]\nseed = 4\n[[encounters]]\nname = \"A\"\nbody_seed = 9\n"
                                     "[[encounters]]\nname = \"B\"\nafter = \"A\"\ninclination = 60.0\n"
                                     "[[encounters]]\nname = \"C\"\nafter = \"B\"\n",
                                     "h.toml");
  EXPECT_EQ(body_seed_of(config, config.find_encounter("C")), 9u);  // the body of the history's first encounter
  EXPECT_EQ(config.find_encounter("B").after, "A");
  EXPECT_EQ(orbit_orientation(config.find_encounter("B")), (OrbitOrientation{60, 0, 90}));
  EXPECT_TRUE(orbit_orientation(config.find_encounter("C")).is_default());
  const std::string text = to_toml(config);
  EXPECT_EQ(parse_config(text, "again.toml").encounters, config.encounters);
  EXPECT_NE(text.find("\nafter = 'A'"), std::string::npos);
  EXPECT_NE(text.find("inclination = 60.0"), std::string::npos);
  EXPECT_EQ(text.find("ascending_node"), std::string::npos);
  EXPECT_EQ(text.find("argument_of_pericenter"), std::string::npos);

  // An ensemble: member k of B comes after member k of A, on member k's body.
  Config ensemble = parse_config("[[encounters]]\nname = \"A\"\n[[encounters]]\nname = \"B\"\nafter = \"A\"\n"
                                 "[ensemble]\nmembers = 3\nvary = \"both\"\n",
                                 "e.toml");
  validate(ensemble, "e.toml");
  ASSERT_EQ(ensemble.encounters.size(), 6u);
  for (int k = 0; k < 3; ++k) {
    const Encounter& b = ensemble.find_encounter(fmt::format("B_m{}", k));
    EXPECT_EQ(b.after, fmt::format("A_m{}", k));
    EXPECT_EQ(body_seed_of(ensemble, b), body_seed_of(ensemble, ensemble.find_encounter(fmt::format("A_m{}", k))));
  }
}

// A welded crust needs an interior that reaches it (docs/crust-support.md): crust-T's own body
// welded (r_I = 0.897, d_IS = 0.10) relaxed strained to 9.5e-4 with 6,134 probe failures. A body
// whose interior stops more than d_IS / 2 under the shell is refused, naming the radius that would
// do; a [material] body fills the ball itself, and an ocean lies between on purpose.
TEST(Config, AWeldedCrustWhoseInteriorStopsShortOfItIsRefused) {
  const std::string short_interior =
      message_of("[interior]\nradius = 0.897\nmin_separation = 0.10\n[cross]\ncoupling = \"welded\"\n");
  EXPECT_EQ(short_interior,
            "bad.toml: cross.coupling = \"welded\" needs an interior that reaches the crust: interior.radius = 0.897 "
            "leaves 0.103 R under the shell, more than half interior.min_separation (0.1); raise interior.radius to "
            "at least 0.95");
  EXPECT_EQ(message_of("[interior]\nradius = 0.96\nmin_separation = 0.10\n[cross]\ncoupling = \"welded\"\n"), "");
  EXPECT_EQ(message_of("[interior]\nradius = 0.897\nmin_separation = 0.10\n"), "");  // the paper's coupling
  for (const char* name : {"quick-welded.toml", "welded-L4.toml", "ocean-L3.toml", "dione.toml"})
    EXPECT_NO_THROW(load_config(workflow(name))) << name;
  auto crust_t = load_config(workflow("crust-T.toml"));
  apply_override(crust_t, "cross.coupling=welded");
  EXPECT_THROW(validate(crust_t, "--set"), InputError);
}
