// The key declarations are true (model/config.cpp, visit_keys): for every key of the configuration
// and of an [[encounters]] table, changed to another valid value, every stage of the table
// (stages/stage_kinds.hpp) is rerun from the SAME parent checkpoint as with the unchanged value,
// and a stage whose result (state hash, record, failure and sample counts) changed must declare
// the key. Otherwise `run` would reuse a stale checkpoint after that change. Tiny bodies (shell
// level 1, ~100-150 interior nodes, a few hundred steps per base) keep it to seconds.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <initializer_list>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "base/errors.hpp"
#include "io/state_hash.hpp"
#include "model/config.hpp"
#include "model/stage_fingerprint.hpp"
#include "stages/stage_kinds.hpp"
#include "support/key_values.hpp"
#include "support/quick_workflow.hpp"

using namespace tidalcrust;

namespace {

/// A spring body: paper rule, direct gravity, linear cross springs, a weak crust (failures in the
/// probe and the encounter), short stages.
const char* const tiny_toml = R"(
[workflow]
name = "tiny"
seed = 3
[interior]
count = 120
radius = 0.82
min_separation = 0.2
spring_distance = 0.46
spring_constant = 0.3
[shell]
level = 1
mass = 0.07
spring_constant = 0.12
bending_constant = 0.006
failure_strain = 0.0015
[cross]
distance = 0.45
spring_constant = 0.03
min_per_shell_node = 0
[integrator]
dt = 0.008
[stretch]
max_iterations = 20
[relax]
duration = 0.2
settle_duration = 0.1
probe_duration = 0.1
rest_length_interval = 4
hinge_reset_interval = 8
crust_support = "paper"
[encounter]
start_distance = 1.35
end_distance = 1.35
fail_interval = 2
sample_interval = 5
failure_rule = "paper"
[[encounters]]
name = "A"
perturber_mass = 1.0
pericenter = 1.2
pericenter_speed = 1.8
failure_strain = 0.0012
[[encounters]]
name = "B"
perturber_mass = 0.5
pericenter = 1.5
pericenter_speed = 1.7
)";

/// The tiny body with the tree code, the local failure rule, nonlinear cross springs and a core.
const char* const variant_sets[] = {"gravity.method=tree",    "encounter.failure_rule=local", "cross.nonlinear=true",
                                    "core.radius=0.4",        "core.density_ratio=2.0",       "core.modulus_ratio=3.0",
                                    "encounters.A.relaxation_crossings=1.5"};

/// A tiny [material] body with a core, the balanced crust, the griffith failure rule and its own dt
/// (chosen by relax's prepare).
const char* const material_toml = R"(
[workflow]
name = "tiny-material"
seed = 4
[material]
youngs_modulus = 1.0
crust_thickness = 0.03
crust_mass = 0.07
coupling_speed_ratio = 0.8
failure_strain = 0.0015
[resolution]
shell_level = 1
interior_spacing = 0.22
[core]
radius = 0.4
density_ratio = 2.0
modulus_ratio = 3.0
[stretch]
max_iterations = 20
[relax]
damping = 5.0
duration = 0.2
settle_duration = 0.1
probe_duration = 0.1
crust_support = "balanced"
[encounter]
start_distance = 1.35
end_distance = 1.35
sample_interval = 5
failure_rule = "griffith"
shadow_distance = 0.6
flaw_length = 0.6
[[encounters]]
name = "A"
perturber_mass = 1.0
pericenter = 1.2
pericenter_speed = 1.8
)";

/// The tiny [material] body's crust by its 2D modulus and density, without a core, and its dt given.
const std::pair<const char*, const char*> material_variant_edits[] = {
    {"crust_thickness = 0.03", "crust_modulus_2d = 0.03"},
    {"crust_mass = 0.07", "crust_density = 0.2"},
    {"[core]\nradius = 0.4\ndensity_ratio = 2.0\nmodulus_ratio = 3.0\n", "[integrator]\ndt = 0.006\n"}};

/// The tiny [material] body given as a moon in SI (docs/moon.md): R = 1000 km and M = 1e21 kg make
/// e_g = 6.674e7 Pa, so E_I = 1.05 e_g, h_S = 0.03 R, M_S = 0.071 M, eps_S = 0.0015; a core of
/// density ratio 2.2 and modulus ratio 2.9.
const std::pair<const char*, const char*> moon_edits[] = {
    {"[material]\nyoungs_modulus = 1.0\ncrust_thickness = 0.03\ncrust_mass = 0.07\n",
     "[moon]\nradius = \"1000 km\"\nmass = \"1e21 kg\"\nyoungs_modulus = \"0.07 GPa\"\ncrust_thickness = \"30 km\"\n"
     "crust_density = \"0.19 g/cm3\"\ntensile_strength = \"0.105 MPa\"\ncore_radius = \"400 km\"\n"
     "core_density = \"0.5 g/cm3\"\ncore_youngs_modulus = \"0.2 GPa\"\n[material]\n"},
    {"failure_strain = 0.0015\n", ""},
    {"[core]\nradius = 0.4\ndensity_ratio = 2.0\nmodulus_ratio = 3.0\n", ""}};
