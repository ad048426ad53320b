#include <gtest/gtest.h>

#include <cmath>

#include "base/errors.hpp"
#include "model/config.hpp"
#include "physics/shell_failure.hpp"

using namespace tidalcrust;

namespace {

/// Four particles on the x axis at 0, 1, 2, 4 and springs 0-1 (shell), 1-2 (shell),
/// 2-3 (interior), 0-2 (shell, failed already). Rest lengths chosen per test.
struct Line {
  Body body;
  State state;
  Line() {
    body.mass = {0.25, 0.25, 0.25, 0.25};
    body.species = {1, 1, 1, 0};
    body.springs = {{0, 1}, {1, 2}, {2, 3}, {0, 2}};
    body.spring_kind = {1, 1, 0, 1};
    state.time = 1.5;
    state.step = 42;
    state.position = {0, 0, 0, 1, 0, 0, 2, 0, 0, 4, 0, 0};
    state.velocity.assign(12, 0.0);
    state.springs.rest_length = {1.0, 1.0, 2.0, 2.0};
    state.springs.stiffness = {2.0, 3.0, 4.0, 5.0};
    state.springs.failed = {0, 0, 0, 1};
  }
};

}  // namespace

TEST(ShellFailure, StrainAndExtremesIgnoreInteriorAndFailedSprings) {
  Line l;
  l.state.springs.rest_length = {0.99, 1.02, 1.0, 1.0};  // +1.01%, -1.96%; interior +100%; failed +100%
  EXPECT_NEAR(spring_strain(l.body, l.state, 0), 1.0 / 0.99 - 1.0, 1e-15);
  EXPECT_NEAR(max_shell_tension(l.body, l.state), 1.0 / 0.99 - 1.0, 1e-15);
  EXPECT_NEAR(max_abs_shell_strain(l.body, l.state), 1.0 - 1.0 / 1.02, 1e-15);
}

TEST(ShellFailure, NothingFailsAtOrBelowThreshold) {
  Line l;
  l.state.springs.rest_length = {1.0, 1.0 / 1.002, 2.0, 1.0};
  // Spring 1 has strain 0.002 (up to rounding), spring 0 none, spring 3 failed already.
  EXPECT_FALSE(fail_most_strained_shell_spring(l.body, l.state, 0.0021, 0.005));
  EXPECT_EQ(l.state.springs.stiffness[1], 3.0);
  // Compression never fails.
  l.state.springs.rest_length = {1.5, 1.5, 2.0, 2.0};
  EXPECT_FALSE(fail_most_strained_shell_spring(l.body, l.state, 0.0, 0.005));
}

TEST(ShellFailure, OnlyTheMostStrainedShellSpringFails) {
  Line l;
  // Strains: spring 0 +0.5%, spring 1 +1%, interior spring 2 +100%, failed spring 3 +100%.
  l.state.springs.rest_length = {1.0 / 1.005, 1.0 / 1.01, 1.0, 1.0};
  auto event = fail_most_strained_shell_spring(l.body, l.state, 0.003, 0.005);
  ASSERT_TRUE(event);
  EXPECT_EQ(event->spring, 1);
  EXPECT_NEAR(event->strain, 0.01, 1e-12);
  EXPECT_EQ(event->step, 42);
  EXPECT_EQ(event->time, 1.5);
  EXPECT_EQ(event->position[0], 1.5);
  EXPECT_EQ(l.state.springs.failed, (std::vector<std::uint8_t>{0, 1, 0, 1}));
  EXPECT_EQ(l.state.springs.stiffness, (std::vector<double>{2.0, 3.0 * 0.005, 4.0, 5.0}));
  // Next check: spring 0 is the only candidate left.
  event = fail_most_strained_shell_spring(l.body, l.state, 0.003, 0.005);
  ASSERT_TRUE(event);
  EXPECT_EQ(event->spring, 0);
  EXPECT_FALSE(fail_most_strained_shell_spring(l.body, l.state, 0.003, 0.005));
}

TEST(ShellFailure, TiesGoToTheLowestIndex) {
  Line l;
  l.state.springs.rest_length = {0.9, 0.9, 2.0, 2.0};
  auto event = fail_most_strained_shell_spring(l.body, l.state, 0.003, 0.005);
  ASSERT_TRUE(event);
  EXPECT_EQ(event->spring, 0);
}

namespace {

/// Shell springs along the x axis, spring n joining particles 2n and 2n+1 (length 0.1) with
/// midpoints at x = 0, 0.5, 0.6, 3: n = 0 and 3 far from everything, 1 and 2 neighbours (0.1 apart).
struct Row {
  Body body;
  State state;
  Row() {
    const double mid[] = {0.0, 0.5, 0.6, 3.0};
    for (int n = 0; n < 4; ++n) {
      body.mass.insert(body.mass.end(), {0.1, 0.1});
      body.species.insert(body.species.end(), {1, 1});
      body.springs.push_back({2 * n, 2 * n + 1});
      body.spring_kind.push_back(1);
      state.position.insert(state.position.end(), {mid[n] - 0.05, 0, 0, mid[n] + 0.05, 0, 0});
      state.springs.stiffness.push_back(1.0);
      state.springs.failed.push_back(0);
    }
    state.velocity.assign(state.position.size(), 0.0);
    state.step = 100;
    // Strains 1%, 3%, 2%, 0.05%.
    for (double strain : {0.01, 0.03, 0.02, 0.0005}) state.springs.rest_length.push_back(0.1 / (1 + strain));
  }
  FailureRule local(std::int64_t interval, double exclusion) const {
    FailureRule rule;
    rule.kind = FailureRuleKind::local;
    rule.failure_strain = 0.001;
    rule.failed_stiffness_factor = 0.005;
    rule.interval = interval;
    rule.exclusion_distance = exclusion;
    return rule;
  }
};

}  // namespace

