// The quick encounter with [gravity] method = "tree" (issue 13): the same bits on one and two
// threads and after stopping and resuming from mid-stage checkpoint files (the tree is rebuilt
// from the positions read back), and other bits than the direct sum. The runs end at
// `last_step` (about a third of the encounter, with several energy samples) to keep the test short.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "io/checkpoint_file.hpp"
#include "io/state_hash.hpp"
#include "model/config.hpp"
#include "stages/encounter_stage.hpp"
#include "support/files.hpp"
#include "support/quick_workflow.hpp"

namespace tidalcrust {
namespace {

namespace fs = std::filesystem;
using namespace test_support;

Config tree_config() {
  Config config = quick_config();
  config.gravity.method = GravityMethod::tree;
  config.gravity.force_error = 1e-4;
  return config;
}

constexpr std::int64_t steps_run = 240;

/// Runs c (tree gravity) until start + steps_run, where it stops without a file.
void run_to_last_step(Checkpoint& c, const Config& config) {
  StepLoopOptions options = quiet_loop();
  options.stop_after_step = c.stage.clock.start_step + steps_run;
  ASSERT_EQ(run_encounter(c, config, options), LoopOutcome::interrupted);
  ASSERT_EQ(c.state.step, c.stage.clock.start_step + steps_run);
}

/// The quick "strong" encounter with tree gravity, straight through on 2 threads.
const Checkpoint& straight_tree_run() {
  static const Checkpoint done = [] {
    const Config config = tree_config();
    Checkpoint c = begin_encounter(quick_relaxed(false), config, config.find_encounter("strong"));
    omp_set_num_threads(2);
    run_to_last_step(c, config);
    return c;
  }();
  return done;
}

}  // namespace

TEST(TreeGravityStages, EncounterIsBitIdenticalOnOneAndTwoThreads) {
  const Checkpoint& straight = straight_tree_run();
  const Config config = tree_config();
  Checkpoint c = begin_encounter(quick_relaxed(false), config, config.find_encounter("strong"));
  omp_set_num_threads(1);
  run_to_last_step(c, config);
  omp_set_num_threads(2);
  EXPECT_EQ(state_hash(c.state), state_hash(straight.state));
  EXPECT_NE(state_hash(c.state), state_hash(quick_relaxed(false).state));  // it moved
}

TEST(TreeGravityStages, StoppedAndResumedEncounterIsBitIdentical) {
  const Checkpoint& straight = straight_tree_run();
  const Config config = tree_config();
  const ScratchFolder scratch("tree_resume");
  const fs::path output = scratch.path / "strong.h5";
  Checkpoint c = begin_encounter(quick_relaxed(false), config, config.find_encounter("strong"));
  const std::int64_t start = c.stage.clock.start_step;
  for (std::int64_t stop : {start + 31, start + 157}) {
    StepLoopOptions options = quiet_loop();
    options.stop_after_step = stop;
    options.mid_checkpoint = scratch.path / "strong.mid.h5";
    ASSERT_EQ(run_encounter(c, config, options, output), LoopOutcome::interrupted);
    c = read_checkpoint(options.mid_checkpoint);  // continue only from what the file holds
    ASSERT_EQ(c.state.step, stop);
  }
  run_to_last_step(c, config);
  EXPECT_EQ(state_hash(c.state), state_hash(straight.state));
  ASSERT_GT(c.observables.timeseries.size(), 10u);
  ASSERT_EQ(c.observables.timeseries.size(), straight.observables.timeseries.size());
  for (std::size_t i = 0; i < c.observables.timeseries.size(); ++i)  // the tree's energy too
    EXPECT_EQ(c.observables.timeseries[i].self_gravity_energy, straight.observables.timeseries[i].self_gravity_energy);
}

TEST(TreeGravityStages, TreeAndDirectAreDifferentRuns) {
  const Config direct = quick_config();
  Checkpoint c = begin_encounter(quick_relaxed(false), direct, direct.find_encounter("strong"));
  StepLoopOptions options = quiet_loop();
  const std::int64_t stop = c.stage.clock.start_step + 20;
  options.stop_after_step = stop;
  ASSERT_EQ(run_encounter(c, direct, options), LoopOutcome::interrupted);
  const Config tree = tree_config();
  Checkpoint t = begin_encounter(quick_relaxed(false), tree, tree.find_encounter("strong"));
  ASSERT_EQ(run_encounter(t, tree, options), LoopOutcome::interrupted);
  EXPECT_NE(state_hash(c.state), state_hash(t.state));
  // ... and close: 20 steps with a 1e-4 gravity error move no particle by more than 1e-6 R.
  double worst = 0;
  for (std::size_t k = 0; k < c.state.position.size(); ++k)
    worst = std::max(worst, std::abs(c.state.position[k] - t.state.position[k]));
  EXPECT_LT(worst, 1e-5);
}

}  // namespace tidalcrust