/// The tiny moon by its mean density and failure strain.
const std::pair<const char*, const char*> moon_variant_edits[] = {
    {"mass = \"1e21 kg\"", "mean_density = \"0.24 g/cm3\""}, {"tensile_strength = \"0.105 MPa\"", "failure_strain = 0.0015"}};

/// What a stage's result is made of, for comparing two runs of it: the body's fixed properties
/// (masses, springs, hinge stiffnesses, softening), the state, the record, the failures and samples.
struct Result {
  std::string error;  ///< the message when the stage refused or failed
  Body body;
  std::string state_hash;
  StageRecord record;
  std::size_t failures = 0;
  std::size_t samples = 0;
  bool operator==(const Result& o) const {
    return error == o.error && body.mass == o.body.mass && body.species == o.body.species &&
           body.springs == o.body.springs && body.spring_kind == o.body.spring_kind && body.hinges == o.body.hinges &&
           body.hinge_stiffness == o.body.hinge_stiffness && body.faces == o.body.faces &&
           body.strength_factor == o.body.strength_factor &&
           body.softening == o.body.softening && state_hash == o.state_hash && record == o.record &&
           failures == o.failures && samples == o.samples;
  }
};

struct Chain {
  std::vector<Checkpoint> checkpoints;  ///< one per stage, in table order
  std::vector<Result> results;
};

Result result_of(const Checkpoint& c) {
  return {"", c.body, state_hash(c.state), c.stage.record, c.observables.failures.size(), c.observables.timeseries.size()};
}

/// Stage `kind` from `parent` with `config`, to completion.
Checkpoint run_kind(const StageKind& kind, const Checkpoint* parent, const Config& config) {
  const Encounter* encounter = kind.per_encounter ? &config.encounters.at(0) : nullptr;
  Checkpoint c = kind.begin(parent, config, encounter);
  if (kind.stepping() && kind.run(c, config, test_support::quiet_loop(), {}) != LoopOutcome::finished)
    throw std::runtime_error("interrupted");
  return c;
}

/// `config` as `run` leaves it for stage `index`: adapted by the prepare step of every stage up to
/// it (relax: the time step), each from its parent in `parents`.
Config prepared(Config config, std::size_t index, const std::vector<Checkpoint>& parents) {
  for (std::size_t i = 1; i <= index; ++i)
    if (const auto& kind = stage_kinds()[i]; kind.prepare) kind.prepare(config, parents[i - 1], "parent");
  return config;
}

/// The result of stage `index` rerun from its parent in `parents` with `config`; a refusal or a
/// blow-up is a result too.
Result rerun(std::size_t index, const Config& config, const std::vector<Checkpoint>& parents) {
  try {
    const Checkpoint* parent = index == 0 ? nullptr : &parents[index - 1];
    return result_of(run_kind(stage_kinds()[index], parent, prepared(config, index, parents)));
  } catch (const std::exception& err) {  // InputError, SimulationError
    Result r;
    r.error = err.what();
    return r;
  }
}

Chain chain_of(const Config& config) {
  Chain chain;
  for (std::size_t i = 0; i < stage_kinds().size(); ++i) {
    const Checkpoint* parent = i == 0 ? nullptr : &chain.checkpoints.back();
    chain.checkpoints.push_back(run_kind(stage_kinds()[i], parent, prepared(config, i, chain.checkpoints)));
    chain.results.push_back(result_of(chain.checkpoints.back()));
  }
  return chain;
}

/// Keys that change bits but are deliberately no fingerprint key, and why.
const std::set<std::string> not_a_result = {
    // Other bits with AVX-512 (the same physics); recorded in each checkpoint and checked on its own
    // (stages/gravity_kernel_check.hpp).
    "gravity.kernel"};

/// Keys declared but without a visible effect on any of the tiny bodies, and why.
const std::map<std::string, std::string> declared_without_visible_effect = {
    {"interior.max_trials", "a limit: the random sequential addition needs far fewer trials"},
    {"stretch.max_iterations", "a limit: the stretch converges in fewer iterations than it and its changes"},
    {"stretch.tolerance", "the stretch converges far below the tolerance and its changes (one more iteration)"},
    {"crust.map_digest", "without crust.map_file it records nothing; with it, the build refuses another digest"},
};

}  // namespace

