#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <numbers>

#include "physics/conservation.hpp"
#include "model/derived_quantities.hpp"
#include "base/errors.hpp"
#include "support/force_test_bodies.hpp"
#include "integrate/leapfrog.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;

namespace {

/// Spring damping of the lively bodies below, 1/t_grav.
constexpr double lively_damping = 5.0;

/// A shaken small body (to be damped at lively_damping) with a perturber passing at ~2.5 R.
Checkpoint lively_body() {
  Checkpoint c = small_body();
  shake(c.state, 3e-3, 0.02, 4);
  c.state.perturber = {true, 0.5, {-1.0, 2.5, 0.2}, {0.9, 0.0, 0.0}};
  return c;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

bool same_state(const State& a, const State& b) {
  return a.step == b.step && std::memcmp(&a.time, &b.time, sizeof(double)) == 0 && same_bits(a.position, b.position) &&
         same_bits(a.velocity, b.velocity) &&
         std::memcmp(&a.perturber.position, &b.perturber.position, sizeof(a.perturber.position)) == 0 &&
         std::memcmp(&a.perturber.velocity, &b.perturber.velocity, sizeof(a.perturber.velocity)) == 0;
}

}  // namespace

TEST(Leapfrog, ConservesMomentumAndAngularMomentumOverDampedSteps) {
  Checkpoint c = lively_body();
  const double dt = c.stage.clock.dt;
  ForceField field(c.body, damped(lively_damping));
  Leapfrog leapfrog(field, clock_at(c.state, dt));
  const Conservation before = measure_conservation(c.body, c.state);
  // Scales: sum of |m v| and of |m x x v| over body and perturber.
  double p_scale = 0, l_scale = 0;
  auto add_scale = [&](double m, const double* x, const double* v) {
    const Vec3 xv(x[0], x[1], x[2]), vv(v[0], v[1], v[2]);
    p_scale += m * vv.norm();
    l_scale += m * xv.cross(vv).norm();
  };
  for (std::size_t i = 0; i < c.body.particle_count(); ++i)
    add_scale(c.body.mass[i], &c.state.position[3 * i], &c.state.velocity[3 * i]);
  add_scale(c.state.perturber.mass, c.state.perturber.position.data(), c.state.perturber.velocity.data());

  State undamped = c.state;
  ForceField undamped_field(c.body);
  Leapfrog(undamped_field, clock_at(undamped, dt)).advance(undamped, 300);
  leapfrog.advance(c.state, 300);
  const Conservation after = measure_conservation(c.body, c.state);
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(std::abs(after.momentum[k] - before.momentum[k]), 1e-12 * p_scale) << k;
    EXPECT_LT(std::abs(after.angular_momentum[k] - before.angular_momentum[k]), 1e-12 * l_scale) << k;
  }
  // Damping took energy out of the internal motion, and the perturber moved.
  EXPECT_LT(internal_kinetic_energy(c.body, c.state), 0.5 * internal_kinetic_energy(c.body, undamped));
  EXPECT_EQ(c.state.step, 300);
  EXPECT_GT(c.state.perturber.position[0], -1.0 + 0.5 * 0.9 * 300 * dt);
}

TEST(Leapfrog, KeplerOrbitKeepsEnergyAndReachesThePericenter) {
  // A perturber of mass 0.5 around a single particle of mass 1: a = 1, e = 0.5, started at
  // apocenter; mu = G (m1 + m2). Pericenter q = a (1 - e) = 0.5.
  Body body;
  body.mass = {1.0};
  body.species = {0};
  const double m1 = 1.0, m2 = 0.5, mu = m1 + m2, a = 1.0, e = 0.5;
  const double apocenter = a * (1 + e), v_apo = std::sqrt(mu * (1 - e) / (a * (1 + e)));
  State state;
  state.position = {-m2 / mu * apocenter, 0, 0};  // centre of mass at rest at the origin
  state.velocity = {0, -m2 / mu * v_apo, 0};
  state.perturber = {true, m2, {m1 / mu * apocenter, 0, 0}, {0, m1 / mu * v_apo, 0}};
  const double period = 2 * std::numbers::pi * std::sqrt(a * a * a / mu);
  const int steps = 4000;
  ForceField field(body);
  Leapfrog leapfrog(field, clock_at(state, period / steps));

  auto separation = [&] {
    return std::hypot(state.perturber.position[0] - state.position[0], state.perturber.position[1] - state.position[1],
                      state.perturber.position[2] - state.position[2]);
  };
  auto energy = [&] {
    const Conservation c = measure_conservation(body, state);
    return c.kinetic_energy - m1 * m2 / separation();
  };
  const double e0 = energy();
  EXPECT_NEAR(e0, -m1 * m2 / (2 * a), 1e-14);
  double closest = separation(), worst_energy = 0;
  for (int s = 0; s < steps; ++s) {
    leapfrog.step(state);
    closest = std::min(closest, separation());
    worst_energy = std::max(worst_energy, std::abs(energy() - e0));
  }
  EXPECT_NEAR(closest, a * (1 - e), 1e-4);
  EXPECT_LT(worst_energy, 1e-4 * std::abs(e0));
  // After one period the perturber is back at apocenter.
  EXPECT_NEAR(separation(), apocenter, 1e-4);
  EXPECT_NEAR(state.time, period, 1e-12);
}

