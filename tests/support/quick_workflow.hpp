#pragma once
// The quick workflow (workflows/quick.toml): its config, its body built, stretched, relaxed once.
#include <omp.h>

#include <initializer_list>
#include <stdexcept>
#include <string>

#include "io/checkpoint_file.hpp"
#include "io/state_hash.hpp"
#include "model/checkpoint.hpp"
#include "model/config.hpp"
#include "stages/build_stage.hpp"
#include "stages/relax_stage.hpp"
#include "stages/step_loop.hpp"
#include "stages/stretch_stage.hpp"
#include "support/files.hpp"
#include "support/shared_checkpoint.hpp"

namespace tidalcrust::test_support {

/// The small body of the command-line tests (shell level 2, 150 interior nodes, dt 0.005, a short
/// relax; the paper's crust support and cross springs, named as the defaults are others): the TOML
/// from [workflow] (named `name`) through [relax]; `shell_extra` lines go into [shell]. Callers
/// append their [relax] keys, [encounter] (with failure_rule = "paper") and encounters.
inline std::string small_body_toml(const std::string& name, const std::string& shell_extra = "") {
  return "[workflow]\nname = \"" + name + R"("
seed = 3
[interior]
count = 150
radius = 0.85
min_separation = 0.2
spring_distance = 0.46
spring_constant = 0.3
[shell]
level = 2
bending_constant = 0.03
)" + shell_extra + R"([cross]
distance = 0.4
spring_constant = 0.03
min_per_shell_node = 0
[integrator]
dt = 0.005
[relax]
duration = 0.5
probe_duration = 0.2
settle_duration = 0.2
crust_support = "paper"
)";
}

inline Config quick_config() { return load_config(workflow_file("quick.toml")); }

/// A small body without a crust (250 interior nodes, [shell] enabled = false), like paper-N.
inline Config interior_only_config() {
  return parse_config(R"(
[workflow]
name = "interior-only"
seed = 5
[interior]
count = 250
radius = 1.0
min_separation = 0.17
spring_distance = 0.4
spring_constant = 0.02
[shell]
enabled = false
[cross]
min_per_shell_node = 0
[integrator]
dt = 0.004
[relax]
crust_support = "paper"
[encounter]
failure_rule = "paper"
)",
                      "interior-only.toml");
}

/// Step loop options for tests: no progress lines, no checkpoint files.
inline StepLoopOptions quiet_loop() {
  StepLoopOptions options;
  options.quiet = true;
  return options;
}

/// The quick body as built (1042 particles).
inline const Checkpoint& quick_built() {
  static const Checkpoint built = build_stage(quick_config());
  return built;
}

inline const Checkpoint& quick_stretched() {
  static const Checkpoint stretched = stretch_stage(quick_built(), quick_config());
  return stretched;
}

namespace detail {
inline Checkpoint relax_quick_body(bool stability_probe) {
  Config config = quick_config();
  config.relax.stability_probe = stability_probe;
  Checkpoint c = begin_relax(quick_stretched(), config);
  if (run_relax(c, config, quiet_loop()) != LoopOutcome::finished)
    throw std::runtime_error("relaxing the quick body was interrupted");
  return c;
}
}  // namespace detail

/// The quick body relaxed for the full relax.duration, as `run` relaxes it. Without the
/// stability probe it takes about half the time and has the same state (the probe runs on a
/// copy); only the probe fields of its RelaxRecord are empty.
inline const Checkpoint& quick_relaxed(bool stability_probe = true) {
  if (stability_probe) {
    static const Checkpoint probed = shared_checkpoint("quick-relaxed", [] { return detail::relax_quick_body(true); });
    return probed;
  }
  static const Checkpoint unprobed =
      shared_checkpoint("quick-relaxed-unprobed", [] { return detail::relax_quick_body(false); });
  return unprobed;
}

/// Relaxes `stretched` by `config` on one thread and on two, expects the same state hash, and
/// returns the two-thread run (the thread count restored).
inline Checkpoint relaxed_alike_on_one_and_two_threads(const Checkpoint& stretched, const Config& config) {
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  Checkpoint one = begin_relax(stretched, config);
  EXPECT_EQ(run_relax(one, config, quiet_loop()), LoopOutcome::finished);
  omp_set_num_threads(2);
  Checkpoint two = begin_relax(stretched, config);
  EXPECT_EQ(run_relax(two, config, quiet_loop()), LoopOutcome::finished);
  omp_set_num_threads(threads);
  EXPECT_EQ(state_hash(one.state), state_hash(two.state));
  return two;
}

/// Relaxes `stretched` by `config` interrupted after each of `stops` steps (a mid-stage checkpoint
/// in a scratch folder named `name`), resumes from the file, and expects the state and record of
/// the straight run `straight`, bit for bit.
inline void expect_relax_resumes_bit_for_bit(const Checkpoint& stretched, const Config& config, const Checkpoint& straight,
                                             std::initializer_list<std::int64_t> stops, const std::string& name) {
  const ScratchFolder scratch(name);
  for (std::int64_t k : stops) {
    Checkpoint c = begin_relax(stretched, config);
    StepLoopOptions o = quiet_loop();
    o.mid_checkpoint = scratch.path / "relax.mid.h5";
    o.stop_after_step = c.stage.clock.start_step + k;
    ASSERT_EQ(run_relax(c, config, o), LoopOutcome::interrupted) << k;
    Checkpoint resumed = read_checkpoint(o.mid_checkpoint);
    o.stop_after_step = -1;
    ASSERT_EQ(run_relax(resumed, config, o), LoopOutcome::finished) << k;
    EXPECT_EQ(state_hash(resumed.state), state_hash(straight.state)) << k;
    EXPECT_EQ(resumed.state.liquid_rest_volume, straight.state.liquid_rest_volume) << k;
    EXPECT_EQ(resumed.stage.record, straight.stage.record) << k;
  }
}

}  // namespace tidalcrust::test_support
