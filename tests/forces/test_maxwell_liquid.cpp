// A Maxwell liquid's pieces (forces/maxwell_liquid.hpp) on bodies small enough to check by hand:
// the support that replaces the springs' resting forces, the creep's rate and its dissipation.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "forces/force_field.hpp"
#include "forces/maxwell_liquid.hpp"
#include "integrate/leapfrog.hpp"

using namespace tidalcrust;

namespace {

/// A tetrahedron of four liquid particles joined by six liquid springs with rest lengths 0.9 of
/// their lengths (all stretched), stiffness 2, no gravity, no pressure layer's tetrahedra beyond
/// the one (bulk modulus 1, rest volume its own: no pressure).
struct Tetra {
  Body body;
  State state;
};

Tetra stretched_tetrahedron() {
  Tetra t;
  t.state.position = {0.0, 0.0, 0.0, 1.0, 0.1, 0.0, 0.2, 1.1, 0.0, 0.3, 0.2, 0.9};
  t.state.velocity.assign(12, 0.0);
  for (int p = 0; p < 4; ++p) {
    t.body.mass.push_back(0.25);
    t.body.species.push_back(static_cast<std::uint8_t>(Species::liquid));
  }
  for (std::int32_t i = 0; i < 4; ++i)
    for (std::int32_t j = i + 1; j < 4; ++j) {
      t.body.springs.push_back({i, j});
      t.body.spring_kind.push_back(static_cast<std::uint8_t>(SpringKind::liquid));
      const Vec3 d = vec3_at(t.state.position, static_cast<std::size_t>(i)) - vec3_at(t.state.position, static_cast<std::size_t>(j));
      t.state.springs.rest_length.push_back(0.9 * d.norm());
      t.state.springs.stiffness.push_back(2.0);
      t.state.springs.failed.push_back(0);
    }
  t.body.liquid.bulk_modulus = 1.0;
  t.body.liquid.tetrahedra = {{0, 1, 2, 3}};
  t.body.liquid.maxwell_time = 0.5;
  t.body.softening = 1e-3;
  t.state.liquid_rest_volume.assign(4, 0.0);
  const double* x = t.state.position.data();
  const double v = std::abs((x[3] * (x[7] * x[11] - x[8] * x[10]) - x[4] * (x[6] * x[11] - x[8] * x[9]) +
                             x[5] * (x[6] * x[10] - x[7] * x[9])) / 6.0);
  t.state.liquid_rest_volume.assign(4, v / 4);  // each corner owns a quarter: P = 0
  return t;
}

ForceOptions no_gravity() {
  ForceOptions o;
  o.self_gravity = false;
  o.damping = 0.0;
  return o;
}

}  // namespace

// The support takes over the springs' resting forces exactly: the same accelerations, springs at
// rest, and a support that sums to zero (no net force) with no net torque (central forces).
TEST(MaxwellLiquid, TheSupportCarriesTheSpringsRestingForcesAndLeavesThemUnstrained) {
  Tetra t = stretched_tetrahedron();
  ForceField forces(t.body, no_gravity());
  Accelerations before, after;
  forces.compute(t.state, before);
  const double energy_before = forces.energies(t.state).potential();
  set_liquid_support(t.body, t.state);
  forces.compute(t.state, after);
  ASSERT_EQ(t.state.liquid_support.size(), 12u);
  double largest = 0;
  for (double a : before.body) largest = std::max(largest, std::abs(a));
  ASSERT_GT(largest, 0.1);  // the springs were strained
  for (std::size_t k = 0; k < 12; ++k) EXPECT_NEAR(after.body[k], before.body[k], 1e-14 * largest) << k;
  for (std::size_t s = 0; s < t.body.spring_count(); ++s) {
    const auto [i, j] = t.body.springs[s];
    const double length = (vec3_at(t.state.position, static_cast<std::size_t>(i)) -
                           vec3_at(t.state.position, static_cast<std::size_t>(j))).norm();
    EXPECT_EQ(t.state.springs.rest_length[s], length) << s;
  }
  Vec3 net = Vec3::Zero(), torque = Vec3::Zero();
  for (std::size_t p = 0; p < 4; ++p) {
    net += vec3_at(t.state.liquid_support, p);
    torque += vec3_at(t.state.position, p).cross(vec3_at(t.state.liquid_support, p));
  }
  EXPECT_LT(net.norm(), 1e-14);
  EXPECT_LT(torque.norm(), 1e-14);
  // The springs' energy is gone, the support's potential (-F.x) is measured from the origin: its
  // gradient is what matters, checked by the conservation test below; here only that it changed.
  EXPECT_NE(forces.energies(t.state).potential(), energy_before);
}

