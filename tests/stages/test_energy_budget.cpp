// The encounter's energy budget (docs/energy-budget.md) on the relaxed quick body: the
// conserved total K + U + damping_dissipated + failure_released - hinge_residual_work stays
// constant up to the leapfrog's O(dt^2) error, undamped, damped and with failures; and each
// accumulator is what it claims to be.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "analysis/energy_budget.hpp"
#include "forces/force_field.hpp"
#include "integrate/leapfrog.hpp"
#include "physics/conservation.hpp"
#include "stages/encounter_stage.hpp"
#include "support/force_test_bodies.hpp"
#include "support/quick_workflow.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;

namespace {

struct BudgetRun {
  std::vector<TimeseriesSample> samples;
  EnergyLedger ledger;
  std::size_t failures = 0;
};

/// The quick workflow's "strong" encounter (the T5 orbit: M2 = 0.5, q = 1.84, V_q = 1.6; ~900
/// steps of dt = 0.004) from the relaxed quick body.
const Encounter strong = encounter_of("strong", 0.5, 1.84, 1.6);

/// The strong encounter at damping gamma, failure strain eps_S (failures checked every step),
/// time step dt * dt_factor, sampled every 0.04 t_grav.
BudgetRun run_encounter_budget(double gamma, double failure_strain, double dt_factor) {
  Config config = quick_config();
  config.encounter.damping = gamma;
  config.encounter.fail_interval = 1;
  config.encounter.sample_interval = 10;
  config.encounter.checkpoint_interval = 0;
  scale_time_step(config, dt_factor);
  Encounter spec = strong;
  spec.failure_strain = failure_strain;
  Checkpoint c = begin_encounter(quick_relaxed(false), config, spec);
  EXPECT_EQ(run_encounter(c, config, quiet_loop()), LoopOutcome::finished);
  return {c.observables.timeseries, c.stage.as<EncounterRecord>().energy, c.observables.failures.size()};
}

/// max over samples of |E - E_0| with E = conserved_energy() + extra(sample), relative to 3/5.
template <typename Extra>
double max_error(const std::vector<TimeseriesSample>& samples, Extra extra) {
  const double e0 = samples.front().conserved_energy() + extra(samples.front());
  double worst = 0;
  for (const auto& s : samples) worst = std::max(worst, std::abs(s.conserved_energy() + extra(s) - e0));
  return worst / uniform_sphere_binding_energy;
}
double max_error(const std::vector<TimeseriesSample>& samples) {
  return max_error(samples, [](const TimeseriesSample&) { return 0.0; });
}

}  // namespace

TEST(EnergyBudget, UndampedWithoutFailuresTheTotalIsConservedToSecondOrder) {
  // Measured: 1.22e-7 of 3/5 at dt = 0.004, 3.06e-8 at dt/2 (ratio 4.00), the same samples in
  // time; allowed: below 5e-7, ratio 3 to 5.
  const BudgetRun coarse = run_encounter_budget(0.0, 1.0, 1.0), fine = run_encounter_budget(0.0, 1.0, 0.5);
  ASSERT_EQ(coarse.failures, 0u);
  ASSERT_EQ(coarse.samples.size(), fine.samples.size());
  EXPECT_EQ(coarse.ledger.damping_dissipated, 0.0);
  EXPECT_EQ(coarse.ledger.failure_released, 0.0);
  const double e1 = max_error(coarse.samples), e2 = max_error(fine.samples);
  std::printf("[ info ] undamped: max |E - E0|/(3/5) = %.3g at dt, %.3g at dt/2 (ratio %.2f); hinge work %.3g\n", e1,
              e2, e1 / e2, coarse.ledger.hinge_residual_work);
  EXPECT_LT(e1, 5e-7);
  EXPECT_GT(e1 / e2, 3.0);
  EXPECT_LT(e1 / e2, 5.0);
}

