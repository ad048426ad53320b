// A body without a crust (the paper's run N) gets snapshots every 0.5 t_grav counted from
// pericenter, for its shape over time (Figure 5); a body with a crust keeps the four of Figure 6.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "base/errors.hpp"

#include "stages/build_stage.hpp"
#include "stages/encounter_stage.hpp"
#include "stages/stretch_stage.hpp"
#include "support/quick_workflow.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;

namespace {

/// `stretched` as if relaxed: begin_encounter needs a complete relax checkpoint, and the
/// snapshot plan depends only on the clock and the orbit.
Checkpoint as_relaxed(Checkpoint stretched) {
  stretched.stage.record = RelaxRecord{};
  stretched.stage.complete = true;
  return stretched;
}

Encounter encounter_n() {
  Encounter spec;
  spec.name = "N";
  spec.perturber_mass = 1.0;
  spec.pericenter = 2.13;
  spec.pericenter_speed = 1.84;
  return spec;
}

}  // namespace

TEST(ShapeSnapshots, BodyWithoutCrustIsSnapshottedEveryHalfTgravFromPericenter) {
  Config config = interior_only_config();
  const Checkpoint parent = as_relaxed(stretch_stage(build_stage(config), config));
  // dt = 0.004: +-1 t_grav are whole intervals (250 = 2 x 125 steps); dt = 0.003 (paper-N): they
  // are not (333 against 2 x 167), and the shape steps next to them are left out.
  for (const double dt : {0.004, 0.003}) {
    SCOPED_TRACE(dt);
    config.integrator.dt = dt;
    const Checkpoint c = begin_encounter(parent, config, encounter_n());
    const auto& record = c.stage.as<EncounterRecord>();
    const auto& steps = record.snapshot_steps;
    ASSERT_TRUE(std::is_sorted(steps.begin(), steps.end()));
    const std::int64_t interval = std::llround(0.5 / dt), offset = std::llround(1.0 / dt);
    auto has = [&](std::int64_t s) { return std::binary_search(steps.begin(), steps.end(), s); };
    // The four of Figure 6 are all there.
    for (std::int64_t s : {record.pericenter_step - offset, record.pericenter_step, record.pericenter_step + offset,
                           c.stage.end_step})
      EXPECT_TRUE(has(s)) << s;
    // No two snapshots closer than half an interval.
    for (std::size_t k = 1; k < steps.size(); ++k) EXPECT_GE(2 * (steps[k] - steps[k - 1]), interval) << steps[k];
    // Every shape step is there unless one of the four is within half an interval of it.
    auto near_figure6 = [&](std::int64_t s) {
      for (std::int64_t f : {record.pericenter_step - offset, record.pericenter_step + offset, c.stage.end_step})
        if (2 * std::abs(f - s) < interval) return true;
      return false;
    };
    std::size_t shape_steps = 0;
    for (std::int64_t s = record.pericenter_step; s > c.stage.clock.start_step; s -= interval)
      if (!near_figure6(s)) {
        EXPECT_TRUE(has(s)) << s;
        ++shape_steps;
      }
    for (std::int64_t s = record.pericenter_step + interval; s <= c.stage.end_step; s += interval)
      if (!near_figure6(s)) {
        EXPECT_TRUE(has(s)) << s;
        ++shape_steps;
      }
    // The encounter lasts ~2.8 t_grav: at least pericenter and +-0.5 t_grav besides the four.
    EXPECT_GE(shape_steps, 3u);
    EXPECT_GE(steps.size(), 6u);
    EXPECT_GT(steps.front(), c.stage.clock.start_step);
    EXPECT_LE(steps.back(), c.stage.end_step);
  }
}

TEST(ShapeSnapshots, BodyWithCrustKeepsTheFourSnapshotsOfFigure6) {
  const Config config = quick_config();
  const Checkpoint c = begin_encounter(as_relaxed(quick_stretched()), config, encounter_n());
  const auto& record = c.stage.as<EncounterRecord>();
  const std::int64_t offset = std::llround(1.0 / config.integrator.dt);
  const std::vector<std::int64_t> expected = {record.pericenter_step - offset, record.pericenter_step,
                                              record.pericenter_step + offset, c.stage.end_step};
  EXPECT_EQ(record.snapshot_steps, expected);
}

// issue 27 item 4: encounter.snapshot_interval gives any body a series every interval counted from
// pericenter (in steps, converted once), besides the four of Figure 6; too many is a one-line error.
TEST(ShapeSnapshots, TheSnapshotIntervalGivesABodyWithACrustASeries) {
  Config config = quick_config();
  config.encounter.snapshot_interval = 0.2;  // 50 steps at dt = 0.004
  const Checkpoint c = begin_encounter(as_relaxed(quick_stretched()), config, encounter_n());
  const auto& record = c.stage.as<EncounterRecord>();
  const auto& steps = record.snapshot_steps;
  const std::int64_t interval = 50, offset = std::llround(1.0 / config.integrator.dt);
  ASSERT_TRUE(std::is_sorted(steps.begin(), steps.end()));
  for (const std::int64_t figure6 : {record.pericenter_step - offset, record.pericenter_step,
                                     record.pericenter_step + offset, c.stage.end_step})
    EXPECT_TRUE(std::binary_search(steps.begin(), steps.end(), figure6)) << figure6;
  for (const std::int64_t s : steps)
    EXPECT_TRUE((s - record.pericenter_step) % interval == 0 || s == c.stage.end_step) << s;
  // Every interval from the first after the start to the end (the end within half an interval
  // of a series step replaces it).
  const std::int64_t span = c.stage.end_step - c.stage.clock.start_step;
  EXPECT_GE(static_cast<std::int64_t>(steps.size()), span / interval - 1);
  EXPECT_GT(steps.size(), 4u);
  // The default keeps the four.
  EXPECT_EQ(begin_encounter(as_relaxed(quick_stretched()), quick_config(), encounter_n())
                .stage.as<EncounterRecord>().snapshot_steps.size(),
            4u);
  config.encounter.snapshot_interval = 0.004;  // one per step over a long encounter: thousands of files
  config.encounter.start_distance = config.encounter.end_distance = 20.0;
  try {
    check_encounter(config, encounter_n());
    ADD_FAILURE() << "a snapshot every step was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("encounter.snapshot_interval = 0.004 t_grav gives"), std::string::npos)
        << e.what();
  }
}