TEST(Leapfrog, TimeIsDerivedFromTheStepCount) {
  Checkpoint c = small_body();
  c.state.time = 1.5;
  c.state.step = 1000;
  ForceField field(c.body);
  Leapfrog leapfrog(field, clock_at(c.state, c.stage.clock.dt));
  leapfrog.advance(c.state, 7);
  EXPECT_EQ(c.state.step, 1007);
  EXPECT_EQ(c.state.time, 1.5 + 7.0 * c.stage.clock.dt);
}

TEST(Leapfrog, ResumedRunEqualsStraightRun) {
  Checkpoint c = lively_body();
  ForceField field(c.body, damped(lively_damping));
  const StepClock clock = clock_at(c.state, c.stage.clock.dt);
  State straight = c.state;
  Leapfrog(field, clock).advance(straight, 20);
  State resumed = c.state;
  Leapfrog(field, clock).advance(resumed, 9);
  Leapfrog(field, clock).advance(resumed, 11);  // a fresh integrator, as after a restart
  EXPECT_TRUE(same_state(straight, resumed));
}

TEST(Leapfrog, BitwiseIdenticalWithOneAndTwoThreads) {
  Checkpoint c = quick_body();
  shake(c.state, 3e-3, 0.02, 6);
  c.state.perturber = {true, 0.5, {-1.0, 2.5, 0.2}, {0.9, 0.0, 0.0}};
  ForceOptions options = damped(lively_damping);
  options.min_parallel_items = 1;  // every loop threaded
  ForceField field(c.body, options);
  const int threads = omp_get_max_threads();
  State one = c.state, two = c.state;
  omp_set_num_threads(1);
  Leapfrog(field, c.stage.clock).advance(one, 12);
  omp_set_num_threads(2);
  Leapfrog(field, c.stage.clock).advance(two, 12);
  omp_set_num_threads(threads);
  EXPECT_TRUE(same_state(one, two));
}

TEST(Leapfrog, DetectsABlowUpAndNamesTheStep) {
  Checkpoint c = small_body();
  shake(c.state, 1e-3, 0.0, 5);
  const double bound = derive_quantities(c.body, c.state, 1.0).dt_max;
  ForceField field(c.body);
  Leapfrog leapfrog(field, clock_at(c.state, 30 * bound));
  std::string message;
  std::int64_t failed_step = -1;
  try {
    for (int s = 0; s < 1000; ++s) leapfrog.step(c.state);
  } catch (const SimulationError& err) {
    message = err.what();
    failed_step = c.state.step + 1;  // the state stays at the start of the failing step
  }
  ASSERT_FALSE(message.empty()) << "no blow-up detected";
  EXPECT_NE(message.find("blow-up at step " + std::to_string(failed_step)), std::string::npos) << message;
  EXPECT_NE(message.find("larger than the stability bound"), std::string::npos) << message;
  // The state left behind is a finite step boundary.
  for (double x : c.state.position) ASSERT_TRUE(std::isfinite(x));
}

TEST(Leapfrog, ExtraAccelerationSeesHalfStepPositionsAndEntersTheKick) {
  Checkpoint c = small_body();
  shake(c.state, 3e-3, 0.02, 4);
  ForceField field(c.body);
  const StepClock clock = clock_at(c.state, c.stage.clock.dt);
  const double half = 0.5 * clock.dt;
  const State start = c.state;
  // Cancelling every force leaves free flight: v unchanged, x = (x + v dt/2) + v dt/2, bit for bit.
  Leapfrog leapfrog(field, clock);
  std::vector<double> seen_x, seen_v;
  leapfrog.set_extra_acceleration([&](const double* x, const double* v, std::vector<double>& a) {
    seen_x.assign(x, x + a.size());
    seen_v.assign(v, v + a.size());
    for (double& ak : a) ak = 0;
  });
  leapfrog.step(c.state);
  std::vector<double> expected_half(start.position.size()), expected_end(start.position.size());
  for (std::size_t k = 0; k < expected_half.size(); ++k) {
    expected_half[k] = start.position[k] + half * start.velocity[k];
    expected_end[k] = expected_half[k] + half * start.velocity[k];
  }
  EXPECT_TRUE(same_bits(seen_x, expected_half));
  EXPECT_TRUE(same_bits(seen_v, start.velocity));  // start-of-step velocities
  EXPECT_TRUE(same_bits(c.state.velocity, start.velocity));
  EXPECT_TRUE(same_bits(c.state.position, expected_end));

  // Without an extra acceleration the step is the plain one; an identity changes no bit.
  State plain = start, zero = start;
  Leapfrog(field, clock).advance(plain, 5);
  Leapfrog with_zero(field, clock);
  with_zero.set_extra_acceleration([](const double*, const double*, std::vector<double>& a) {
    for (double& ak : a) ak *= 1.0;
  });
  with_zero.advance(zero, 5);
  EXPECT_TRUE(same_state(plain, zero));
}
