// The golden reference (tests/reference/golden.toml; tests/reference/README.md says where it came
// from): the quick workflow's relaxed body and the first steps of its encounter "strong" must
// give the stored bits and numbers. It checks the code against the commit that wrote the file,
// not against itself, so a refactor that changes one bit of a step fails here.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <toml++/toml.h>
#include <xxhash.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include "io/state_hash.hpp"
#include "physics/conservation.hpp"
#include "physics/orbital_frame.hpp"
#include "physics/shell_failure.hpp"
#include "stages/encounter_stage.hpp"
#include "support/files.hpp"
#include "support/quick_workflow.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;

namespace {

constexpr const char* golden_table = "quick_strong_first_steps";

/// The stored hashes come from the AVX-512 gravity kernel; the portable kernel differs in the
/// last bits (forces/gravity.hpp), so without AVX-512 only the readable values are checked.
#if defined(__AVX512F__)
constexpr bool same_gravity_kernel = true;
#else
constexpr bool same_gravity_kernel = false;
#endif

/// One value of the reference: a hash (compared exactly), a count (exactly) or a real number
/// (within the file's relative_tolerance).
struct Value {
  std::string key;
  std::variant<std::string, std::int64_t, double> value;
};

/// XXH3-128 of the bytes of position [N*3] followed by velocity [N*3] (float64), written as
/// state_hash writes its hash: 32 hex digits, high 64 bits first.
std::string position_velocity_hash(const State& state) {
  std::vector<double> values(state.position);
  values.insert(values.end(), state.velocity.begin(), state.velocity.end());
  const XXH128_hash_t h = XXH3_128bits(values.data(), values.size() * sizeof(double));
  return fmt::format("{:016x}{:016x}", h.high64, h.low64);
}

/// The quick body relaxed as `run` relaxes it (the stability probe changes no state), then the
/// encounter "strong" from its first step for `steps` steps.
Checkpoint first_steps_of_strong(std::int64_t steps) {
  const Config config = quick_config();
  Checkpoint c = begin_encounter(quick_relaxed(false), config, config.find_encounter("strong"));
  StepLoopOptions options = quiet_loop();
  options.stop_after_step = c.stage.clock.start_step + steps;
  EXPECT_EQ(run_encounter(c, config, options), LoopOutcome::interrupted);
  return c;
}

/// What this build computes, in the order of golden.toml.
std::vector<Value> measure(const Checkpoint& c) {
  const State& s = c.state;
  const auto& failures = c.observables.failures;
  const Vec3 perturber(s.perturber.position[0], s.perturber.position[1], s.perturber.position[2]);
  return {
      {"position_velocity_xxh3_128", position_velocity_hash(s)},
      {"state_hash", state_hash(s)},
      {"step", s.step},
      {"failed_springs", static_cast<std::int64_t>(std::count(s.springs.failed.begin(), s.springs.failed.end(), 1))},
      {"failure_events", static_cast<std::int64_t>(failures.size())},
      {"first_failed_spring", failures.empty() ? std::int64_t{-1} : std::int64_t{failures.front().spring}},
      {"time", s.time},
      {"kinetic_energy", measure_conservation(c.body, s).kinetic_energy},
      {"internal_kinetic_energy", internal_kinetic_energy(c.body, s)},
      {"max_shell_tension", max_shell_tension(c.body, s)},
      {"perturber_distance", (perturber - body_center_of_mass(c.body, s)).norm()},
  };
}

/// `values` as TOML lines, to paste into golden.toml after a deliberate change of physics.
std::string as_toml(const std::vector<Value>& values) {
  std::string text;
  for (const auto& [key, value] : values) {
    if (const auto* s = std::get_if<std::string>(&value)) {
      text += fmt::format("{} = \"{}\"\n", key, *s);
    } else if (const auto* n = std::get_if<std::int64_t>(&value)) {
      text += fmt::format("{} = {}\n", key, *n);
    } else {
      std::string x = fmt::format("{}", std::get<double>(value));  // shortest text that reads back exactly
      if (x.find_first_of(".en") == std::string::npos) x += ".0";   // a TOML float, not an integer
      text += fmt::format("{} = {}\n", key, x);
    }
  }
  return text;
}

}  // namespace

TEST(GoldenReference, QuickStrongEncounterFirstStepsMatchTheStoredValues) {
  const auto file = source_file("tests/reference/golden.toml");
  const toml::table golden = toml::parse_file(file.string());
  const toml::node_view<const toml::node> stored = golden[golden_table];
  ASSERT_TRUE(stored.is_table()) << file << ": no table [" << golden_table << "]";
  const auto steps = stored["steps"].value<std::int64_t>();
  const auto tolerance = stored["relative_tolerance"].value<double>();
  ASSERT_TRUE(steps && tolerance) << file << ": steps or relative_tolerance missing";

  const std::vector<Value> measured = measure(first_steps_of_strong(*steps));
  for (const auto& [key, value] : measured) {
    const auto node = stored[key];
    if (!node) {
      ADD_FAILURE() << file << ": no key " << key;
      continue;
    }
    if (const auto* s = std::get_if<std::string>(&value)) {
      if (same_gravity_kernel) {
        EXPECT_EQ(node.value_or(std::string()), *s) << key;
      }
    } else if (const auto* n = std::get_if<std::int64_t>(&value)) {
      EXPECT_EQ(node.value_or(std::int64_t{-2}), *n) << key;
    } else {
      const double expected = node.value_or(std::numeric_limits<double>::quiet_NaN()), actual = std::get<double>(value);
      EXPECT_LE(std::abs(actual - expected), *tolerance * std::abs(expected))
          << key << ": stored " << expected << ", computed " << actual;
    }
  }
  if (!same_gravity_kernel) std::cout << "note: built without AVX-512: the stored hashes were not compared\n";
  if (HasFailure())
    std::cout << "This build computes (for [" << golden_table << "] in " << file.string()
              << ", only after a deliberate change of physics):\n"
              << as_toml(measured);
}
