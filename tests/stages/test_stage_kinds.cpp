// The table of stage kinds (stages/stage_kinds.hpp) is consistent with the records and the
// configuration, and run_stage (stages/run_stage.hpp) locks before it removes or begins anything.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "base/errors.hpp"
#include "io/checkpoint_file.hpp"
#include "io/checkpoint_names.hpp"
#include "io/stage_lock.hpp"
#include "model/config.hpp"
#include "stages/run_stage.hpp"
#include "stages/stage_kinds.hpp"
#include "support/files.hpp"
#include "support/quick_workflow.hpp"

using namespace tidalcrust;
namespace fs = std::filesystem;

TEST(StageKinds, OneRowPerRecordInPipelineOrderWithWhatItsKindNeeds) {
  ASSERT_EQ(stage_kinds().size(), stage_count);
  const Config config;
  bool per_encounter_seen = false;
  for (std::size_t i = 0; i < stage_kinds().size(); ++i) {
    const StageKind& kind = stage_kinds()[i];
    EXPECT_EQ(static_cast<std::size_t>(kind.id), i);
    EXPECT_STREQ(kind.name(), stage_names[i]);
    EXPECT_EQ(&stage_kind(kind.id), &kind);
    EXPECT_NE(std::string(kind.summary), "") << kind.name();
    ASSERT_NE(kind.begin, nullptr) << kind.name();
    // Parents come earlier in the pipeline (or are the stage itself: an encounter branches from one).
    for (std::size_t p = i + 1; p < stage_count; ++p) EXPECT_FALSE(kind.parents.contains(static_cast<StageId>(p)));
    EXPECT_EQ(kind.parents.empty(), i == 0) << "only the first stage begins from the configuration alone";
    // The body chain first, then the stages run once per encounter.
    if (per_encounter_seen) {
      EXPECT_TRUE(kind.per_encounter) << kind.name();
    }
    per_encounter_seen = per_encounter_seen || kind.per_encounter;
    if (kind.stepping()) {
      // Its checkpoint interval is an integer key that changes no result.
      ASSERT_NE(kind.checkpoint_interval_key, nullptr) << kind.name();
      EXPECT_GE(kind.checkpoint_interval(config), 0);
      bool found = false;
      for (const KeyInfo& key : describe_keys(config))
        if (key.section + "." + key.name == kind.checkpoint_interval_key) {
          found = true;
          EXPECT_TRUE(key.readers.empty() && key.conditional_readers.empty()) << kind.checkpoint_interval_key;
        }
      EXPECT_TRUE(found) << kind.checkpoint_interval_key;
      EXPECT_EQ(kind.doing, nullptr) << kind.name();
    } else {
      EXPECT_EQ(kind.checkpoint_interval_key, nullptr) << kind.name();
      ASSERT_NE(kind.doing, nullptr) << kind.name();
      EXPECT_NE(kind.doing(config), "") << kind.name();
    }
  }
  EXPECT_TRUE(per_encounter_seen);
  EXPECT_EQ(stage_kind(StageId::relax).checkpoint_interval(config), config.relax.checkpoint_interval);
  EXPECT_EQ(stage_kind(StageId::encounter).checkpoint_interval(config), config.encounter.checkpoint_interval);
}

// Another process holds the lock: the single-stage way refuses (naming the holder) before it
// removes what a superseded run left or begins the stage; `run`'s way refuses a holder computing
// another version. The leftovers are still there afterwards.
TEST(StageKinds, RunStageLocksBeforeItRemovesOrBeginsAnything) {
  const test_support::ScratchFolder scratch("run_stage_lock");
  const fs::path file = scratch.path / "relax.h5";
  const fs::path diagnostic = sibling_checkpoint(file, "diagnostic"), mid = sibling_checkpoint(file, "mid");
  test_support::write_file(diagnostic, "left by a superseded run");
  test_support::write_file(mid, "left by a superseded run");
  LockAttempt held = try_lock_stage(file, "another version");
  ASSERT_TRUE(held.lock);

  const Config config = test_support::quick_config();
  const StageJob job{&stage_kind(StageId::relax), "relax", file, &test_support::quick_stretched(), "stretch.h5",
                     nullptr};
  for (const bool wait : {false, true}) {
    StageRunOptions options;
    options.wait_for_same_version = wait;
    options.find_resume = wait;
    options.reuse_current = wait;
    try {
      run_stage(job, config, std::move(options));
      ADD_FAILURE() << "not refused";
    } catch (const InputError& err) {
      EXPECT_NE(std::string(err.what()).find(lock_path(file).string()), std::string::npos) << err.what();
    }
    EXPECT_EQ(test_support::read_file(diagnostic), "left by a superseded run");
    EXPECT_EQ(test_support::read_file(mid), "left by a superseded run");
    EXPECT_FALSE(fs::exists(file));
  }
}