TEST(LocalFailureRule, EveryOverStrainedNeighbourhoodFailsMostStrainedFirst) {
  Row r;
  std::vector<FailureEvent> log;
  // Exclusion 0.2: springs 1 and 2 (0.1 apart) share a neighbourhood, 0 is alone, 3 is below eps_S.
  EXPECT_EQ(apply_failure_rule(r.local(5, 0.2), r.body, r.state, 0, log), 2u);
  ASSERT_EQ(log.size(), 2u);
  EXPECT_EQ(log[0].spring, 1);  // 3%: the most strained first
  EXPECT_EQ(log[1].spring, 0);  // 1%: far from spring 1; spring 2 (2%) is excluded by spring 1
  EXPECT_EQ(r.state.springs.failed, (std::vector<std::uint8_t>{1, 1, 0, 0}));
  EXPECT_DOUBLE_EQ(r.state.springs.stiffness[1], 0.005);
  EXPECT_EQ(log[0].step, 100);
}

TEST(LocalFailureRule, ANeighbourhoodWaitsOneRelaxationIntervalAfterAFailure) {
  Row r;
  std::vector<FailureEvent> log;
  apply_failure_rule(r.local(5, 0.2), r.body, r.state, 0, log);
  for (std::int64_t step = 101; step <= 104; ++step) {  // spring 1 failed at 100: 100 > step - 5
    r.state.step = step;
    EXPECT_EQ(apply_failure_rule(r.local(5, 0.2), r.body, r.state, 0, log), 0u) << "step " << step;
  }
  r.state.step = 105;  // 5 steps later the neighbourhood has relaxed
  EXPECT_EQ(apply_failure_rule(r.local(5, 0.2), r.body, r.state, 0, log), 1u);
  EXPECT_EQ(log.back().spring, 2);
}

TEST(LocalFailureRule, WithoutExclusionEveryOverStrainedSpringFails) {
  Row r;
  std::vector<FailureEvent> log;
  EXPECT_EQ(apply_failure_rule(r.local(1, 1e-9), r.body, r.state, 0, log), 3u);
  EXPECT_EQ(log[0].spring, 1);
  EXPECT_EQ(log[1].spring, 2);
  EXPECT_EQ(log[2].spring, 0);
}

TEST(PaperFailureRule, OneSpringPerCheckEveryFailInterval) {
  Row r;
  FailureRule rule = r.local(3, 0);
  rule.kind = FailureRuleKind::paper;
  std::vector<FailureEvent> log;
  EXPECT_EQ(apply_failure_rule(rule, r.body, r.state, 99, log), 0u);  // 1 step after the start: no check
  EXPECT_EQ(apply_failure_rule(rule, r.body, r.state, 97, log), 1u);  // 3 steps after: the worst fails
  EXPECT_EQ(log.at(0).spring, 1);
}

TEST(FailureRuleSchedule, LocalIntervalIsCrossingTimesInStepsConvertedOnce) {
  Config config;
  config.encounter.failure_rule = FailureRuleKind::local;
  config.encounter.relaxation_crossings = 2.0;
  config.encounter.exclusion_radius = 1.5;
  config.shell.mass = 0.07;
  Row r;
  r.body.mass.assign(r.body.mass.size(), 0.07 / 8);
  double mean = 0;
  for (double l : r.state.springs.rest_length) mean += l / 4;
  const double V_SP = std::sqrt(1.0 * 4 * std::acos(-1.0) / 0.07);  // eq. 19, k_S = 1
  const FailureRule rule = make_failure_rule(config, 0.002, std::nullopt, r.body, r.state, 0.001);
  EXPECT_EQ(rule.kind, FailureRuleKind::local);
  EXPECT_EQ(rule.interval, std::llround(2.0 * mean / V_SP / 0.001));
  EXPECT_NEAR(rule.exclusion_distance, 1.5 * mean, 1e-15);
  EXPECT_EQ(rule.failure_strain, 0.002);
  // An encounter's own relaxation interval wins over the workflow's.
  EXPECT_EQ(make_failure_rule(config, 0.002, 0.5, r.body, r.state, 0.001).interval,
            std::llround(0.5 * mean / V_SP / 0.001));
  // Half the time step: twice the steps, the same physical interval (to rounding).
  EXPECT_NEAR(static_cast<double>(make_failure_rule(config, 0.002, std::nullopt, r.body, r.state, 0.0005).interval),
              2.0 * static_cast<double>(rule.interval), 1.0);
  config.encounter.failure_rule = FailureRuleKind::paper;
  config.encounter.fail_interval = 3;
  EXPECT_EQ(make_failure_rule(config, 0.002, std::nullopt, r.body, r.state, 0.001).interval, 3);
}