TEST(EnergyBudget, DampedTheTotalWithTheDampingWorkIsConserved) {
  // gamma = 1: the damping takes out far more than the leapfrog error (measured: 6.4e-6 G M^2/R
  // dissipated; max error 1.2e-7 of 3/5 with the term, 1.1e-5 without).
  const BudgetRun r = run_encounter_budget(1.0, 1.0, 1.0);
  ASSERT_EQ(r.failures, 0u);
  const double error = max_error(r.samples);
  const double without = max_error(r.samples, [](const TimeseriesSample& s) { return -s.damping_dissipated; });
  std::printf("[ info ] damped: dissipated %.3g, max error %.3g with the damping term, %.3g without\n",
              r.ledger.damping_dissipated, error, without);
  EXPECT_GT(r.ledger.damping_dissipated, 0.0);
  EXPECT_LT(error, 5e-7);
  EXPECT_GT(without, 50 * error);  // measured 88x
}

TEST(EnergyBudget, WithFailuresTheTotalWithTheReleasedEnergyIsConserved) {
  const BudgetRun r = run_encounter_budget(0.01, 0.003, 1.0);
  ASSERT_GT(r.failures, 50u);
  const double error = max_error(r.samples);
  const double without = max_error(r.samples, [](const TimeseriesSample& s) { return -s.failure_released; });
  std::printf("[ info ] failures: %zu, released %.3g, max error %.3g with the failure term, %.3g without\n",
              r.failures, r.ledger.failure_released, error, without);
  EXPECT_GT(r.ledger.failure_released, 0.0);
  EXPECT_LT(error, 5e-7);
  EXPECT_GT(without, 10 * error);
}

TEST(EnergyBudget, DampingWorkIsExactlyTheKineticEnergyTheKickRemoves) {
  // With damping the only force (no stiffness, no hinges, no gravity), one step's kinetic energy
  // change is minus the measured damping work, to rounding.
  Checkpoint c = small_body();
  shake(c.state, 5e-3, 0.05, 11);
  std::fill(c.state.springs.stiffness.begin(), c.state.springs.stiffness.end(), 0.0);
  std::fill(c.body.hinge_stiffness.begin(), c.body.hinge_stiffness.end(), 0.0);
  ForceOptions options = damped(5.0);
  options.self_gravity = false;
  ForceField field(c.body, options);
  Leapfrog leapfrog(field, clock_at(c.state, 0.003));
  leapfrog.measure_work(true);
  for (int step = 0; step < 5; ++step) {
    const double before = measure_conservation(c.body, c.state).kinetic_energy;
    leapfrog.step(c.state);
    const double change = measure_conservation(c.body, c.state).kinetic_energy - before;
    ASSERT_GT(leapfrog.last_work().damping_removed, 0.0);
    EXPECT_NEAR(change, -leapfrog.last_work().damping_removed, 1e-12 * leapfrog.last_work().damping_removed);
    EXPECT_EQ(leapfrog.last_work().hinge_added, 0.0);
  }
}

TEST(EnergyBudget, ReportsTheEnergyPutIntoTheBodyAndTheImpulseEstimate) {
  const BudgetRun r = run_encounter_budget(0.01, 1.0, 1.0);
  const EnergyBudget b = energy_budget(r.samples, strong);
  // Eq. 3: Delta v = 2 m /(q^2 V_q); eq. 4: M Delta v^2.
  const double delta_v = 2 * 0.5 / (1.84 * 1.84 * 1.6);
  EXPECT_DOUBLE_EQ(b.impulse_estimate, delta_v * delta_v);
  EXPECT_DOUBLE_EQ(b.impulse_estimate_uniform_sphere, delta_v * delta_v / 5);
  EXPECT_DOUBLE_EQ(b.internal_change, b.internal_kinetic_change + b.elastic_change + b.self_gravity_change);
  std::printf("[ info ] deposited %.3g (kinetic %.3g, elastic %.3g, self-gravity %.3g), dissipated %.3g; "
              "impulse estimates %.3g (eq. 4), %.3g (uniform sphere)\n",
              b.internal_change, b.internal_kinetic_change, b.elastic_change, b.self_gravity_change, b.dissipated,
              b.impulse_estimate, b.impulse_estimate_uniform_sphere);
  EXPECT_GT(b.internal_change, 0.0);  // the tides do work on the body
  EXPECT_LT(b.max_error, 5e-7);
  // Without a budget in the samples (the relax stage), the errors and changes are NaN.
  std::vector<TimeseriesSample> bare(2);
  EXPECT_TRUE(std::isnan(energy_budget(bare, strong).max_error));
}
