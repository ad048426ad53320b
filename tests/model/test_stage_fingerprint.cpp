// A changed value reruns exactly the stages it affects: each stage's fingerprint holds the keys
// that declare it (model/config.cpp) and nothing else. Whether the declarations are true (a stage
// whose result a key changes declares it) is tests/stages/test_key_readers.cpp.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "model/config.hpp"
#include "model/stage_fingerprint.hpp"
#include "support/files.hpp"
#include "support/key_values.hpp"

using namespace tidalcrust;

namespace {

using Fingerprints = std::array<std::string, stage_count>;

/// Every stage's fingerprint of `c`; the encounter stage's for its first encounter.
Fingerprints of(const Config& c) {
  Fingerprints out;
  for (std::size_t i = 0; i < stage_count; ++i) {
    const auto stage = static_cast<StageId>(i);
    out[i] = stage_fingerprint(c, stage, stage == StageId::encounter ? &c.encounters.at(0) : nullptr);
  }
  return out;
}

/// The stages whose fingerprints differ between `a` and `b`.
StageSet changed_between(const Config& a, const Config& b) {
  const Fingerprints fa = of(a), fb = of(b);
  StageSet changed;
  for (std::size_t i = 0; i < stage_count; ++i)
    if (!same_fingerprint(fa[i], fb[i])) changed = changed | StageSet{static_cast<StageId>(i)};
  return changed;
}

/// Which fingerprints change when `assignment` is applied to paper-T, as "build, relax".
std::string changed_by(const std::string& assignment) {
  const Config base = load_config(test_support::workflow_file("paper-T.toml"));
  Config changed = base;
  apply_override(changed, assignment);
  return stage_list(changed_between(base, changed));
}

/// The configurations the key test starts from: paper-T (direct gravity, the paper's failure rule,
/// linear cross springs); the same with the tree code, the local failure rule, nonlinear cross
/// springs, a core and encounter overrides; a [material] body with a core and balanced crust; and
/// a [moon] body, without and with a core.
std::vector<std::pair<std::string, Config>> bases() {
  std::vector<std::pair<std::string, Config>> out;
  out.emplace_back("paper-T", load_config(test_support::workflow_file("paper-T.toml")));
  Config variant = out.back().second;
  for (const char* set : {"gravity.method=tree", "encounter.failure_rule=local", "cross.nonlinear=true",
                          "core.radius=0.4", "core.density_ratio=2.0", "core.modulus_ratio=3.0"})
    apply_override(variant, set);
  apply_override(variant, fmt::format("encounters.{}.failure_strain=0.004", variant.encounters.at(0).name));
  apply_override(variant, fmt::format("encounters.{}.relaxation_crossings=1.5", variant.encounters.at(0).name));
  validate(variant, "variant");
  out.emplace_back("paper-T variant", variant);
  out.emplace_back("core-T", load_config(test_support::workflow_file("core-T.toml")));
  // An ocean (its keys have no other valid base). With the paper's coupling: in a welded [material]
  // body material.crust_thickness also sets interior.radius, which the stretch reads, while the
  // key declares build only (a gap of the welded coupling's declarations, not of the ocean's).
  Config ocean = load_config(test_support::workflow_file("ocean-L3.toml"));
  apply_override(ocean, "cross.coupling=paper");
  validate(ocean, "ocean-L3 with the paper's coupling");
  out.emplace_back("ocean-L3 (paper coupling)", ocean);
  // The crust by its 2D modulus and density instead of its thickness and mass, without a core.
  std::string text = test_support::read_file(test_support::workflow_file("core-T.toml"));
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"crust_thickness = 0.0226", "crust_modulus_2d = 0.07"},
           {"crust_mass = 0.07 ", "crust_density = 0.25 "},
           {"radius = 0.5\n", "\n"},
           {"density_ratio = 3.0\n", "\n"},
           {"modulus_ratio = 10.0\n", "\n"}}) {
    const auto at = text.find(from);
    if (at == std::string::npos) throw std::runtime_error("core-T.toml changed: " + from);
    text.replace(at, from.size(), to);
  }
  out.emplace_back("core-T by modulus and density", parse_config(text, "core-T variant"));
  // A moon in SI (docs/moon.md), and the same with a core.
  out.emplace_back("tethys", load_config(test_support::workflow_file("tethys.toml")));
  text = test_support::read_file(test_support::workflow_file("tethys.toml"));
  const std::string preset = "preset = \"tethys\"\n";
  if (text.find(preset) == std::string::npos) throw std::runtime_error("tethys.toml changed: " + preset);
  text.insert(text.find(preset) + preset.size(),
              "core_radius = \"150 km\"\ncore_density = \"2.5 g/cm3\"\ncore_youngs_modulus = \"90 GPa\"\n");
  out.emplace_back("tethys with a core", parse_config(text, "tethys with a core"));
  return out;
}

}  // namespace

