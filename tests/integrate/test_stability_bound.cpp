// The stability bound of springs and hinges with node masses (integrate/stability_bound.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "base/errors.hpp"
#include "forces/force_field.hpp"
#include "integrate/leapfrog.hpp"
#include "integrate/stability_bound.hpp"
#include "model/body.hpp"
#include "model/state.hpp"

using namespace tidalcrust;

namespace {

/// Two particles of mass m joined by one spring of stiffness k along x.
void two_node_spring(Body& body, State& state, double m1, double m2, double k) {
  body.mass = {m1, m2};
  body.species = {0, 0};
  body.springs = {{0, 1}};
  body.spring_kind = {static_cast<std::uint8_t>(SpringKind::interior)};
  state.position = {0, 0, 0, 0.1, 0, 0};
  state.velocity.assign(6, 0.0);
  state.springs.rest_length = {0.1};
  state.springs.stiffness = {k};
  state.springs.failed = {0};
}

}  // namespace

TEST(StabilityBound, TwoEqualMassesOnOneSpringGiveTheAnalyticTwoOverOmega) {
  Body body;
  State state;
  const double m = 0.003, k = 0.076;
  two_node_spring(body, state, m, m, k);
  const StabilityBound bound = stability_bound(body, state);
  const double omega = std::sqrt(k / (m / 2));  // the one mode: reduced mass m/2
  EXPECT_NEAR(bound.safe_dt, 2.0 / omega, 1e-15);
  // The one-node Rayleigh quotient k/m is half of omega^2: unstable above sqrt(2) * 2/omega.
  EXPECT_NEAR(bound.unstable_dt, std::sqrt(2.0) * 2.0 / omega, 1e-15);
  EXPECT_DOUBLE_EQ(bound.safe_limit.springs, 1.0);
}

TEST(StabilityBound, DampingShrinksTheBoundToTheLeapfrogsExactLimit) {
  // One mode: relative coordinate r'' = -omega^2 r - gamma r' (reduced mass m/2). Our
  // drift-kick-drift is stable iff omega^2 dt^2 + 2 gamma dt <= 4, and the Gershgorin sums are
  // exact here, so the bound is that limit: 4 / (gamma + sqrt(gamma^2 + 4 omega^2)).
  Body body;
  State state;
  const double m = 0.003, k = 0.076, gamma = 50.0;
  two_node_spring(body, state, m, m, k);
  const double omega2 = k / (m / 2);
  const StabilityBound bound = stability_bound(body, state, gamma);
  const double limit = 4.0 / (gamma + std::sqrt(gamma * gamma + 4 * omega2));
  EXPECT_NEAR(bound.safe_dt, limit, 1e-15);
  EXPECT_LT(bound.safe_dt, 0.2 * stability_bound(body, state).safe_dt);  // damping-limited here
  EXPECT_DOUBLE_EQ(bound.damping_rate, gamma);
  EXPECT_DOUBLE_EQ(stability_bound(body, state, gamma).unstable_dt, stability_bound(body, state).unstable_dt);

  // The project's integrator with the project's damped spring: 2% below the limit a stretch
  // decays, 2% above it grows (or is caught as a blow-up).
  ForceOptions options;
  options.damping = gamma;
  options.self_gravity = false;
  ForceField field(body, options);
  auto stretch_after = [&](double dt) {
    State s = state;
    s.position[3] += 1e-3;
    try {
      Leapfrog(field, StepClock{0.0, 0, dt}).advance(s, 400);
    } catch (const SimulationError&) {
      return std::numeric_limits<double>::infinity();
    }
    return std::abs(s.position[3] - s.position[0] - 0.1);
  };
  EXPECT_LT(stretch_after(0.98 * limit), 1e-4);
  EXPECT_GT(stretch_after(1.02 * limit), 1e-2);
}

TEST(StabilityBound, UnequalMassesStayBelowTheTrueLimit) {
  Body body;
  State state;
  const double m1 = 0.001, m2 = 0.004, k = 0.05;
  two_node_spring(body, state, m1, m2, k);
  const StabilityBound bound = stability_bound(body, state);
  const double omega = std::sqrt(k * (1 / m1 + 1 / m2));
  EXPECT_LE(bound.safe_dt, 2.0 / omega);        // safe: never above the true limit
  EXPECT_GE(bound.unstable_dt, 2.0 / omega);    // unstable: never below it
  EXPECT_EQ(bound.safe_limit.node, 0u);         // the light end limits
}

TEST(StabilityBound, AHingeStiffensItsNodes) {
  // Two triangles sharing the edge 2-3, folded slightly; one hinge, no springs.
  Body body;
  State state;
  body.mass = {0.001, 0.001, 0.001, 0.001};
  body.species = {1, 1, 1, 1};
  body.hinges = {{0, 1, 2, 3}};
  body.hinge_stiffness = {0.0075};
  state.position = {0.0, 0.0866, 0.0, 0.0, -0.0866, 0.001, -0.05, 0.0, 0.0, 0.05, 0.0, 0.0};
  state.velocity.assign(12, 0.0);
  state.hinges.rest_angle = {0.0};
  const StabilityBound bound = stability_bound(body, state);
  ASSERT_GT(bound.safe_dt, 0);
  EXPECT_DOUBLE_EQ(bound.safe_limit.hinges, 1.0);
  EXPECT_LE(bound.safe_dt, bound.unstable_dt);
  // Four times the stiffness: half the step.
  body.hinge_stiffness = {0.03};
  EXPECT_NEAR(stability_bound(body, state).safe_dt, bound.safe_dt / 2, 1e-12 * bound.safe_dt);
}