TEST(KeyReaders, AStageWhoseResultAKeyChangesDeclaresIt) {
  Config variant = parse_config(tiny_toml, "tiny.toml");
  for (const char* set : variant_sets) apply_override(variant, set);
  validate(variant, "variant");
  const auto edited = [](std::string text, const auto& edits) {
    for (const auto& [from, to] : edits) {
      const auto at = text.find(from);
      if (at == std::string::npos) throw std::runtime_error(std::string("material_toml changed: ") + from);
      text.replace(at, std::string_view(from).size(), to);
    }
    return text;
  };
  const std::string material_variant = edited(material_toml, material_variant_edits);
  struct Base {
    std::string label;
    Config config;
    std::string only_section;  ///< "": every key
  };
  Config interior_only = parse_config(tiny_toml, "tiny.toml");
  apply_override(interior_only, "shell.enabled=false");
  const std::vector<Base> bases = {
      {"tiny", parse_config(tiny_toml, "tiny.toml"), ""},
      {"tiny variant", variant, ""},
      {"tiny material", parse_config(material_toml, "tiny-material.toml"), ""},
      {"tiny material variant", parse_config(material_variant, "tiny-material-variant.toml"), "material"},
      {"tiny interior-only", interior_only, "interior"},
      {"tiny moon", parse_config(edited(material_toml, moon_edits), "tiny-moon.toml"), "moon"},
      {"tiny moon variant", parse_config(edited(edited(material_toml, moon_edits), moon_variant_edits), "tiny-moon-variant.toml"),
       "moon"}};

  std::set<std::string> tried, visible;
  for (const auto& [label, base, only_section] : bases) {
    const Chain chain = chain_of(base);
    const Encounter& own = base.encounters.at(0);
    std::vector<std::pair<KeyInfo, std::string>> keys;
    for (const KeyInfo& key : describe_keys(base)) keys.emplace_back(key, key.section + "." + key.name);
    for (const KeyInfo& key : describe_keys(own, base))
      keys.emplace_back(key, fmt::format("encounters.{}.{}", own.name, key.name));
    for (const auto& [key, path] : keys) {
      const std::string full = key.section + "." + key.name;
      if (!only_section.empty() && key.section != only_section) continue;
      for (const std::string& value : test_support::other_key_values(key)) {
        const std::optional<Config> maybe_changed = test_support::changed_config(base, key, path, value);
        if (!maybe_changed) continue;  // the same value, or not a valid one here: try the next one
        const Config& changed = *maybe_changed;
        tried.insert(full);
        StageSet declared;
        for (const Config* c : std::initializer_list<const Config*>{&base, &changed})
          for (const KeyInfo& k : key.section == "encounters" ? describe_keys(c->encounters.at(0), *c) : describe_keys(*c))
            if (k.section == key.section && k.name == key.name) declared = declared | k.read_by;
        for (std::size_t i = 0; i < stage_kinds().size(); ++i) {
          const StageKind& kind = stage_kinds()[i];
          const Result again = rerun(i, changed, chain.checkpoints);
          if (again == chain.results[i]) continue;
          visible.insert(full);
          // A value derived from the key that the stage's fingerprint holds (a [material] body's
          // derived keys, the time step relax's prepare chooses from the damping rates) reruns it too.
          const Config before = prepared(base, i, chain.checkpoints), after = prepared(changed, i, chain.checkpoints);
          const auto own_of = [&](const Config& c) { return kind.per_encounter ? &c.encounters.at(0) : nullptr; };
          if (!same_fingerprint(stage_fingerprint(before, kind.id, own_of(before)),
                                stage_fingerprint(after, kind.id, own_of(after))))
            continue;
          EXPECT_TRUE(declared.contains(kind.id) || not_a_result.contains(full))
              << label << ": " << path << " = " << value << " changes the result of " << kind.name()
              << ", which does not declare it" << (again.error.empty() ? "" : " (" + again.error + ")");
        }
        break;
      }
    }
  }
  // Every key got a valid other value in some base, but encounters.after: it names the checkpoint
  // an encounter begins from (another encounter's), which the parent hash checks, not the
  // fingerprint (tests/cli/test_encounter_history.cpp); the tiny bases have one encounter.
  EXPECT_EQ(tried.size(), 102u);
  EXPECT_FALSE(tried.contains("encounters.after"));
  // Every declared key shows its effect on some tiny body, but those listed (with the reason).
  for (const std::string& key : tried) {
    const bool listed = declared_without_visible_effect.contains(key);
    if (visible.contains(key)) {
      EXPECT_FALSE(listed) << key << " is listed as without visible effect, but changes a result";
      continue;
    }
    bool reads = false;
    for (const auto& [label, base, only_section] : bases)
      for (const KeyInfo& k : key.starts_with("encounters.") ? describe_keys(base.encounters.at(0), base)
                                                             : describe_keys(base))
        if (k.section + "." + k.name == key) {
          reads = reads || !k.readers.empty() || !k.conditional_readers.empty();
        }
    if (reads) {
      EXPECT_TRUE(listed) << key << " is declared but changed no result on the tiny bodies";
    }
  }
}