// For every key of the configuration and of an [[encounters]] table, in configurations where its
// conditions hold and where they do not: a valid other value changes exactly the fingerprints of
// the stages that read it there (KeyInfo::read_by, before or after the change) and of the stages
// whose conditional keys it turns on or off (gravity.method, shell.enabled). Keys a [material]
// body derives reach the stages that read what they derive.
TEST(StageFingerprint, EveryKeyChangesExactlyTheFingerprintsOfTheStagesItDeclares) {
  std::map<std::string, int> covered;
  for (const auto& [label, base] : bases()) {
    const Encounter& own = base.encounters.at(0);
    std::vector<std::pair<KeyInfo, std::string>> keys;  // the key, its --set prefix
    for (const KeyInfo& key : describe_keys(base)) keys.emplace_back(key, key.section + "." + key.name);
    for (const KeyInfo& key : describe_keys(own, base))
      keys.emplace_back(key, fmt::format("encounters.{}.{}", own.name, key.name));
    for (const auto& [key, path] : keys) {
      const std::string full = key.section + "." + key.name;
      covered.try_emplace(full, 0);
      for (const std::string& value : test_support::other_key_values(key)) {
        const std::optional<Config> maybe_changed = test_support::changed_config(base, key, path, value);
        if (!maybe_changed) continue;  // the same value, or not a valid one here: try the next one
        const Config& changed = *maybe_changed;
        const auto read_by = [&](const Config& c) {
          const Encounter& e = c.encounters.at(0);
          for (const KeyInfo& k : key.section == "encounters" ? describe_keys(e, c) : describe_keys(c))
            if (k.name == key.name && k.section == key.section) return k.read_by;
          return StageSet{};
        };
        StageSet expected = read_by(base) | read_by(changed);
        // A key a condition depends on (gravity.method, shell.enabled) also changes which stages
        // read the conditional keys.
        const auto all_base = describe_keys(base), all_changed = describe_keys(changed);
        for (std::size_t k = 0; k < all_base.size(); ++k)
          for (std::size_t i = 0; i < stage_count; ++i) {
            const auto stage = static_cast<StageId>(i);
            if (all_base[k].read_by.contains(stage) != all_changed[k].read_by.contains(stage))
              expected = expected | StageSet{stage};
          }
        EXPECT_EQ(stage_list(changed_between(base, changed)), stage_list(expected))
            << label << ": " << path << " = " << value;
        ++covered[full];
        break;
      }
    }
  }
  EXPECT_EQ(covered.size(), 107u);  // 96 keys of Config, 11 of [[encounters]]
  for (const auto& [key, count] : covered) EXPECT_GT(count, 0) << key << ": no valid other value in any base";
}