// dL0/dt = (L - L0) / tau_M, explicit: a held stretch decays as (1 - dt/tau_M)^n, and the energy
// the creep reports is exactly the springs' elastic energy it removed.
TEST(MaxwellLiquid, TheCreepRelaxesAHeldStretchAtTheRateOneOverTauAndCountsItsEnergy) {
  Tetra t = stretched_tetrahedron();
  ForceField forces(t.body, no_gravity());
  const std::vector<double> rest0 = t.state.springs.rest_length;
  const double rate = 0.1;
  double dissipated = 0;
  const double elastic0 = forces.energies(t.state).spring;
  for (int n = 0; n < 10; ++n) dissipated += creep_liquid_springs(t.body, t.state, rate);
  const double kept = std::pow(1 - rate, 10);
  for (std::size_t s = 0; s < t.body.spring_count(); ++s) {
    const auto [i, j] = t.body.springs[s];
    const double length = (vec3_at(t.state.position, static_cast<std::size_t>(i)) -
                           vec3_at(t.state.position, static_cast<std::size_t>(j))).norm();
    EXPECT_NEAR(length - t.state.springs.rest_length[s], kept * (length - rest0[s]), 1e-15) << s;
  }
  const double elastic = forces.energies(t.state).spring;
  EXPECT_NEAR(elastic, kept * kept * elastic0, 1e-15);
  EXPECT_NEAR(dissipated, elastic0 - elastic, 1e-15);
  EXPECT_GT(dissipated, 0.0);
}

// In motion (no damping, no gravity): the liquid's energy plus the kinetic energy plus what the
// dashpots took stays the energy at the start, to the leapfrog's O(dt^2); the momentum stays 0.
TEST(MaxwellLiquid, EnergyIsConservedOnceTheCreepsDissipationIsCounted) {
  Tetra t = stretched_tetrahedron();
  ForceField forces(t.body, no_gravity());
  set_liquid_support(t.body, t.state);
  t.state.velocity = {0.3, 0, 0, -0.1, 0.2, 0, 0, -0.2, 0.1, -0.2, 0, -0.1};  // zero total momentum
  auto total = [&] {
    double kinetic = 0;
    for (std::size_t k = 0; k < 12; ++k) kinetic += 0.5 * t.body.mass[k / 3] * t.state.velocity[k] * t.state.velocity[k];
    return kinetic + forces.energies(t.state).potential();
  };
  const double e0 = total();
  Leapfrog leapfrog(forces, StepClock{0.0, 0, 1e-3});
  leapfrog.measure_work(true);
  double dissipated = 0;
  for (int n = 0; n < 2000; ++n) {
    leapfrog.step(t.state);
    dissipated += leapfrog.last_work().damping_removed;
  }
  EXPECT_GT(dissipated, 1e-4);  // the springs were strained by the motion and creep took energy
  EXPECT_NEAR(total() + dissipated, e0, 1e-6 * e0 + 1e-6);
  Vec3 momentum = Vec3::Zero();
  for (std::size_t p = 0; p < 4; ++p) momentum += t.body.mass[p] * vec3_at(t.state.velocity, p);
  EXPECT_LT(momentum.norm(), 1e-13);
}

// A Maxwell time shorter than the step would overshoot: refused when the integrator is made.
TEST(MaxwellLiquid, AMaxwellTimeShorterThanTheStepIsAnInputError) {
  Tetra t = stretched_tetrahedron();
  ForceField forces(t.body, no_gravity());
  t.body.liquid.maxwell_time = 1e-4;
  try {
    Leapfrog leapfrog(forces, StepClock{0.0, 0, 1e-3});
    FAIL() << "accepted tau_M < dt";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ocean.maxwell_time = 0.0001 t_grav is shorter than the time step"),
              std::string::npos)
        << e.what();
  }
}