TEST(StageFingerprint, EachValueReachesExactlyTheStagesThatReadIt) {
  EXPECT_EQ(changed_by("interior.count=1500"), "build");
  EXPECT_EQ(changed_by("workflow.seed=2"), "build");
  EXPECT_EQ(changed_by("shell.spring_constant=0.05"), "build");
  EXPECT_EQ(changed_by("stretch.cross_compression=0.001"), "stretch");
  EXPECT_EQ(changed_by("cross.nonlinear=true"), "stretch, relax, encounter");
  EXPECT_EQ(changed_by("relax.damping=40.0"), "relax");
  EXPECT_EQ(changed_by("shell.failure_strain=0.0025"), "relax, encounter");  // the probe and the encounters
  EXPECT_EQ(changed_by("encounter.damping=0.02"), "encounter");
  EXPECT_EQ(changed_by("encounter.fail_interval=2"), "relax, encounter");
  EXPECT_EQ(changed_by("encounters.T5.pericenter=1.9"), "encounter");
  EXPECT_EQ(changed_by("encounters.T1.failure_strain=0.0025"), "relax");  // the probe checks every eps_S
  EXPECT_EQ(changed_by("integrator.dt=0.001"), "relax, encounter");
  EXPECT_EQ(changed_by("core.radius=0.4"), "build, stretch");  // masses and stiffnesses; the layered pressure
  EXPECT_EQ(changed_by("interior.radius=0.9"), "build, stretch");
  // Checkpoint intervals, the workflow name, the gravity kernel and the figures change no result.
  EXPECT_EQ(changed_by("relax.checkpoint_interval=100"), "");
  EXPECT_EQ(changed_by("encounter.checkpoint_interval=100"), "");
  EXPECT_EQ(changed_by("workflow.name=\"other\""), "");
  EXPECT_EQ(changed_by("gravity.kernel=portable"), "");
  EXPECT_EQ(changed_by("analysis.figures=false"), "");
}

TEST(StageFingerprint, TheTreeGravityMethodAndItsErrorAreOtherStages) {
  // Every stage that computes forces (stretch, relax, encounter) reads the gravity method.
  EXPECT_EQ(changed_by("gravity.method=\"tree\""), "stretch, relax, encounter");
  // The direct sum does not read force_error: a direct run's fingerprints stay as they were.
  EXPECT_EQ(changed_by("gravity.force_error=0.001"), "");
  Config tree = load_config(test_support::workflow_file("paper-T.toml"));
  apply_override(tree, "gravity.method=\"tree\"");
  Config looser = tree;
  apply_override(looser, "gravity.force_error=0.001");
  EXPECT_NE(stage_fingerprint(tree, StageId::encounter, &tree.find_encounter("T5")),
            stage_fingerprint(looser, StageId::encounter, &looser.find_encounter("T5")));
  EXPECT_NE(stage_fingerprint(tree, StageId::relax).find("gravity.method = 'tree'"), std::string::npos);
  EXPECT_NE(stage_fingerprint(looser, StageId::stretch).find("gravity.force_error = 0.001"), std::string::npos);
  // A [material] body derives interior.radius, which stretch reads, from shell.enabled.
  const Config material = load_config(test_support::workflow_file("core-T.toml"));
  EXPECT_NE(stage_fingerprint(material, StageId::stretch).find("shell.enabled = true"), std::string::npos);
  EXPECT_EQ(stage_fingerprint(tree, StageId::stretch).find("shell.enabled"), std::string::npos);
}

TEST(StageFingerprint, TextIsOneLinePerKeyAndTheEncounterTable) {
  const Config c = load_config(test_support::workflow_file("quick.toml"));
  const std::string encounter = stage_fingerprint(c, StageId::encounter, &c.encounters.at(0));
  EXPECT_NE(encounter.find("encounter.damping = 0.01\n"), std::string::npos) << encounter;
  EXPECT_NE(encounter.find("integrator.dt = 0.004\n"), std::string::npos) << encounter;
  EXPECT_NE(encounter.find("[[encounters]]\nname = 'strong'\nperturber_mass = 0.5\n"), std::string::npos) << encounter;
  EXPECT_EQ(encounter.find("checkpoint_interval"), std::string::npos) << encounter;
  EXPECT_EQ(stage_fingerprint(c, StageId::build).find("material."), std::string::npos);  // unset: not written
}

TEST(StageFingerprint, SameFingerprintIgnoresOrderAndComments) {
  // As fingerprints were written before they were derived from the key descriptions: other
  // order, the [[encounters]] table with unit comments.
  const std::string old_text = "encounter.damping = 0.01\nintegrator.dt = 0.002\n[[encounters]]\nname = 'T5'\n"
                               "perturber_mass = 0.5  # [M] M2\n";
  const std::string new_text = "integrator.dt = 0.002\nencounter.damping = 0.01\n[[encounters]]\nname = 'T5'\n"
                               "perturber_mass = 0.5\n";
  EXPECT_TRUE(same_fingerprint(old_text, new_text));
  EXPECT_EQ(first_difference(old_text, new_text), "");
  EXPECT_FALSE(same_fingerprint(old_text, "integrator.dt = 0.002\nencounter.damping = 0.01\n"));
  EXPECT_FALSE(same_fingerprint(new_text, new_text + "relax.damping = 50.0\n"));
  EXPECT_EQ(first_difference(new_text, "integrator.dt = 0.001\nencounter.damping = 0.01\n"),
            "'integrator.dt = 0.002' -> 'integrator.dt = 0.001'");
  EXPECT_EQ(first_difference("a.b = 1\nc.d = 2\n", "a.b = 1\n"), "'c.d = 2' -> ''");
}

TEST(StageFingerprint, FirstDifferenceNamesTheKey) {
  Config a = load_config(test_support::workflow_file("paper-T.toml"));
  Config b = a;
  apply_override(b, "interior.count=1500");
  EXPECT_EQ(first_difference(stage_fingerprint(a, StageId::build), stage_fingerprint(b, StageId::build)),
            "'interior.count = 1869' -> 'interior.count = 1500'");
}

TEST(StageFingerprint, ABodyStageReadsEachEncounterKeyOnItsOwn) {
  // A body stage's fingerprint lists the distinct values of each encounter key it reads, not which
  // encounter holds them: exact only while no body stage reads two keys of one encounter together.
  const Config paper = load_config(test_support::workflow_file("paper-T.toml"));
  for (std::size_t i = 0; i < stage_count; ++i) {
    const auto stage = static_cast<StageId>(i);
    if (stage == StageId::encounter) continue;
    std::vector<std::string> read;
    for (const KeyInfo& key : describe_keys(paper.encounters.at(0), paper))
      if (key.read_by.contains(stage)) read.push_back(key.name);
    EXPECT_LE(read.size(), 1u) << stage_list(StageSet{stage}) << " reads " << fmt::format("{}", fmt::join(read, ", "));
  }
}

TEST(StageFingerprint, EnsembleMembersAndRenamedEncountersReuseTheRelaxedBody) {
  const Config base = load_config(test_support::workflow_file("paper-T.toml"));  // T1 overrides eps_S
  Config members = base;
  apply_override(members, "ensemble.members=5");
  ASSERT_EQ(members.encounters.size(), 5 * base.encounters.size());
  EXPECT_EQ(stage_list(changed_between(base, members)), "encounter");  // the members' own tables
  const std::string relax = stage_fingerprint(base, StageId::relax, nullptr);
  EXPECT_NE(relax.find("encounters.*.failure_strain = 0.002\n"), std::string::npos) << relax;
  // A relax fingerprint stored before 2026-12-06 named the encounter: it is the same fingerprint.
  std::string named = relax;
  named.replace(named.find("encounters.*."), 13, "encounters.T1.x.");
  EXPECT_TRUE(same_fingerprint(named, relax));
  EXPECT_EQ(first_difference(named, relax), "");
  // Another value is another fingerprint, and the message names it.
  Config weaker = base;
  apply_override(weaker, "encounters.T1.failure_strain=0.0025");
  const std::string changed = stage_fingerprint(weaker, StageId::relax, nullptr);
  EXPECT_FALSE(same_fingerprint(named, changed));
  EXPECT_EQ(first_difference(named, changed),
            "'encounters.*.failure_strain = 0.002' -> 'encounters.*.failure_strain = 0.0025'");
}
